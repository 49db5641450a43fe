"""Improvement time for rockerarm at levels 2 and 3 (target: level 2 <= 1 s), with the quality
before and after. Run: HEXDOM_BUILD_DIR=build /usr/bin/python3 bench/bench_improve.py
Prints, never asserts."""

import os
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.environ.get("HEXDOM_DATA", os.path.join(ROOT, "..", "shared", "data"))
sys.path.insert(0, ROOT)


def main():
    d = os.path.join(DATA, "hexdom", "rockerarm")
    if not os.path.isdir(d):
        print(f"skipped: shared data missing: {d}")
        return
    import HexDomWorkbench as hexdom
    surface = hexdom.read_surface(os.path.join(d, "rockerarm_indexPatch_hexdom.k"))
    structure = hexdom.read_mesh(os.path.join(d, "rockerarm_polycube_withtet.k"))
    for level in (2, 3):
        mesh = hexdom.generate(surface, structure, level=level)
        q0 = hexdom.quality_report(mesh)
        t0, c0 = time.perf_counter(), time.process_time()
        better = hexdom.improve(mesh, surface=surface)
        dt, cpu = time.perf_counter() - t0, time.process_time() - c0
        q1 = hexdom.quality_report(better)
        inv = lambda q: q["hex"]["inverted"] + q["prism"]["inverted"] + q["tet"]["inverted"]  # noqa: E731
        print(f"level {level}: {len(mesh.types)} -> {len(better.types)} cells in {dt:6.2f} s "
              f"({cpu:.2f} s CPU; improvement is single-threaded, so wall > CPU means a busy machine); "
              f"worst hex SJ {q0['hex']['sj_min']:.3f} -> {q1['hex']['sj_min']:.3f}, "
              f"mean {q0['hex']['sj_mean']:.3f} -> {q1['hex']['sj_mean']:.3f}, inverted {inv(q0)} -> {inv(q1)}")


if __name__ == "__main__":
    main()
