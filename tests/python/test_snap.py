"""Boundary nodes on the B-rep (issues 7 and 9): `hexdom mesh PART` puts the final mesh's boundary
nodes exactly on the CAD faces, edges and vertices, and core.snap_to_brep / core.mesh_part do the same.

Oracles nobody here wrote: FreeCAD's Part (Part.read, shape.distToShape, shape.Volume) for the
distance of every boundary node to the B-rep and the volume; VTK (vtkDataSetSurfaceFilter for the
boundary nodes, Verdict through vtkMeshQuality for the scaled Jacobians)."""

import glob
import re
import subprocess

import numpy as np
import pytest

import hexdom_oracles as oracle
import hexdom_test_support as support

DATA = support.DATA_ROOT

CAD_PARTS = ["s09o_bridge", "s11o_cube_cyl", "s15o_cylinder", "s12o_cube_rounded_1", "s14o_cube_corner_sub_sphere",
             "n11o_limit_cycle", "i10o_simp", "i11o_s1", "i01o_m1"]
# Parts the automatic polycube stage cannot mesh yet (another engineer's stage; see test_auto.py).
_NOT_MESHED = {}
# Targets not met after the snap, with the measured figure (size = diagonal / 30, level 1).
_SJ_DEFECT = {}
_SJ_DEFECT.update({
    "i01o_m1": "issue 9: worst hex SJ 0.134 after the snap (mean 0.78, 2,130 hexes): level 1 "
               "reached only 0.003 (one cell inverted by the snap), so the mesh is level 0's; its worst cells sit "
               "on the round rim at the 45 degree diagonals, where two rim quarters meet at a polycube edge beside "
               "the diagonal bolt holes",
})
# Parts meshed with inverted cells (hexdom mesh --allow-inverted), with the measured figure.
_INVERTED_DEFECT = {}
_VOLUME_DEFECT = {}


def _marks(stem, extra):
    if stem in _NOT_MESHED:
        return pytest.param(stem, marks=pytest.mark.xfail(strict=True, reason=_NOT_MESHED[stem]))
    if stem in extra:
        return pytest.param(stem, marks=pytest.mark.xfail(strict=True, reason=extra[stem]))
    return stem


@pytest.fixture(scope="module")
def Part(freecad):
    return freecad[1]


def _cad(stem):
    paths = glob.glob(str(DATA / "cad" / f"{stem}.*"))
    if not paths:
        pytest.skip(support.missing(DATA / "cad" / f"{stem}.*"))
    return paths[0]


_MESHED = {}


@pytest.fixture(scope="module")
def meshed(tmp_path_factory, core):
    """meshed(stem) -> (part path, vtkUnstructuredGrid, stdout+stderr of `hexdom mesh`), once per part."""
    if not core._hexdom.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")

    def get(stem):
        if stem not in _MESHED:
            part = _cad(stem)
            out = tmp_path_factory.mktemp(stem) / f"{stem}.vtk"
            # The snap of the polycube mesh the path makes without a time budget (i01o_m1's takes
            # longer than auto's default 20 s, and a mesh stopped early is another input).
            r = subprocess.run([str(support.hexdom_bin()), "mesh", part, "-o", str(out), "--allow-inverted",
                                "--polycube-seconds", "0"], capture_output=True, text=True)
            _MESHED[stem] = (part, r, out)
        part, r, out = _MESHED[stem]
        if r.returncode != 0:
            pytest.fail(f"hexdom mesh {stem} exited {r.returncode}: {r.stderr.strip().splitlines()[-1]}")
        g, _ = oracle.read_legacy_vtk(out)
        return part, g, r.stdout + r.stderr
    return get


def _solid(Part, path):
    shape = Part.read(path)
    return shape.Solids[0] if shape.Solids else shape


def _brep_distances(Part, shape, P):
    """Distances of the points to the boundary of the solid: to its faces, since distToShape to the
    solid itself is 0 for a point inside (OCCT's inner solution)."""
    import FreeCAD
    faces = Part.Compound(shape.Faces)
    return np.array([faces.distToShape(Part.Vertex(FreeCAD.Vector(*map(float, p))))[0] for p in P])


@pytest.mark.parametrize("stem", [_marks(s, {}) for s in CAD_PARTS])
def test_boundary_nodes_lie_on_the_brep(stem, meshed, Part):
    part, g, log = meshed(stem)
    # The progress line gives hexdom's own figure relative to the diagonal.
    m = re.search(r"^hexdom: snap: .* -> \S+ \((\S+) of the diagonal\)", log, re.M)
    assert m, log
    assert float(m.group(1)) <= 1e-7
    shape = _solid(Part, part)
    diag = shape.BoundBox.DiagonalLength
    P = oracle.boundary_points(g)
    d = _brep_distances(Part, shape, P)
    print(f"{stem}: {len(P)} boundary nodes, B-rep distance max {d.max():.3g} = {d.max() / diag:.2e} x diagonal")
    assert d.max() <= 1e-7 * diag, f"{stem}: a boundary node is {d.max() / diag:.2e} x diagonal off the B-rep"


@pytest.mark.parametrize("stem", [_marks(s, _INVERTED_DEFECT) for s in CAD_PARTS])
def test_snapped_mesh_has_no_inverted_cell(stem, meshed):
    _, g, _ = meshed(stem)
    sj, _ = oracle.verdict_metrics(g)
    assert np.all(sj > 0), f"{stem}: {int(np.sum(sj <= 0))} inverted cells (worst SJ {sj.min():.3f})"


@pytest.mark.parametrize("stem", [_marks(s, _SJ_DEFECT) for s in CAD_PARTS])
def test_snapped_worst_hex_sj_at_least_0_3(stem, meshed):
    _, g, _ = meshed(stem)
    sj, _ = oracle.verdict_metrics(g)
    types = np.array([g.GetCellType(i) for i in range(g.GetNumberOfCells())])
    hex_sj = sj[types == oracle.HEX]
    print(f"{stem}: hex SJ min {hex_sj.min():.3f} mean {hex_sj.mean():.3f} over {len(hex_sj)} hexes")
    assert hex_sj.min() >= 0.3


@pytest.mark.parametrize("stem", [_marks(s, {}) for s in CAD_PARTS])
def test_snap_keeps_the_worst_cell_it_was_given(stem, meshed):
    """The snap may not cost more than 0.02 of the worst SJ that improve reached (hexdom's own
    figure before the snap, from its progress line; the one after by Verdict). i10o_simp lost
    0.201 -> 0.074 before the restoration kept a floor and the progressive snap."""
    _, g, log = meshed(stem)
    m = re.search(r"^hexdom: snap: .* worst SJ (\S+) -> (\S+), \d+ inverted", log, re.M)
    assert m, log
    before = float(m.group(1))
    sj, _ = oracle.verdict_metrics(g)
    print(f"{stem}: worst SJ {before:.3f} before the snap, {sj.min():.3f} after (Verdict)")
    assert sj.min() >= before - 0.02


@pytest.mark.parametrize("stem", [_marks(s, _VOLUME_DEFECT) for s in CAD_PARTS])
def test_snapped_volume_within_1_percent_of_the_brep(stem, meshed, Part):
    part, g, _ = meshed(stem)
    volume = float(oracle.signed_volumes(g).sum())
    brep = _solid(Part, part).Volume
    print(f"{stem}: mesh volume {volume:.6g}, B-rep {brep:.6g}, error {100 * (volume - brep) / brep:+.3f}%")
    assert volume == pytest.approx(brep, rel=0.01)


def test_snap_moves_nodes_off_the_tessellation_onto_the_brep(core, Part):
    """core.snap_to_brep on a mesh that core.mesh_part left on the tessellation (snap=False)."""
    if not core.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")
    part = _cad("s15o_cylinder")
    surface = core.Surface(*core.tessellate_file(part))
    run = core.mesh_part(part, snap=False, allow_inverted=True)
    assert run.snap is None and "snap" not in run.seconds
    shape = _solid(Part, part)
    diag = shape.BoundBox.DiagonalLength
    mesh, rep = core.snap_to_brep(run.mesh, part, surface)
    kinds = rep["kind"][rep["kind"] > 0]
    assert len(kinds) == rep["boundary_nodes"] == rep["face_nodes"] + rep["edge_nodes"] + rep["vertex_nodes"]
    assert rep["edge_nodes"] > 0 and rep["face_nodes"] > 0
    assert core.SNAP_KINDS[int(kinds.max())] in ("edge", "vertex")
    # Independent distances before and after, at the same nodes.
    idx = np.flatnonzero(rep["kind"] > 0)
    before = _brep_distances(Part, shape, run.mesh.V[idx])
    after = _brep_distances(Part, shape, mesh.V[idx])
    print(f"s15o_cylinder: B-rep distance max {before.max():.3g} -> {after.max():.3g}, "
          f"OCCT's own figures {rep['max_before']:.3g} -> {rep['max_after']:.3g}")
    assert before.max() > 1e-5 * diag  # the tessellation's chords are measurably off the B-rep
    assert after.max() <= 1e-7 * diag
    # The report's own distances are to the face, edge or vertex each node is put on: at least
    # the distance to the whole B-rep that FreeCAD measures.
    assert rep["max_before"] >= before.max() * (1 - 1e-6)
    assert after.max() <= rep["max_after"] + 1e-12 * diag and rep["max_after"] <= 1e-7 * diag
    # Interior nodes stay inside: the interior moved only to restore quality.
    assert np.array_equal(mesh.cells, run.mesh.cells)
    sj, _ = oracle.verdict_metrics(oracle.vtk_grid(mesh.V, mesh.cells, mesh.types))
    assert sj.min() == pytest.approx(rep["worst_sj"], abs=1e-9)
    assert rep["inverted"] == int(np.sum(sj <= 0)) == 0
    # Face ids of edge nodes name real edges of the part.
    edge_ids = rep["entity"][rep["kind"] == 2]
    assert edge_ids.min() >= 1 and edge_ids.max() <= len(shape.Edges)


def test_mesh_part_snaps_and_reports(core, Part):
    if not core.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")
    part = _cad("s11o_cube_cyl")
    run = core.mesh_part(part)
    assert list(run.seconds) == ["tessellate", *core.MESH_STAGES, "snap"]
    assert run.snap["max_after"] <= 1e-7 * run.snap["diagonal"]
    assert run.quality == run.snap["quality"] and run.inverted == 0
    shape = _solid(Part, part)
    idx = np.flatnonzero(run.snap["kind"] > 0)
    d = _brep_distances(Part, shape, run.mesh.V[idx])
    assert d.max() <= 1e-7 * shape.BoundBox.DiagonalLength


def test_snap_rejects_a_tessellation_of_another_part(core):
    if not core.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")
    part = _cad("s15o_cylinder")
    surface = core.Surface(*core.tessellate_file(_cad("s09o_bridge")))
    n_faces = core.cad_info(part)["faces"]
    if surface.patch.max() <= n_faces:
        pytest.skip("the bridge has no more faces than the cylinder")
    mesh = core.Mesh(np.eye(4, 3), np.array([[0, 1, 2, 3, -1, -1, -1, -1]], np.int32), np.array([core.TET], np.int32),
                     np.zeros(1, np.int32))
    with pytest.raises(core.InputError, match=rf"s15o_cylinder.stp: tessellation triangle \d+ names Face\d+, "
                                               rf"but the solid has {n_faces} faces"):
        core.snap_to_brep(mesh, part, surface)


def test_cli_no_snap_leaves_the_tessellation(tmp_path, Part):
    part = _cad("s15o_cylinder")
    out = tmp_path / "plain.vtk"
    r = subprocess.run([str(support.hexdom_bin()), "mesh", part, "-o", str(out), "--no-snap", "--allow-inverted"],
                       capture_output=True, text=True)
    if "built without OpenCASCADE" in r.stderr:
        pytest.skip("hexdom built without OpenCASCADE")
    assert r.returncode == 0, r.stderr
    assert "snap:" not in r.stderr + r.stdout
    g, _ = oracle.read_legacy_vtk(out)
    shape = _solid(Part, part)
    d = _brep_distances(Part, shape, oracle.boundary_points(g))
    assert d.max() > 1e-5 * shape.BoundBox.DiagonalLength


def test_an_overlay_mesh_is_snapped_alike_by_hexdom_mesh_and_by_snap_to_brep(core):
    """The overlay's nodes on a smooth region go onto a CAD face only (some were let off a sharp
    curve on purpose): `hexdom mesh` (mesh_part) and core.snap_to_brep with the run's face_only (the
    workbench's Mesh object) snap them alike, to the same mesh."""
    if not core.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")
    part = _cad("s15o_cylinder")
    surface = core.Surface(*core.tessellate_file(part))
    bare = core.mesh_part(part, snap=False, allow_inverted=True, method="overlay")
    face_only = np.asarray(bare.face_only)
    assert bare.method == "overlay" and len(face_only) == len(bare.mesh.V)
    assert 0 < face_only.sum() < len(face_only)
    mesh, rep = core.snap_to_brep(bare.mesh, part, surface, max_edge_ratio=core.TARGET_EDGE_RATIO,
                                  face_only=bare.face_only)
    assert np.all(rep["kind"][face_only == 1] == 1)  # onto a face, never an edge or vertex
    snapped = core.mesh_part(part, allow_inverted=True, method="overlay")
    assert np.array_equal(snapped.mesh.cells, mesh.cells)
    assert np.abs(snapped.mesh.V - mesh.V).max() <= 1e-9 * rep["diagonal"]
    with pytest.raises(core.InputError, match="face_only has 3 entries"):
        core.snap_to_brep(bare.mesh, part, surface, face_only=[1, 0, 1])
    # A polycube run has none.
    assert core.mesh_part(part, snap=False, method="polycube").face_only == []
