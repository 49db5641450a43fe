"""Generation time, element throughput and peak memory for rockerarm at levels 2, 3 and 4, with the
plain relaxation (the default) and with untangle=True.

Run: HEXDOM_BUILD_DIR=build /usr/bin/python3 bench/bench_generate.py [levels...]
Each level runs in its own process so that its peak memory is its own. Prints wall-clock and CPU
time (the machine may be shared: CPU time is the steadier figure), never asserts.
"""

import os
import resource
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.environ.get("HEXDOM_DATA", os.path.join(ROOT, "..", "shared", "data"))


def one(level, untangle):
    sys.path.insert(0, ROOT)
    import HexDomWorkbench as hexdom
    d = os.path.join(DATA, "hexdom", "rockerarm")
    surface = hexdom.read_surface(os.path.join(d, "rockerarm_indexPatch_hexdom.k"))
    structure = hexdom.read_mesh(os.path.join(d, "rockerarm_polycube_withtet.k"))
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    t0, c0 = time.perf_counter(), time.process_time()
    mesh = hexdom.generate(surface, structure, level=level, untangle=untangle)
    dt, dc = time.perf_counter() - t0, time.process_time() - c0
    t1 = time.perf_counter()
    q = hexdom.quality_report(mesh)
    dq = time.perf_counter() - t1
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    n = len(mesh.types)
    print(f"level {level}{' untangle' if untangle else '         '}: {n:8d} cells in {dt * 1000:8.1f} ms = {n / dt / 1e6:5.2f} M cells/s "
          f"(CPU {dc * 1000:7.1f} ms = {n / dc / 1e6:5.2f} M cells/s); "
          f"quality {dq * 1000:6.1f} ms; peak RSS {peak / 1024:6.0f} MB (+{(peak - base) / 1024:.0f} MB); "
          f"inverted {q['hex']['inverted']}/{q['prism']['inverted']}/{q['tet']['inverted']} (hex/prism/tet)")


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "--one":
        one(int(sys.argv[2]), sys.argv[3] == "untangle")
        sys.exit(0)
    if not os.path.isdir(os.path.join(DATA, "hexdom", "rockerarm")):
        print(f"skipped: shared data missing: {os.path.join(DATA, 'hexdom', 'rockerarm')}")
        sys.exit(0)
    for level in [int(a) for a in sys.argv[1:]] or [2, 3, 4]:
        for mode in ("plain", "untangle"):
            subprocess.run([sys.executable, __file__, "--one", str(level), mode], check=True)
