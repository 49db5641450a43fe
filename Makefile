# HexDom for FreeCAD. `make demo` and `make test` work on a fresh Debian 12 machine: each installs the
# Debian packages it needs (scripts/install-deps.sh, idempotent), builds, then does its job.
PYTHON   ?= /usr/bin/python3
BUILD    ?= build
JOBS     ?= $(shell nproc)
HEXDOM_DATA ?= $(abspath $(CURDIR)/../shared/data)
FREECAD_MOD ?= $(HOME)/.local/share/FreeCAD/Mod/HexDom
export HEXDOM_DATA

.PHONY: all deps build test test-cpp test-python test-freecad demo install package bench clean sanitize fuzz

all: build

deps:
	@bash scripts/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=$(PYTHON) \
	  -DHEXDOM_BUILD_TESTS=ON > $(BUILD).cmake.log 2>&1 || (cat $(BUILD).cmake.log; exit 1)
	@cmake --build $(BUILD) -j $(JOBS)

test-cpp: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

test-python: build
	HEXDOM_BUILD_DIR=$(abspath $(BUILD)) $(PYTHON) -m pytest -q -rs $(wildcard tests/python tests/cli)

# FreeCAD App tests (freecadcmd) and GUI tests (xvfb); see tests/freecad/run.sh.
test-freecad: build
	@if [ -x tests/freecad/run.sh ]; then HEXDOM_BUILD_DIR=$(abspath $(BUILD)) tests/freecad/run.sh; fi

# C++ suites, FreeCAD suites, then the Python suites; pytest's summary line closes the run.
test: test-cpp test-freecad test-python

demo: build
	@bash examples/run_demo.sh $(BUILD)

install: build
	@bash scripts/install-freecad.sh $(BUILD) $(FREECAD_MOD)

# The Debian package build/hexdom_<version>_<arch>.deb (CPack; see CMakeLists.txt); scripts/check-package.sh
# installs it, checks it and removes it again.
package: build
	cd $(BUILD) && cpack -G DEB

bench: build
	HEXDOM_BUILD_DIR=$(abspath $(BUILD)) $(PYTHON) bench/bench_io_quality.py

# The C++ suites with AddressSanitizer and UndefinedBehaviorSanitizer (any report fails a test).
sanitize: deps
	@cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHEXDOM_SANITIZE=ON -DHEXDOM_BUILD_PYTHON=OFF \
	  > build-sanitize.cmake.log 2>&1 || (cat build-sanitize.cmake.log; exit 1)
	@cmake --build build-sanitize -j $(JOBS)
	cd build-sanitize && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitize/lsan.supp ctest --output-on-failure -j $(JOBS)

# The readers' libFuzzer targets (clang, sanitizers built in), a short run each from the committed
# seeds; bench/fuzz_campaign.sh build-fuzz 1000000 is the long campaign.
FUZZ_RUNS ?= 20000
fuzz: deps
	@cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHEXDOM_FUZZ=ON \
	  -DHEXDOM_BUILD_TESTS=OFF -DHEXDOM_BUILD_PYTHON=OFF -DHEXDOM_WITH_CAD=OFF > build-fuzz.cmake.log 2>&1 \
	  || (cat build-fuzz.cmake.log; exit 1)
	@cmake --build build-fuzz -j $(JOBS) --target fuzz_k fuzz_vtk fuzz_vtu fuzz_inp fuzz_msh fuzz_stl fuzz_obj fuzz_corner_points \
	  fuzz_sharp_nodes fuzz_manual_labels fuzz_surface_checks fuzz_structure
	bash bench/fuzz_campaign.sh build-fuzz $(FUZZ_RUNS)

clean:
	rm -rf $(BUILD) $(BUILD).cmake.log
