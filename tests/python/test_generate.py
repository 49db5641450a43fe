"""hexdom generate on the paper models, checked with VTK as the independent reader and oracle:
cell counts, conformity, closedness, boundary nodes on the input surface, volume."""

import json
import os
import subprocess

import numpy as np
import pytest
import vtk
from vtk.util.numpy_support import vtk_to_numpy

import hexdom_oracles as O

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.environ.get("HEXDOM_DATA", os.path.join(ROOT, "..", "shared", "data"))
BUILD = os.environ.get("HEXDOM_BUILD_DIR", os.path.join(ROOT, "build"))
HEXDOM = os.path.join(BUILD, "bin", "hexdom")

MODELS = {  # model: (patch file, structure, (hex, prism, tet) blocks)
    "rockerarm": ("rockerarm_indexPatch_hexdom.k", "rockerarm_polycube_withtet.k", (60, 11, 2)),
    "mount1": ("mount1_patch_hexdom.k", "mount1_polycube_hexdom_withtet.k", (66, 10, 2)),
    "hepta": ("hepta_patch_hexdom.k", "hepta_polycube_withtet.k", (59, 22, 4)),
    "fertility": ("fertility_indexPatch_hexdom.k", "fertility_polycube_hexdom_withtet.k", (43, 5, 2)),
    "ant": ("ant_indexPatch_hexdom.k", "ant_polycube_withtet.k", (70, 24, 2)),
    "mountwithhole": ("mountwithhole_patch_hexdom.k", "mountwithhole_polycube_withtet.k", (58, 6, 2)),
}


def _model_paths(model):
    patch, structure, _ = MODELS[model]
    p = os.path.join(DATA, "hexdom", model, patch)
    s = os.path.join(DATA, "hexdom", model, structure)
    for f in (p, s):
        if not os.path.exists(f):
            pytest.skip(f"shared data missing: {f}")
    return p, s


def _generate(patches, structure, level, out, *extra):
    r = subprocess.run([HEXDOM, "generate", "-i", patches, "-p", structure, "-s", str(level), "-o", out,
                        "--report", out + ".json", *extra], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with open(out + ".json") as f:
        return json.load(f)


def _read_grid(path):
    r = vtk.vtkUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def _read_surface(path):
    """Triangles of a .k shell file, parsed here (not by our reader), as a vtkPolyData."""
    nodes, tris, section = {}, [], None
    with open(path) as f:
        for line in f:
            if line.startswith("$"):
                continue
            if line.startswith("*"):
                section = line.strip().upper()
                continue
            fields = line.replace(",", " ").split()
            if section == "*NODE" and len(fields) >= 4:
                nodes[int(fields[0])] = [float(x) for x in fields[1:4]]
            elif section == "*ELEMENT_SHELL" and len(fields) >= 5:
                tris.append([int(x) for x in fields[2:5]])
    ids = {nid: i for i, nid in enumerate(nodes)}
    V = np.array(list(nodes.values()))
    F = np.array([[ids[n] for n in t] for t in tris])
    pts = vtk.vtkPoints()
    pts.SetDataTypeToDouble()
    for p in V:
        pts.InsertNextPoint(*p)
    polys = vtk.vtkCellArray()
    for t in F:
        polys.InsertNextCell(3, [int(x) for x in t])
    pd = vtk.vtkPolyData()
    pd.SetPoints(pts)
    pd.SetPolys(polys)
    return pd, V, F


def _faces_of(grid):
    faces = {}
    for c in range(grid.GetNumberOfCells()):
        cell = grid.GetCell(c)
        for k in range(cell.GetNumberOfFaces()):
            f = cell.GetFace(k)
            ids = tuple(f.GetPointId(i) for i in range(f.GetNumberOfPoints()))
            faces.setdefault(tuple(sorted(ids)), []).append(ids)
    return faces


_VOLUME_DEFECT = pytest.mark.xfail(
    strict=True, reason="issue 3: at level 2 the boundary faces of fertility and ant are chords of a "
    "strongly curved surface and the mesh volume is 2.93% / 1.61% short of the enclosed volume. Measured "
    "(bench/bench_volume_deficit.py): the mesh volume equals its boundary polyhedron's to 0.001%, the "
    "surface-side estimate (distance x area) gives 2.90% / 1.43%, and the deficit falls by 3.97 / 3.98 from "
    "level 2 to 3 and 3.89 / 3.82 from 3 to 4: chordal O(h^2). No patch holds more than 13% of it and "
    "boundary-face areas vary by a median factor of 1.7 / 1.8 within a patch, so redistributing boundary "
    "nodes cannot reach 1%; a tube spanned by four block faces is a 16-gon at level 2 (2.6% short). "
    "Sliding the boundary nodes within the surface to enlarge the volume does not reach 1% on fertility either "
    "and costs 0.1 of mean hex SJ (docs/experiments/volume-slide.md). Level 3 is within 1%, see "
    "test_level3_volume_of_curved_models; everything else holds at level 2")


@pytest.mark.parametrize("model", MODELS)
def test_level2_counts_conformity_and_surface(model, tmp_path):
    patches, structure = _model_paths(model)
    out = str(tmp_path / f"{model}.vtk")
    report = _generate(patches, structure, 2, out)
    grid = _read_grid(out)
    types = vtk_to_numpy(grid.GetCellTypesArray())
    nh, npr, nt = MODELS[model][2]
    assert (np.sum(types == 12), np.sum(types == 13), np.sum(types == 10)) == (64 * nh, 64 * npr, 64 * nt)
    assert report["hex"]["count"] == 64 * nh

    # Conforming and closed: no face in more than two cells; boundary edges in exactly two
    # boundary faces.
    faces = _faces_of(grid)
    assert max(len(v) for v in faces.values()) <= 2
    boundary = [v[0] for v in faces.values() if len(v) == 1]
    edges = {}
    for f in boundary:
        for i in range(len(f)):
            e = tuple(sorted((f[i], f[(i + 1) % len(f)])))
            edges[e] = edges.get(e, 0) + 1
    assert set(edges.values()) == {2}

    # No coincident nodes.
    X = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    diag = np.linalg.norm(X.max(0) - X.min(0))
    assert len(np.unique(np.round(X / (1e-9 * diag)), axis=0)) == len(X)

    # Boundary nodes lie on the input triangles (VTK's cell locator as the oracle).
    pd, SV, SF = _read_surface(patches)
    loc = vtk.vtkCellLocator()
    loc.SetDataSet(pd)
    loc.BuildLocator()
    bnodes = sorted({i for f in boundary for i in f})
    worst = 0.0
    closest = [0.0, 0.0, 0.0]
    cid, sub, d2 = vtk.reference(0), vtk.reference(0), vtk.reference(0.0)
    for i in bnodes:
        loc.FindClosestPoint(X[i], closest, cid, sub, d2)
        worst = max(worst, float(d2) ** 0.5)
    sdiag = np.linalg.norm(SV.max(0) - SV.min(0))
    assert worst <= 1e-9 * sdiag, f"boundary node {worst / sdiag:.2e} x diagonal off the surface"


def _volume_and_enclosed(patches, mesh_path):
    """The mesh's volume (VTK's cell sizes) and the volume its input surface encloses (divergence
    theorem over the input triangles)."""
    _, SV, SF = _read_surface(patches)
    a, b, c = SV[SF[:, 0]], SV[SF[:, 1]], SV[SF[:, 2]]
    enclosed = abs(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)
    sizes = vtk.vtkCellSizeFilter()
    sizes.SetInputData(_read_grid(mesh_path))
    sizes.Update()
    return vtk_to_numpy(sizes.GetOutput().GetCellData().GetArray("Volume")).sum(), enclosed


@pytest.mark.parametrize("model", [pytest.param(m, marks=_VOLUME_DEFECT) if m in ("fertility", "ant") else m
                                   for m in MODELS])
def test_level2_volume(model, tmp_path):
    patches, structure = _model_paths(model)
    out = str(tmp_path / f"{model}.vtk")
    _generate(patches, structure, 2, out)
    vol, enclosed = _volume_and_enclosed(patches, out)
    assert abs(vol - enclosed) <= 0.01 * enclosed, (vol, enclosed)


@pytest.mark.parametrize("model", ["fertility", "ant"])
def test_level3_volume_of_curved_models(model, tmp_path):
    patches, structure = _model_paths(model)
    out = str(tmp_path / f"{model}3.vtk")
    _generate(patches, structure, 3, out)
    vol, enclosed = _volume_and_enclosed(patches, out)
    assert abs(vol - enclosed) <= 0.01 * enclosed, (vol, enclosed)


# Inverted cells straight out of generation (the default run, with its untangling), before any
# improvement, by Verdict. The original's raw HexGen output had inverted hexes on every model but
# hepta (rockerarm: 11, min SJ -0.451); the plain relaxation alone (--no-untangle) leaves 2-110
# inverted cells on four of six models.
_INVERTED_LEFT = {
    "ant": "issue 3: 20 cells of the ant (15 prisms, 5 tets; worst Verdict SJ -0.225) stay inverted before "
           "improvement, next to its flat structure tets (block SJ 0.15) where a boundary curve bows 14% of an "
           "edge: each has three to five of its six nodes on the boundary. The plain relaxation leaves 110 "
           "(1 hex, 50 prisms, 59 tets); untangling with surface nodes within 0.45 of a lattice step at once "
           "left 7 prisms but made improve end at worst hex 0.245 on ant and 0.223 on fertility "
           "(bench/bench_untangle_improve.py); improvement removes the rest",
}


def _verdict_inverted(path):
    sj, _ = O.verdict_metrics(_read_grid(path))
    bad = ~((sj > 0) & (sj <= 1))  # Verdict: <= 0 inverted, DBL_MAX degenerate
    return int(bad.sum()), float(np.min(np.where(bad & (sj > 1), -1.0, sj)))


@pytest.mark.parametrize("model", [pytest.param(m, marks=pytest.mark.xfail(strict=True, reason=_INVERTED_LEFT[m]))
                                   if m in _INVERTED_LEFT else m for m in MODELS])
def test_level2_has_no_inverted_cell_before_improvement(model, tmp_path):
    patches, structure = _model_paths(model)
    out = str(tmp_path / f"{model}.vtk")
    report = _generate(patches, structure, 2, out)
    inverted, worst = _verdict_inverted(out)
    assert inverted == report["hex"]["inverted"] + report["prism"]["inverted"] + report["tet"]["inverted"]
    assert inverted == 0, f"{inverted} inverted cells, worst scaled Jacobian {worst:.3f}"


def test_relaxation_untangles_the_raw_placement(tmp_path):
    # Fertility's raw placement (--relax 0) has inverted hexes and prisms; the default run untangles
    # them all, sliding boundary nodes within the surface where needed; boundary nodes stay on the
    # input triangles (checked below with VTK's locator, as in test_level2_counts_conformity_and_surface).
    patches, structure = _model_paths("fertility")
    raw = str(tmp_path / "raw.vtk")
    r = subprocess.run([HEXDOM, "generate", "-i", patches, "-p", structure, "-s", "2", "-o", raw, "--relax", "0"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    relaxed = str(tmp_path / "relaxed.vtk")
    _generate(patches, structure, 2, relaxed)
    n0, w0 = _verdict_inverted(raw)
    n1, w1 = _verdict_inverted(relaxed)
    assert n0 > 0 and n1 == 0, (n0, n1)
    assert w1 > w0
    grid = _read_grid(relaxed)
    boundary = [v[0] for v in _faces_of(grid).values() if len(v) == 1]
    X = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    pd, SV, _ = _read_surface(patches)
    loc = vtk.vtkCellLocator()
    loc.SetDataSet(pd)
    loc.BuildLocator()
    closest, cid, sub, d2 = [0.0, 0.0, 0.0], vtk.reference(0), vtk.reference(0), vtk.reference(0.0)
    worst = 0.0
    for i in sorted({i for f in boundary for i in f}):
        loc.FindClosestPoint(X[i], closest, cid, sub, d2)
        worst = max(worst, float(d2) ** 0.5)
    assert worst <= 1e-9 * np.linalg.norm(SV.max(0) - SV.min(0))


_LEVEL3_INVERTED = pytest.mark.xfail(
    strict=True, reason="issue 3: at level 3 rockerarm keeps 3 inverted hexes and 1 prism in the default run "
    "(worst SJ -0.227): each inverted hex corner and its three edge neighbours are all boundary nodes at a "
    "boundary edge, where the two patches meet at about 180 degrees: with all four on the surface the corner's "
    "Jacobian sample cannot be made positive by sliding them within it (the raw placement had 10 hexes, 36 "
    "prisms; improve's pillow layer removes them)")


@_LEVEL3_INVERTED
def test_rockerarm_level3_has_no_inverted_cell(tmp_path):
    patches, structure = _model_paths("rockerarm")
    out = str(tmp_path / "r3.vtk")
    _generate(patches, structure, 3, out)
    inverted, worst = _verdict_inverted(out)
    assert inverted == 0, f"{inverted} inverted cells, worst scaled Jacobian {worst:.3f}"


def test_untangling_moves_only_nodes_near_inverted_cells(tmp_path):
    # The default run is the plain relaxation (--no-untangle) plus the untangling of the cells it
    # leaves inverted: every node that differs lies within two cell rings of a cell the plain run
    # left inverted (Verdict), and everything else is bit for bit the plain run's.
    patches, structure = _model_paths("fertility")
    plain, untangled = str(tmp_path / "plain.vtk"), str(tmp_path / "untangled.vtk")
    _generate(patches, structure, 2, plain, "--no-untangle")
    _generate(patches, structure, 2, untangled)
    g0, g1 = _read_grid(plain), _read_grid(untangled)
    X0 = vtk_to_numpy(g0.GetPoints().GetData()).astype(float)
    X1 = vtk_to_numpy(g1.GetPoints().GetData()).astype(float)
    cells = [[g0.GetCell(c).GetPointId(i) for i in range(g0.GetCell(c).GetNumberOfPoints())]
             for c in range(g0.GetNumberOfCells())]
    sj, _ = O.verdict_metrics(g0)
    bad = ~((sj > 0) & (sj <= 1))
    assert bad.sum() > 0 and _verdict_inverted(untangled)[0] == 0
    near = {v for c in np.flatnonzero(bad) for v in cells[c]}
    for _ in range(2):
        near |= {v for cell in cells if near.intersection(cell) for v in cell}
    moved = set(np.flatnonzero(np.any(X0 != X1, axis=1)).tolist())
    assert moved, "the untangling moved no node"
    assert moved <= near, f"{len(moved - near)} nodes moved away from the inverted cells"
    assert len(moved) < 0.05 * len(X0)


def test_thread_count_does_not_change_the_mesh(tmp_path):
    patches, structure = _model_paths("rockerarm")
    outs = []
    for threads in (1, 2, 3):
        out = str(tmp_path / f"t{threads}.vtk")
        r = subprocess.run([HEXDOM, "generate", "-i", patches, "-p", structure, "-s", "2", "-o", out,
                            "--threads", str(threads)], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        outs.append(open(out, "rb").read())
    assert outs[0] == outs[1] == outs[2]


@pytest.mark.parametrize("level", [0, 1, 3])
def test_rockerarm_levels(level, tmp_path):
    patches, structure = _model_paths("rockerarm")
    out = str(tmp_path / "r.vtk")
    _generate(patches, structure, level, out)
    types = vtk_to_numpy(_read_grid(out).GetCellTypesArray())
    per = 8 ** level
    assert (np.sum(types == 12), np.sum(types == 13), np.sum(types == 10)) == (60 * per, 11 * per, 2 * per)


def test_bundled_example_has_no_inverted_cell(tmp_path):
    ex = os.path.join(ROOT, "examples", "data")
    out = str(tmp_path / "lb.vtk")
    report = _generate(os.path.join(ex, "lbracket_patches.k"), os.path.join(ex, "lbracket_structure.k"), 2, out)
    grid = _read_grid(out)
    q = vtk.vtkMeshQuality()
    q.SetInputData(grid)
    q.SetHexQualityMeasureToScaledJacobian()
    q.Update()
    sj = vtk_to_numpy(q.GetOutput().GetCellData().GetArray("Quality"))
    types = vtk_to_numpy(grid.GetCellTypesArray())
    assert sj[types == 12].min() > 0.5
    assert report["hex"]["inverted"] == report["prism"]["inverted"] == 0
    assert report["hex"]["count"] == 3 * 64 and report["prism"]["count"] == 64


def _fails_without_output(args, out, needle):
    r = subprocess.run([HEXDOM] + args, capture_output=True, text=True)
    assert r.returncode == 1, r.stderr
    assert needle in r.stderr, r.stderr
    assert not os.path.exists(out)


def test_face_matching_no_patch_is_an_error(tmp_path):
    ex = os.path.join(ROOT, "examples", "data")
    # Merge patch 2 into its neighbour 1: block 1's face x=0 then matches no patch's corners.
    out_lines, section = [], None
    for line in open(os.path.join(ex, "lbracket_patches.k")).read().splitlines():
        if line.startswith("*"):
            section = line.strip()
        elif section == "*ELEMENT_SHELL" and int(line[8:16]) == 2:
            line = line[:8] + "%8d" % 1 + line[16:]
        out_lines.append(line)
    merged = tmp_path / "merged.k"
    merged.write_text("\n".join(out_lines) + "\n")
    out = str(tmp_path / "o.vtk")
    _fails_without_output(["generate", "-i", str(merged), "-p", os.path.join(ex, "lbracket_structure.k"), "-s", "1", "-o", out],
                          out, "matches no patch")


def test_non_manifold_patch_file_is_an_error(tmp_path):
    ex = os.path.join(ROOT, "examples", "data")
    text = open(os.path.join(ex, "lbracket_patches.k")).read()
    # Repeat the first triangle: its edges are then shared by three triangles.
    lines = text.splitlines()
    shell = [i for i, l in enumerate(lines) if l.strip() == "*ELEMENT_SHELL"][0]
    first = lines[shell + 1].split()
    lines.insert(shell + 1, "%8d%8d%8d%8d%8d%8d" % (999999, 1, int(first[2]), int(first[3]), int(first[4]), int(first[4])))
    bad = tmp_path / "bad.k"
    bad.write_text("\n".join(lines) + "\n")
    out = str(tmp_path / "o.vtk")
    _fails_without_output(["generate", "-i", str(bad), "-p", os.path.join(ex, "lbracket_structure.k"), "-s", "1", "-o", out],
                          out, "non-manifold edge")


def test_level_outside_range_is_an_error(tmp_path):
    ex = os.path.join(ROOT, "examples", "data")
    out = str(tmp_path / "o.vtk")
    _fails_without_output(["generate", "-i", os.path.join(ex, "lbracket_patches.k"), "-p",
                           os.path.join(ex, "lbracket_structure.k"), "-s", "7", "-o", out], out, "outside 0..6")
