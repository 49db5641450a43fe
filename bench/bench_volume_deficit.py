"""Where the generated mesh loses volume against the surface it was made from (issue 3).

Run: HEXDOM_BUILD_DIR=build /usr/bin/python3 bench/bench_volume_deficit.py [model...]
For each model and level it prints the volume the surface encloses, the mesh volume (VTK's cell
sizes), the volume of the mesh's boundary polyhedron (its boundary quads and triangles, split into
triangles), the deficit and its ratio to the next level's (about 4 for a chordal O(h^2) error).
Then, at level 2, where the deficit sits: each input triangle's signed distance to the boundary
polyhedron (VTK's vtkImplicitPolyDataDistance) times its area, summed per patch, with the patches'
share of the total and the spread of boundary-face areas on them (max / min: a harmonic map that
concentrates or starves regions would show a large spread). Prints, never asserts.
"""

import os
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.environ.get("HEXDOM_DATA", os.path.join(ROOT, "..", "shared", "data"))
sys.path.insert(0, os.path.join(ROOT, "tests", "python"))
import hexdom_test_support as support  # noqa: E402

MODELS = support.PAPER_MODELS
FACES = {  # VTK local faces, outward
    12: [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)],
    13: [(0, 1, 2), (3, 5, 4), (0, 3, 4, 1), (1, 4, 5, 2), (2, 5, 3, 0)],
    10: [(0, 1, 3), (1, 2, 3), (2, 0, 3), (0, 2, 1)],
}


def enclosed(V, tris):
    a, b, c = V[tris[:, 0]], V[tris[:, 1]], V[tris[:, 2]]
    return np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0


def boundary_faces(mesh):
    """Boundary faces of a mesh (hexdom.Mesh), outward, as lists of node ids."""
    seen = {}
    for cell, t in zip(np.asarray(mesh.cells), np.asarray(mesh.types)):
        for f in FACES[int(t)] if int(t) in FACES else []:
            ids = tuple(int(cell[i]) for i in f)
            key = tuple(sorted(ids))
            seen[key] = None if key in seen else ids
    return [f for f in seen.values() if f is not None]


def polydata(V, tris):
    pd = vtk.vtkPolyData()
    pts = vtk.vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(V, dtype=float), deep=True))
    pd.SetPoints(pts)
    conn = np.hstack([np.full((len(tris), 1), 3), tris]).astype(np.int64).ravel()
    cells = vtk.vtkCellArray()
    cells.SetCells(len(tris), numpy_to_vtkIdTypeArray(conn, deep=True))
    pd.SetPolys(cells)
    return pd


def main(models):
    sys.path.insert(0, ROOT)
    import HexDomWorkbench as hexdom
    for model in models:
        pf, sf = MODELS[model]
        d = os.path.join(DATA, "hexdom", model)
        if not os.path.exists(os.path.join(d, pf)):
            print(f"{model}: skipped, shared data missing")
            continue
        S = hexdom.read_surface(os.path.join(d, pf))
        T = hexdom.read_mesh(os.path.join(d, sf))
        SV, SF, SP = np.asarray(S.V), np.asarray(S.F), np.asarray(S.patch)
        v_surf = enclosed(SV, SF)
        deficits = {}
        for level in (2, 3, 4):
            M = hexdom.generate(S, T, level=level)
            X = np.asarray(M.V)
            bf = boundary_faces(M)
            tris = np.array([[f[0], f[k], f[k + 1]] for f in bf for k in range(1, len(f) - 1)])
            v_poly = enclosed(X, tris)
            v_mesh = float(np.sum(np.asarray(hexdom.cell_metrics(M)[2])))
            deficits[level] = (v_mesh - v_surf) / v_surf
            print(f"{model:14s} level {level}: surface {v_surf:.6g}  mesh {v_mesh:.6g}  boundary polyhedron "
                  f"{v_poly:.6g}  deficit {100 * deficits[level]:+.2f}%  (mesh - polyhedron {100 * (v_mesh - v_poly) / v_surf:+.3f}%)")
            if level != 2:
                continue
            # Per input triangle: signed distance of its centroid to the boundary polyhedron
            # (positive outside it: volume the mesh misses) times its area.
            dist = vtk.vtkImplicitPolyDataDistance()
            dist.SetInput(polydata(X, tris))
            cen = SV[SF].mean(axis=1)
            area = 0.5 * np.linalg.norm(np.cross(SV[SF[:, 1]] - SV[SF[:, 0]], SV[SF[:, 2]] - SV[SF[:, 0]]), axis=1)
            sd = np.array([dist.EvaluateFunction(p) for p in cen])
            lost = -sd * area  # vtk: negative inside; a surface point outside the mesh is volume lost
            total = lost.sum()
            print(f"{'':14s}   sum of distance x area {100 * -total / v_surf:+.2f}% of the volume "
                  f"(the deficit above, estimated from the surface side)")
            # Boundary-face areas per patch (faces grouped by nearest patch triangle label).
            fa = [(0.5 * np.linalg.norm(np.cross(X[f[1]] - X[f[0]], X[f[2]] - X[f[0]])) +
                   (0.5 * np.linalg.norm(np.cross(X[f[2]] - X[f[0]], X[f[3]] - X[f[0]])) if len(f) == 4 else 0.0),
                   X[list(f)].mean(axis=0)) for f in bf]
            loc = vtk.vtkCellLocator()
            spd = polydata(SV, SF)
            loc.SetDataSet(spd)
            loc.BuildLocator()
            closest, cid, sub, d2 = [0.0] * 3, vtk.reference(0), vtk.reference(0), vtk.reference(0.0)
            by_patch = {}
            for a, c in fa:
                loc.FindClosestPoint(c, closest, cid, sub, d2)
                by_patch.setdefault(int(SP[int(cid)]), []).append(a)
            rows = []
            for pid in np.unique(SP):
                sel = SP == pid
                areas = by_patch.get(int(pid), [1.0])
                rows.append((lost[sel].sum() / total, int(pid), area[sel].sum(), max(areas) / min(areas), len(areas)))
            rows.sort(reverse=True)
            spreads = np.array([r[3] for r in rows])
            top = rows[:5]
            print(f"{'':14s}   boundary-face area spread per patch (max/min): median {np.median(spreads):.2f}, "
                  f"90th percentile {np.percentile(spreads, 90):.2f}")
            print(f"{'':14s}   largest shares: " + ", ".join(
                f"patch {pid} {100 * share:.0f}% (spread {spread:.1f})" for share, pid, _, spread, _ in top))
        print(f"{'':14s} deficit ratios level 2/3 {deficits[2] / deficits[3]:.2f}, 3/4 {deficits[3] / deficits[4]:.2f} "
              f"(4 = chordal, O(h^2))")


if __name__ == "__main__":
    main(sys.argv[1:] or ["fertility", "ant", "rockerarm"])
