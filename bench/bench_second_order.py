"""Second-order meshes (issue "second-order elements"): `hexdom mesh --order 2` against the same part
at order 1, on the 9 CAD parts of ../shared/data/cad, the bundled bracket and (with --corpus) parts of
bench/make_corpus.py's corpus.

Per part: cells; the volume error against the B-rep at order 1 and 2 (the program's report); the
worst scaled Jacobian of the straight cells and of the curved ones (nodes and Gauss points); the
boundary mid-edge nodes and how many were placed on the B-rep, shortened towards their edge or kept
straight (a cell would have dropped below min(0.2, its straight value)); the largest distance of a
placed one from the B-rep (FreeCAD's distToShape, over the diagonal); the seconds of both runs.

Run: /usr/bin/python3 bench/bench_second_order.py [--hexdom build/bin/hexdom] [--data ../shared/data]
     [--corpus DIR --limit N] [--no-distance]
Prints; never asserts.
"""

import argparse
import glob
import json
import os
import re
import subprocess
import sys
import tempfile
import time

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
HEX_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
WEDGE_EDGES = [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)]
WEDGE_FACES = [(0, 1, 2), (3, 5, 4), (0, 3, 4, 1), (1, 4, 5, 2), (2, 5, 3, 0)]
TET_EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
TET_FACES = [(0, 1, 3), (1, 2, 3), (2, 0, 3), (0, 2, 1)]
TABLES = {"hexahedron20": (8, HEX_EDGES, HEX_FACES), "wedge15": (6, WEDGE_EDGES, WEDGE_FACES),
          "tetra10": (4, TET_EDGES, TET_FACES)}


def boundary_mid_nodes(path):
    """(points, mid-edge nodes of the boundary edges) of a second-order .vtu (meshio)."""
    import meshio
    m = meshio.read(path)
    count = {}
    for name, cells in m.cells_dict.items():
        n, _, faces = TABLES[name]
        for cell in cells:
            for f in faces:
                key = tuple(sorted(cell[list(f)]))
                count[key] = count.get(key, 0) + 1
    boundary = {k for k, c in count.items() if c == 1}
    mids = set()
    for name, cells in m.cells_dict.items():
        n, edges, faces = TABLES[name]
        for cell in cells:
            for k, (i, j) in enumerate(edges):
                if any(i in f and j in f and tuple(sorted(cell[list(f)])) in boundary for f in faces):
                    mids.add(int(cell[n + k]))
    return m.points, sorted(mids)


def run(hexdom, part, out, *extra):
    t = time.perf_counter()
    r = subprocess.run([hexdom, "mesh", part, "-o", out, "--allow-inverted", *extra], capture_output=True, text=True)
    return r, time.perf_counter() - t


def volume_error(log):
    m = re.search(r"B-rep volume \S+ \(([-+0-9.]+)%\)", log)
    return float(m.group(1)) if m else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--hexdom", default=os.path.join(REPO, "build", "bin", "hexdom"))
    ap.add_argument("--data", default=os.environ.get("HEXDOM_DATA", os.path.join(REPO, "..", "shared", "data")))
    ap.add_argument("--corpus")
    ap.add_argument("--limit", type=int, default=10)
    ap.add_argument("--no-distance", action="store_true")
    a = ap.parse_args()
    parts = [os.path.join(REPO, "examples", "data", "bracket.step")]
    parts += sorted(glob.glob(os.path.join(a.data, "cad", "*.st*p")))
    if a.corpus:
        found = sorted(glob.glob(os.path.join(a.corpus, "*.step")))
        step = max(1, len(found) // max(1, a.limit))
        parts += found[::step][:a.limit]
    FreeCAD = Part = None
    if not a.no_distance:
        sys.path.append("/usr/lib/freecad-python3/lib")
        import FreeCAD  # noqa: F811
        import Part  # noqa: F811
    print(f"{'part':30s} {'cells':>6s} {'vol1 %':>8s} {'vol2 %':>8s} {'SJ1':>6s} {'SJ2':>6s} {'mids':>6s} "
          f"{'placed':>6s} {'short':>5s} {'str':>4s} {'dist/diag':>9s} {'s1':>5s} {'s2':>5s}")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for part in parts:
            name = os.path.splitext(os.path.basename(part))[0]
            r1, s1 = run(a.hexdom, part, os.path.join(tmp, "a.vtu"), "--report", os.path.join(tmp, "a.json"))
            out2 = os.path.join(tmp, "b.vtu")
            r2, s2 = run(a.hexdom, part, out2, "--order", "2", "--report", os.path.join(tmp, "b.json"))
            if r1.returncode or r2.returncode:
                print(f"{name:30s} failed: {(r2.stderr or r1.stderr).strip().splitlines()[-1:]}")
                continue
            q1 = json.load(open(os.path.join(tmp, "a.json")))
            q2 = json.load(open(os.path.join(tmp, "b.json")))
            so = re.search(r"second order: (\d+) boundary mid-edge nodes.*?; (\d+) placed, (\d+) halfway or less, "
                           r"(\d+) kept straight", r2.stderr)
            mids, placed, short, straight = map(int, so.groups())
            sj1 = min(q1[t]["sj_min"] for t in ("hex", "prism", "tet") if q1[t]["count"])
            sj2 = min(q2[t]["sj_min"] for t in ("hex20", "wedge15", "tet10") if q2[t]["count"])
            cells = sum(q2[t]["count"] for t in ("hex20", "wedge15", "tet10"))
            dist = float("nan")
            if Part is not None:
                shape = Part.read(part).Solids[0]
                faces = Part.Compound(shape.Faces)
                P, ids = boundary_mid_nodes(out2)
                d = np.array([faces.distToShape(Part.Vertex(FreeCAD.Vector(*map(float, P[v]))))[0] for v in ids])
                # The placed ones: all but the shortened and straight, which are the farthest.
                d.sort()
                dist = d[:placed].max() / shape.BoundBox.DiagonalLength if placed else 0.0
            row = (name, cells, volume_error(r1.stderr + r1.stdout), volume_error(r2.stderr + r2.stdout), sj1, sj2,
                   mids, placed, short, straight, dist, s1, s2)
            rows.append(row)
            print(f"{name:30.30s} {cells:6d} {row[2]:+8.3f} {row[3]:+8.3f} {sj1:6.3f} {sj2:6.3f} {mids:6d} {placed:6d} "
                  f"{short:5d} {straight:4d} {dist:9.1e} {s1:5.1f} {s2:5.1f}", flush=True)
    if rows:
        v1 = np.array([abs(r[2]) for r in rows])
        v2 = np.array([abs(r[3]) for r in rows])
        placed = sum(r[7] for r in rows) / max(1, sum(r[6] for r in rows))
        print(f"\n{len(rows)} parts: |volume error| median {np.median(v1):.3f}% -> {np.median(v2):.3f}%, "
              f"max {v1.max():.3f}% -> {v2.max():.3f}%; inverted curved cells: "
              f"{sum(1 for r in rows if r[5] <= 0)} parts; mid-edge nodes placed {placed:.2%}; "
              f"time ratio median {np.median([r[12] / r[11] for r in rows]):.2f}")


if __name__ == "__main__":
    main()
