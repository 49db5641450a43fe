"""Local sizes on CAD faces (issue "element size that FEM users can steer"): `hexdom mesh
--face-size FACE=SIZE` on many parts and sizes, against the same part meshed without it.

Parts: the bundled bracket (its hole, Face10) and, with --corpus, parts of bench/make_corpus.py's
corpus spread over its names, each with one face chosen by a fixed rule (its largest curved face, or
its smallest plane face of at least 1% of the area). Sizes: the default element size H (the box
diagonal / 30) over each of --divisions. Per run: cells (and without the local size), seconds,
inverted cells, worst hex scaled Jacobian (the program's report), and on the chosen face (FreeCAD
finds the boundary quads whose four nodes lie on it): their count, the medians of their mean and
of their longest edge over the size asked (they differ on the flat cells of a thin part's grid),
the share of mean edges within 20% of it; neighbour size ratio (cube roots of volumes of cells
sharing a face) at the 99th percentile and its largest.

Run: /usr/bin/python3 bench/bench_local_size.py [--hexdom build/bin/hexdom] [--corpus DIR]
     [--limit 12] [--divisions 2,3,5] [--method auto|overlay|polycube]
Prints; never asserts.
"""

import argparse
import glob
import json
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


def chosen_face(shape):
    """1-based number of the face the rule picks (see the module doc)."""
    solid = shape.Solids[0]
    area = sum(f.Area for f in solid.Faces)
    curved = [(f.Area, i) for i, f in enumerate(solid.Faces, 1) if f.Surface.__class__.__name__ != "Plane"]
    if curved:
        return max(curved)[1]
    planes = [(f.Area, i) for i, f in enumerate(solid.Faces, 1) if f.Area >= 0.01 * area]
    return min(planes)[1]


def hexes(path):
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    g = r.GetOutput()
    P = vtk_to_numpy(g.GetPoints().GetData())
    cells = [[g.GetCell(c).GetPointId(i) for i in range(g.GetCell(c).GetNumberOfPoints())]
             for c in range(g.GetNumberOfCells())]
    return P, cells


HEX_FACES = ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))


def measure(path, face, size):
    """(quads on the face, median mean edge / size, median longest edge / size, share of mean
    edges within 20%, neighbour ratio 99%, max)."""
    import Part
    P, cells = hexes(path)
    owners = {}
    for c, cell in enumerate(cells):
        if len(cell) != 8:
            continue
        for f in HEX_FACES:
            q = tuple(cell[i] for i in f)
            owners.setdefault(tuple(sorted(q)), []).append((c, q))
    # Cell sizes: cube roots of volumes (hexes by their 6 pyramids to the centroid).
    sizes = np.zeros(len(cells))
    for c, cell in enumerate(cells):
        x = P[cell]
        if len(cell) != 8:
            sizes[c] = np.mean(np.linalg.norm(x - x.mean(axis=0), axis=1))
            continue
        m, v = x.mean(axis=0), 0.0
        for f in HEX_FACES:
            a, b, cc, d = (x[i] for i in f)
            for t in ((a, b, cc), (a, cc, d)):
                v += abs(np.dot(t[0] - m, np.cross(t[1] - m, t[2] - m))) / 6
        sizes[c] = np.cbrt(v)
    ratios = [max(sizes[o[0][0]], sizes[o[1][0]]) / min(sizes[o[0][0]], sizes[o[1][0]])
              for o in owners.values() if len(o) == 2]
    bb = face.BoundBox
    tol = 1e-6 * max(1.0, bb.DiagonalLength)
    on = {}
    quads = []
    for o in owners.values():
        if len(o) != 1:
            continue
        q = o[0][1]
        ok = True
        for v in q:
            if v not in on:
                x = P[v]
                inside = (bb.XMin - tol <= x[0] <= bb.XMax + tol and bb.YMin - tol <= x[1] <= bb.YMax + tol
                          and bb.ZMin - tol <= x[2] <= bb.ZMax + tol)
                on[v] = inside and face.distToShape(Part.Vertex(*map(float, x)))[0] < 1e-6
            ok = ok and on[v]
            if not ok:
                break
        if ok:
            x = P[list(q)]
            e = np.linalg.norm(x - np.roll(x, 1, axis=0), axis=1)
            quads.append((np.mean(e), np.max(e)))
    quads = np.array(quads).reshape(-1, 2) / size
    if len(quads) == 0:
        return 0, float("nan"), float("nan"), float("nan"), np.percentile(ratios, 99), max(ratios)
    return (len(quads), float(np.median(quads[:, 0])), float(np.median(quads[:, 1])),
            float(np.mean(np.abs(quads[:, 0] - 1) <= 0.2)), float(np.percentile(ratios, 99)), float(max(ratios)))


def counts(report):
    """(cells, inverted cells) of the program's JSON quality report."""
    kinds = [report[t] for t in ("hex", "prism", "tet")]
    return sum(int(k["count"]) for k in kinds), sum(int(k["inverted"]) for k in kinds)


def run(hexdom, part, out, extra):
    report = out + ".json"
    t0 = time.time()
    p = subprocess.run([hexdom, "mesh", part, "-o", out, "--report", report, "--allow-inverted"] + extra,
                       capture_output=True, text=True)
    seconds = time.time() - t0
    if p.returncode != 0 or not os.path.exists(report):
        return None, seconds, p.stderr.strip().splitlines()[-1:] or [""]
    return json.load(open(report)), seconds, None


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--hexdom", default=os.path.join(REPO, "build", "bin", "hexdom"))
    ap.add_argument("--corpus", help="folder of make_corpus.py's STEP files")
    ap.add_argument("--limit", type=int, default=12)
    ap.add_argument("--divisions", default="2,3,5")
    ap.add_argument("--method", default="auto", choices=("auto", "overlay", "polycube"),
                    help="the path asked for with the local size (auto: the overlay's, which meets them); the "
                         "plain mesh is that path's without it (auto: the overlay's)")
    a = ap.parse_args(argv)
    import FreeCAD  # noqa: F401
    import Part
    parts = [os.path.join(REPO, "examples", "data", "bracket.step")]
    if a.corpus:
        found = sorted(glob.glob(os.path.join(a.corpus, "*.step")))
        step = max(1, len(found) // max(1, a.limit))
        parts += found[::step][:a.limit]
    divisions = [float(d) for d in a.divisions.split(",")]
    work = tempfile.mkdtemp(prefix="hexdom-local-size-")
    print("%-26s %5s %7s %8s %7s %6s %4s %6s %6s %6s %6s %6s %5s %5s" % (
        "part", "face", "size", "cells", "plain", "sec", "inv", "SJ", "quads", "med", "medmax", "in20%", "r99",
        "rmax"))
    rows = []
    for part in parts:
        name = os.path.splitext(os.path.basename(part))[0]
        shape = Part.read(part)
        face_no = 10 if name == "bracket" else chosen_face(shape)
        face = shape.Solids[0].Faces[face_no - 1]
        H = shape.Solids[0].BoundBox.DiagonalLength / 30
        plain_method = "overlay" if a.method == "auto" else a.method
        base, _, err = run(a.hexdom, part, os.path.join(work, name + "_plain.vtu"), ["--method", plain_method])
        plain = counts(base)[0] if base else 0
        for d in divisions:
            size = H / d
            out = os.path.join(work, "%s_%g.vtu" % (name, d))
            rep, seconds, err = run(a.hexdom, part, out, ["--face-size", "%d=%.6g" % (face_no, size), "--method", a.method])
            if rep is None:
                print("%-26s %5d %7.3g  failed: %s" % (name, face_no, size, err[0][:80]))
                rows.append(None)
                continue
            cells, inv = counts(rep)
            sj = rep["hex"]["sj_min"] if rep["hex"]["count"] else float("nan")
            n, med, medmax, share, r99, rmax = measure(out, face, size)
            rows.append((inv, med, share, r99, medmax))
            print("%-26s %5d %7.3g %8d %7s %6.2f %4d %6.3f %6d %6.2f %6.2f %6.2f %5.2f %5.2f" % (
                name, face_no, size, cells, plain or "-", seconds, inv, sj, n, med, medmax, share, r99, rmax))
            sys.stdout.flush()
    done = [r for r in rows if r is not None]
    print("\nruns %d, failed %d; no inverted cell %d; face median within 20%%: %d by the mean edge, %d by the "
          "longest; neighbour ratio 99%% <= 2: %d" % (
              len(rows), len(rows) - len(done), sum(r[0] == 0 for r in done),
              sum(abs(r[1] - 1) <= 0.2 for r in done), sum(abs(r[4] - 1) <= 0.2 for r in done),
              sum(r[3] <= 2 for r in done)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
