"""Generation time, element throughput, stage times and peak memory for rockerarm at levels 2, 3
and 4 (issue 3 targets: level 2 well under 1 s, >= 1M cells/s at level 4, aim 1.5M; memory linear
in the cell count).

Run: HEXDOM_BUILD_DIR=build /usr/bin/python3 bench/bench_generate.py [--runs N] [--threads T] [levels...]
Each level runs in its own process so that its peak memory is its own. Per level: the median (and
range) over N runs (default 5) of the wall-clock time of the whole generate call through the
Python API (the default run: patch maps, placement, relaxation and untangling), the throughput
from the median, the CPU time, the peak RSS, and the median per-stage times that `hexdom generate`
logs (its own runs, same options). Prints, never asserts: the machine may be shared.
"""

import os
import re
import resource
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.environ.get("HEXDOM_DATA", os.path.join(ROOT, "..", "shared", "data"))
BUILD = os.environ.get("HEXDOM_BUILD_DIR", os.path.join(ROOT, "build"))
MODEL = os.path.join(DATA, "hexdom", "rockerarm")
PATCHES = os.path.join(MODEL, "rockerarm_indexPatch_hexdom.k")
STRUCTURE = os.path.join(MODEL, "rockerarm_polycube_withtet.k")


def stage_times(level, runs, threads):
    """Median per-stage times (ms) over `runs` runs of the CLI, from its 'stage times' log line."""
    rows = []
    out = os.path.join("/tmp", f"bench_generate_{os.getpid()}.vtk")
    for _ in range(runs):
        r = subprocess.run([os.path.join(BUILD, "bin", "hexdom"), "generate", "-i", PATCHES, "-p", STRUCTURE, "-s",
                            str(level), "-o", out, "--threads", str(threads)], capture_output=True, text=True, check=True)
        line = next(l for l in r.stderr.splitlines() if "stage times" in l)
        rows.append({k.strip(): float(v) for k, v in re.findall(r"([a-z ]+?) ([0-9.]+)", line.split(":", 2)[2])})
    if os.path.exists(out):
        os.remove(out)
    return {k: statistics.median(r[k] for r in rows) for k in rows[0]}


def one(level, runs, threads):
    sys.path.insert(0, ROOT)
    import HexDomWorkbench as hexdom
    surface = hexdom.read_surface(PATCHES)
    structure = hexdom.read_mesh(STRUCTURE)
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    wall, cpu = [], []
    for _ in range(runs):
        t0, c0 = time.perf_counter(), time.process_time()
        mesh = hexdom.generate(surface, structure, level=level, threads=threads)
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    q = hexdom.quality_report(mesh)
    n = len(mesh.types)
    w, c = statistics.median(wall), statistics.median(cpu)
    print(f"level {level}: {n:8d} cells, median of {runs}: {w * 1000:7.1f} ms = {n / w / 1e6:5.2f} M cells/s "
          f"(range {min(wall) * 1000:.1f}..{max(wall) * 1000:.1f} ms; CPU {c * 1000:.1f} ms); "
          f"peak RSS {peak / 1024:6.0f} MB (+{(peak - base) / 1024:.0f} MB = {(peak - base) * 1024 / n:.0f} B/cell); "
          f"inverted {q['hex']['inverted']}/{q['prism']['inverted']}/{q['tet']['inverted']} (hex/prism/tet)")
    st = stage_times(level, runs, threads)
    print("         stages (ms, median): " + ", ".join(f"{k} {v:.1f}" for k, v in st.items()) +
          f"; sum {sum(st.values()):.1f}", flush=True)


if __name__ == "__main__":
    args = sys.argv[1:]
    if args[:1] == ["--one"]:
        one(int(args[1]), int(args[2]), int(args[3]))
        sys.exit(0)
    runs, threads = 5, 0
    while args[:1] in (["--runs"], ["--threads"]):
        if args[0] == "--runs":
            runs = int(args[1])
        else:
            threads = int(args[1])
        args = args[2:]
    if not os.path.isdir(MODEL):
        print(f"skipped: shared data missing: {MODEL}")
        sys.exit(0)
    print(f"threads {threads or os.cpu_count()} (0: one per hardware thread), load average {os.getloadavg()[0]:.2f}")
    for level in [int(a) for a in args] or [2, 3, 4]:
        subprocess.run([sys.executable, __file__, "--one", str(level), str(runs), str(threads)], check=True)
