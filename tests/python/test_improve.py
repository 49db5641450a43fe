"""hexdom improve on the paper models: generated level-2 meshes and the original program's raw
outputs. Quality is judged by VTK's Verdict (vtkMeshQuality), not by our own metrics."""

import os
import subprocess

import numpy as np
import pytest
import vtk
from vtk.util.numpy_support import vtk_to_numpy

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.environ.get("HEXDOM_DATA", os.path.join(ROOT, "..", "shared", "data"))
BUILD = os.environ.get("HEXDOM_BUILD_DIR", os.path.join(ROOT, "build"))
HEXDOM = os.path.join(BUILD, "bin", "hexdom")

# model: patch file, structure, the paper's Table 1 worst hex SJ
MODELS = {
    "rockerarm": ("rockerarm_indexPatch_hexdom.k", "rockerarm_polycube_withtet.k", 0.20),
    "mount1": ("mount1_patch_hexdom.k", "mount1_polycube_hexdom_withtet.k", 0.20),
    "hepta": ("hepta_patch_hexdom.k", "hepta_polycube_withtet.k", 0.50),
    "fertility": ("fertility_indexPatch_hexdom.k", "fertility_polycube_hexdom_withtet.k", 0.20),
    "ant": ("ant_indexPatch_hexdom.k", "ant_polycube_withtet.k", 0.21),
    "mountwithhole": ("mountwithhole_patch_hexdom.k", "mountwithhole_polycube_withtet.k", 0.0),
}
RAW = ["rockerarm/rockerarm3_hex.vtk", "mount1/mount_1_hex.vtk", "hepta/hepta_hex.vtk",
       "fertility/fertility3_hex.vtk", "ant/ant_hex.vtk", "mountwithhole/mountwithhole_hex.vtk"]


def _need(path):
    if not os.path.exists(path):
        pytest.skip(f"shared data missing: {path}")
    return path


def _run(*args):
    r = subprocess.run([HEXDOM, *args], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r


def _grid(path):
    r = vtk.vtkUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def _verdict_sj(grid):
    """Scaled Jacobian per cell by Verdict (wedges in Verdict's node order)."""
    out = np.empty(grid.GetNumberOfCells())
    wedge = vtk.vtkWedge()
    for c in range(grid.GetNumberOfCells()):
        cell = grid.GetCell(c)
        t = cell.GetCellType()
        if t == 12:
            out[c] = vtk.vtkMeshQuality.HexScaledJacobian(cell)
        elif t == 10:
            out[c] = vtk.vtkMeshQuality.TetScaledJacobian(cell)
        else:  # no wedge function in VTK 9.1's Python API: the corner formula on Verdict's order
            p = np.array([cell.GetPoints().GetPoint(i) for i in (1, 0, 2, 4, 3, 5)])
            corners = [(0, 1, 3, 2), (1, 2, 4, 0), (2, 0, 5, 1), (3, 0, 4, 5), (4, 1, 5, 3), (5, 3, 4, 2)]
            vals = []
            for o, a, b, c3 in corners:
                v1, v2, v3 = p[a] - p[o], p[b] - p[o], p[c3] - p[o]
                vals.append(np.dot(v2, np.cross(v1, v3)) / np.sqrt(v1 @ v1 * (v2 @ v2) * (v3 @ v3)))
            out[c] = min(vals) * 2 / np.sqrt(3)
    del wedge
    return out, vtk_to_numpy(grid.GetCellTypesArray())


def _volume(grid):
    f = vtk.vtkCellSizeFilter()
    f.SetInputData(grid)
    f.Update()
    return vtk_to_numpy(f.GetOutput().GetCellData().GetArray("Volume")).sum()


@pytest.fixture(scope="module")
def improved(tmp_path_factory):
    """Generates and improves every model once; returns {model: (raw path, improved path, patches)}."""
    out = {}
    d = tmp_path_factory.mktemp("improve")
    for model, (patch, structure, _) in MODELS.items():
        p = os.path.join(DATA, "hexdom", model, patch)
        s = os.path.join(DATA, "hexdom", model, structure)
        if not (os.path.exists(p) and os.path.exists(s)):
            continue
        raw, imp = str(d / f"{model}.vtk"), str(d / f"{model}_improved.vtk")
        _run("generate", "-i", p, "-p", s, "-s", "2", "-o", raw)
        _run("improve", "-i", raw, "-o", imp, "--surface", p)
        out[model] = (raw, imp, p)
    return out


_MEAN_DEFECT = pytest.mark.xfail(strict=False, reason="issue 4: mean hex SJ after improvement is "
                                 "0.83 (rockerarm), 0.76 (fertility), 0.81 (ant), below the 0.85 "
                                 "target: thin pillow cells at sharp corners pull the mean down")


@pytest.mark.parametrize("model", list(MODELS))
def test_generated_mesh_improves_to_valid_and_paper_quality(model, improved):
    if model not in improved:
        pytest.skip(f"shared data missing for {model} under {DATA}/hexdom")
    raw, imp, patches = improved[model]
    sj, types = _verdict_sj(_grid(imp))
    assert np.all(sj > 0), f"{np.sum(sj <= 0)} inverted cells"
    assert sj[types == 12].min() >= MODELS[model][2]
    # Volume changes by at most 1%.
    v0, v1 = _volume(_grid(raw)), _volume(_grid(imp))
    assert abs(v1 - v0) <= 0.01 * abs(v0), (v0, v1)


@pytest.mark.parametrize("model", ["rockerarm", "mount1", "fertility", "ant", "mountwithhole"])
def test_worst_hex_at_least_point_three(model, improved):
    if model not in improved:
        pytest.skip(f"shared data missing for {model}")
    sj, types = _verdict_sj(_grid(improved[model][1]))
    assert sj[types == 12].min() >= 0.3


@pytest.mark.parametrize("model", [pytest.param(m, marks=_MEAN_DEFECT) if m in ("rockerarm", "fertility", "ant")
                                   else m for m in ["rockerarm", "mount1", "hepta", "fertility", "ant"]])
def test_mean_hex_sj(model, improved):
    if model not in improved:
        pytest.skip(f"shared data missing for {model}")
    sj, types = _verdict_sj(_grid(improved[model][1]))
    assert sj[types == 12].mean() >= 0.85


def test_boundary_nodes_stay_on_the_surface(improved):
    if "rockerarm" not in improved:
        pytest.skip("shared data missing for rockerarm")
    _, imp, patches = improved["rockerarm"]
    grid = _grid(imp)
    # Boundary faces by VTK's own geometry filter; the surface parsed here.
    surf = vtk.vtkDataSetSurfaceFilter()
    surf.SetInputData(grid)
    surf.Update()
    X = vtk_to_numpy(surf.GetOutput().GetPoints().GetData()).astype(float)
    nodes, tris, sec = {}, [], None
    for line in open(patches):
        if line.startswith("*"):
            sec = line.strip()
            continue
        f = line.replace(",", " ").split()
        if sec == "*NODE" and len(f) >= 4 and not line.startswith("$"):
            nodes[int(f[0])] = [float(x) for x in f[1:4]]
        elif sec == "*ELEMENT_SHELL" and len(f) >= 5:
            tris.append([int(x) for x in f[2:5]])
    ids = {n: i for i, n in enumerate(nodes)}
    pts = vtk.vtkPoints()
    pts.SetDataTypeToDouble()
    for p in nodes.values():
        pts.InsertNextPoint(*p)
    polys = vtk.vtkCellArray()
    for t in tris:
        polys.InsertNextCell(3, [ids[n] for n in t])
    pd = vtk.vtkPolyData()
    pd.SetPoints(pts)
    pd.SetPolys(polys)
    loc = vtk.vtkCellLocator()
    loc.SetDataSet(pd)
    loc.BuildLocator()
    V = np.array(list(nodes.values()))
    diag = np.linalg.norm(V.max(0) - V.min(0))
    closest, cid, sub, d2 = [0.0] * 3, vtk.reference(0), vtk.reference(0), vtk.reference(0.0)
    worst = 0.0
    for x in X:
        loc.FindClosestPoint(x, closest, cid, sub, d2)
        worst = max(worst, float(d2) ** 0.5)
    assert worst <= 1e-6 * diag, worst / diag


@pytest.mark.parametrize("raw", RAW)
def test_original_raw_outputs_end_without_inverted_cells(raw, tmp_path):
    path = _need(os.path.join(DATA, "hexdom", raw))
    out = str(tmp_path / "o.vtk")
    before, _ = _verdict_sj(_grid(path))
    _run("improve", "-i", path, "-o", out)
    sj, _ = _verdict_sj(_grid(out))
    assert np.all(sj > 0), f"{np.sum(sj <= 0)} inverted cells remain (input had {np.sum(before <= 0)})"


def test_python_api_improves(tmp_path):
    import sys
    sys.path.insert(0, ROOT)
    import HexDomWorkbench as hexdom
    ex = os.path.join(ROOT, "examples", "data")
    surface = hexdom.read_surface(os.path.join(ex, "lbracket_patches.k"))
    mesh = hexdom.generate(surface, hexdom.read_mesh(os.path.join(ex, "lbracket_structure.k")), level=2)
    better = hexdom.improve(mesh, surface=surface)
    q0, q1 = hexdom.quality_report(mesh), hexdom.quality_report(better)
    assert q1["hex"]["inverted"] == 0 and q1["prism"]["inverted"] == 0
    # The worst cell of any type never gets worse.
    worst = lambda q: min(q[t]["sj_min"] for t in ("hex", "prism") if q[t]["count"])  # noqa: E731
    assert worst(q1) >= worst(q0) - 1e-9


def test_inverted_cells_left_exit_three(tmp_path):
    # Only smoothing, no optimisation, on a mesh with an inverted hex the smoother cannot reach
    # (all its nodes are corners): the program says so and exits 3.
    path = tmp_path / "bad.vtk"
    pts = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    lines = ["# vtk DataFile Version 3.0", "x", "ASCII", "DATASET UNSTRUCTURED_GRID", "POINTS 8 double"]
    lines += [f"{x} {y} {-z}" for x, y, z in pts]
    lines += ["CELLS 1 9", "8 0 1 2 3 4 5 6 7", "CELL_TYPES 1", "12"]
    path.write_text("\n".join(lines) + "\n")
    out = str(tmp_path / "o.vtk")
    r = subprocess.run([HEXDOM, "improve", "-i", str(path), "-o", out, "--smooth", "2"], capture_output=True, text=True)
    assert r.returncode == 3, r.stderr
    assert "inverted" in r.stderr
