"""Element size (issue "element size that FEM users can steer"): thin parts and cells against size.

1. Thin parts made here with FreeCAD (a 100 x 100 x 0.5 plate, a 1000 x 1 x 1 rod, a 200 x 100 x 1
   sheet with holes, a washer, a slotted strip, a round rod, an L of two sheets), meshed by
   `hexdom mesh` at the default size: cells, largest edge ratio, worst scaled Jacobian, seconds, and
   the fewest cells across the part's thinnest bounding-box axis (distinct node levels - 1).
   Targets: >= 2 cells across, edge ratio <= 5 on the plate and the rod.
2. One part (the bundled bracket, or --part) at sizes diagonal / N: cells, seconds, peak memory of
   the process (/usr/bin/time), and the exponent of cells against size fitted over the sizes (about
   -3 expected).

Run: /usr/bin/python3 bench/bench_sizing.py [--hexdom build/bin/hexdom] [--part P.step]
     [--divisions 15,30,60,90] [--skip-thin]
Prints; never asserts.
"""

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
for p in ("/usr/lib/freecad-python3/lib",):
    if p not in sys.path:
        sys.path.append(p)


def make_thin_parts(folder):
    import FreeCAD  # noqa: F401
    import Part
    from FreeCAD import Vector as V

    def hole(r, x, y):
        return Part.makeCylinder(r, 3, V(x, y, -1))
    parts = {"plate": Part.makeBox(100, 100, 0.5), "rod": Part.makeBox(1000, 1, 1)}
    s = Part.makeBox(200, 100, 1)
    for x, y, r in ((30, 30, 8), (100, 50, 15), (170, 70, 6)):
        s = s.cut(hole(r, x, y))
    parts["sheet_holes"] = s
    parts["washer"] = Part.makeCylinder(40, 0.8).cut(Part.makeCylinder(12, 0.8))
    parts["strip_slot"] = Part.makeBox(300, 20, 1.2).cut(Part.makeBox(60, 6, 3, V(120, 7, -1)))
    parts["round_rod"] = Part.makeCylinder(2, 400)
    parts["sheet_l"] = Part.makeBox(100, 50, 1).fuse(Part.makeBox(1, 50, 60)).removeSplitter()
    paths = {}
    for name, shape in parts.items():
        paths[name] = os.path.join(folder, name + ".step")
        shape.exportStep(paths[name])
    return paths


def run(hexdom, part, out, *extra):
    """(seconds, peak resident MB or None, stderr) of one `hexdom mesh` process. The peak comes from
    /usr/bin/time (package time): a child's own rusage would count this Python process's memory,
    which the child inherits until it execs."""
    mem = out + ".mem"
    timer = ["/usr/bin/time", "-f", "%M", "-o", mem] if os.path.exists("/usr/bin/time") else []
    t0 = time.perf_counter()
    r = subprocess.run(timer + [hexdom, "mesh", part, "-o", out, "--allow-inverted", *extra],
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    dt = time.perf_counter() - t0
    if r.returncode != 0:
        raise RuntimeError(r.stderr.strip().splitlines()[-1] if r.stderr.strip() else f"exit {r.returncode}")
    mb = None
    if timer:
        with open(mem) as f:
            mb = float(f.read().split()[-1]) / 1024.0
    return dt, mb, r.stderr


def fmt_mb(mb):
    return f"{mb:6.0f}" if mb is not None else f"{'-':>6s}"


def measure(path):
    """(cells, largest edge ratio, worst SJ, cells across) of a .vtu, by VTK (Verdict for the
    cells). Across: the cells a line along the thinnest bounding-box axis crosses, through the point
    at 0.3237 of the box along the other two (off the middle, where a washer has its hole)."""
    sys.path.insert(0, os.path.join(REPO, "tests", "python"))
    import vtk
    import hexdom_oracles as oracles
    g = oracles.read_vtu(path)
    sj, er = oracles.verdict_metrics(g)
    P, _, _ = oracles.grid_arrays(g)
    lo, hi = P.min(axis=0), P.max(axis=0)
    a = int(np.argmin(hi - lo))
    p0 = lo + 0.3237 * (hi - lo)
    p1 = p0.copy()
    p0[a], p1[a] = lo[a] - 1e-3 * (hi[a] - lo[a]), hi[a] + 1e-3 * (hi[a] - lo[a])
    loc = vtk.vtkCellLocator()
    loc.SetDataSet(g)
    loc.BuildLocator()
    ids = vtk.vtkIdList()
    loc.FindCellsAlongLine(list(p0), list(p1), 1e-9, ids)
    return g.GetNumberOfCells(), float(np.nanmax(er)), float(np.nanmin(sj)), ids.GetNumberOfIds()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--hexdom", default=os.path.join(REPO, "build", "bin", "hexdom"))
    ap.add_argument("--part", default=os.path.join(REPO, "examples", "data", "bracket.step"))
    ap.add_argument("--divisions", default="15,30,60,90", help="sizes: bounding-box diagonal / N")
    ap.add_argument("--skip-thin", action="store_true")
    args = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="hexdom-bench-sizing-")
    if not args.skip_thin:
        print(f"{'thin part':14s} {'path':9s} {'cells':>7s} {'max ER':>7s} {'worst SJ':>8s} {'across':>6s} {'s':>6s} "
              f"{'MB':>6s}")
        for name, path in make_thin_parts(tmp).items():
            out = os.path.join(tmp, name + ".vtu")
            try:
                dt, mb, err = run(args.hexdom, path, out)
            except RuntimeError as e:
                print(f"{name:14s} failed: {e}")
                continue
            kept = next((ln.split("kept: ")[1].split(" ")[0] for ln in err.splitlines() if "kept: " in ln), "?")
            cells, er, sj, across = measure(out)
            print(f"{name:14s} {kept:9s} {cells:7d} {er:7.2f} {sj:8.3f} {across:6d} {dt:6.2f} {fmt_mb(mb)}", flush=True)
    sys.path.insert(0, os.path.join(os.environ.get("HEXDOM_BUILD_DIR", os.path.join(REPO, "build")), "python"))
    import _hexdom
    V = np.asarray(_hexdom.tessellate_file(args.part)[0])
    diag = float(np.linalg.norm(V.max(axis=0) - V.min(axis=0)))
    print(f"\n{os.path.basename(args.part)} (diagonal {diag:.4g}): cells and time against size")
    print(f"{'size':>9s} {'cells':>8s} {'s':>7s} {'MB':>6s} {'cells/s':>9s}")
    rows = []
    for n in (int(x) for x in args.divisions.split(",")):
        size = diag / n
        out = os.path.join(tmp, f"sweep_{n}.vtu")
        try:
            dt, mb, _ = run(args.hexdom, args.part, out, "--size", repr(size))
        except RuntimeError as e:
            print(f"{size:9.4g} failed: {e}")
            continue
        cells = measure(out)[0]
        rows.append((size, cells, dt, mb))
        print(f"{size:9.4g} {cells:8d} {dt:7.2f} {fmt_mb(mb)} {cells / dt:9.0f}", flush=True)
    if len(rows) >= 2:
        x = np.log([r[0] for r in rows])
        slope = np.polyfit(x, np.log([r[1] for r in rows]), 1)[0]
        print(f"cells ~ size^{slope:.2f} (fitted over the sizes)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
