"""The automatic path (issue 9) checked from outside: `hexdom autopolycube` feeding `hexdom generate`,
`hexdom mesh` on the paper's raw surfaces and the shared CAD parts, and core.autopolycube /
mesh_surface / mesh_part. VTK reads the outputs and Verdict (vtkMeshQuality) judges the cells; the
.k files are parsed by hexdom_oracles.parse_k, not by our readers."""

import glob
import json
import os
import subprocess

import numpy as np
import pytest
import vtk

import hexdom_oracles as oracle
import hexdom_test_support as support

DATA = support.DATA_ROOT


def _need(path):
    if not os.path.exists(path):
        pytest.skip(support.missing(path))
    return str(path)


def _run(*args, ok=True):
    r = subprocess.run([str(support.hexdom_bin()), *map(str, args)], capture_output=True, text=True)
    if ok:
        assert r.returncode == 0, r.stderr
    return r


def _raw(model):
    return _need(DATA / "hexdom" / model / f"{model}.k")


def _k_surface(path):
    """(V, F, pid per triangle) of the shells of a .k file, parsed independently."""
    k = oracle.parse_k(path)
    ids = {nid: i for i, nid in enumerate(k["nodes"])}
    V = np.array(list(k["nodes"].values()), float)
    F = np.array([[ids[n] for n in s[2][:3]] for s in k["shells"]])
    return V, F, np.array([s[1] for s in k["shells"]])


def _enclosed(V, F):
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def _locator(V, F):
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
    loc = vtk.vtkCellLocator()
    loc.SetDataSet(pd)
    loc.BuildLocator()
    return loc, pd


def _distance(loc, p):
    closest = [0.0, 0.0, 0.0]
    cid, sub, d2 = vtk.reference(0), vtk.reference(0), vtk.reference(0.0)
    loc.FindClosestPoint(list(p), closest, cid, sub, d2)
    return float(d2) ** 0.5


def _faces(conn):
    faces = {}
    for c in conn:
        for f in ([0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]):
            key = tuple(sorted(c[i] for i in f))
            faces.setdefault(key, []).append([c[i] for i in f])
    return faces


def _check_hex_mesh(path, surface_V, surface_F):
    """All hexes, conforming and closed, boundary nodes on the surface; returns (Verdict SJ, VTK
    volume)."""
    g, _ = oracle.read_legacy_vtk(path)
    P, types, conn = oracle.grid_arrays(g)
    assert set(types.tolist()) == {oracle.HEX}
    faces = _faces(conn)
    assert max(len(v) for v in faces.values()) <= 2
    boundary = [v[0] for v in faces.values() if len(v) == 1]
    edges = {}
    for f in boundary:
        for i in range(4):
            e = tuple(sorted((f[i], f[(i + 1) % 4])))
            edges[e] = edges.get(e, 0) + 1
    assert set(edges.values()) == {2}
    loc, _ = _locator(surface_V, surface_F)
    diag = np.linalg.norm(surface_V.max(0) - surface_V.min(0))
    worst = max(_distance(loc, P[i]) for i in {i for f in boundary for i in f})
    assert worst <= 1e-6 * diag, f"a boundary node is {worst / diag:.1e} x diagonal off the surface"
    sj, _ = oracle.verdict_metrics(g)
    return sj, float(oracle.signed_volumes(g).sum())


# ------------------------------------------------------------------------------------------------
# hexdom autopolycube -> hexdom generate

@pytest.fixture(scope="module")
def hepta_auto(tmp_path_factory):
    d = tmp_path_factory.mktemp("hepta_auto")
    raw = _raw("hepta")
    _run("segment", "-i", raw, "-o", d / "labels.k")
    r = _run("autopolycube", "-i", d / "labels.k", "-o", d / "structure.k", "--patches-out", d / "patches.k",
             "--polycube-out", d / "polycube.vtk")
    return d, raw, r


def test_autopolycube_outputs_feed_generate_unchanged(hepta_auto):
    d, raw, _ = hepta_auto
    solids = oracle.parse_k(d / "structure.k")["solids"]
    assert solids and all(len(set(s[2])) == 8 for s in solids)  # hex blocks only
    _run("generate", "-i", d / "patches.k", "-p", d / "structure.k", "-s", "1", "-o", d / "mesh.vtk")
    V, F, _ = _k_surface(raw)
    sj, volume = _check_hex_mesh(d / "mesh.vtk", V, F)
    g, _ = oracle.read_legacy_vtk(d / "mesh.vtk")
    assert g.GetNumberOfCells() == 8 * len(solids)
    assert sj.min() > 0
    assert volume == pytest.approx(_enclosed(V, F), rel=0.01)


def test_patch_surface_keeps_the_input_geometry(hepta_auto):
    d, raw, _ = hepta_auto
    V, F, _ = _k_surface(raw)
    PV, PF, pid = _k_surface(d / "patches.k")
    assert _enclosed(PV, PF) == pytest.approx(_enclosed(V, F), rel=1e-9)
    loc, _ = _locator(V, F)
    diag = np.linalg.norm(V.max(0) - V.min(0))
    assert max(_distance(loc, p) for p in PV) <= 1e-9 * diag
    # One patch per boundary face of the structure (faces used by one block only).
    solids = [s[2] for s in oracle.parse_k(d / "structure.k")["solids"]]
    boundary = [k for k, v in _faces(solids).items() if len(v) == 1]
    assert len(set(pid.tolist())) == len(boundary)


def test_autopolycube_reports_its_figures(hepta_auto):
    _, _, r = hepta_auto
    assert "blocks:" in r.stdout and "boundary squares:" in r.stdout and "worst block SJ:" in r.stdout


def test_autopolycube_errors_write_nothing(tmp_path):
    raw = _raw("hepta")
    out, patches = tmp_path / "s.k", tmp_path / "p.k"
    # One part id over the whole closed surface: neither labels 1..6 nor patches of one orientation.
    V, F, _ = _k_surface(raw)
    bad = tmp_path / "bad.obj"
    with open(bad, "w") as f:
        f.write("".join(f"v {x} {y} {z}\n" for x, y, z in V))
        f.write("g patch_9\n" + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F))
    r = _run("autopolycube", "-i", bad, "-o", out, "--patches-out", patches, ok=False)
    assert r.returncode == 1 and "bad.obj: part 9 (" in r.stderr and "faces no one axis" in r.stderr
    assert not out.exists() and not patches.exists()
    r = _run("autopolycube", "-i", raw, "-o", tmp_path / "s.xyz", "--patches-out", patches, ok=False)
    assert r.returncode == 1 and not patches.exists()


# ------------------------------------------------------------------------------------------------
# hexdom mesh on the paper's raw surfaces

_RAW_VOLUME = {
    "mount1": "issue 9: volume -1.09% at size = diagonal / 30 (chords of the 16-facet ear holes and rounds; "
              "worst hex SJ 0.363, mean 0.77, 1392 hex)",
    # rockerarm: the polycube mesh is -3.70% (issue 9); auto then meshes the overlay grid too and
    # keeps it (0 inverted, worst SJ 0.58, volume within 1%).
}


@pytest.fixture(scope="module")
def paper_mesh(tmp_path_factory):
    """hexdom mesh on a paper model's raw surface, once per model and method, the polycube path
    without a time budget: (raw, mesh, report, stderr)."""
    runs = {}

    def run(model, method="auto"):
        if (model, method) not in runs:
            raw = _raw(model)
            d = tmp_path_factory.mktemp(model)
            out = d / f"{model}.vtk"
            # The polycube path's figures on the paper's models, whatever it takes: no time budget
            # (rockerarm's label repair alone takes longer than auto's default 20 s).
            r = _run("mesh", raw, "-o", out, "--report", d / "q.json", "--polycube-seconds", "0", "--method", method,
                     ok=False)
            assert r.returncode == 0, r.stderr
            with open(d / "q.json") as f:
                runs[(model, method)] = (raw, out, json.load(f), r.stderr)
        return runs[(model, method)]
    return run


@pytest.mark.parametrize("model", ["hepta", "mount1", "rockerarm"])
def test_mesh_paper_model_has_no_inverted_cell(model, paper_mesh):
    raw, out, report, stderr = paper_mesh(model)
    # One line per stage; the polycube path's first candidate may have been stopped after 5 s
    # because the overlay's mesh met every target (pipeline/choice.h), the line says so.
    stopped = "the overlay mesh meets every target" in stderr
    for stage in ("segment:",) + (() if stopped else ("autopolycube:", "generate:", "improve:")):
        assert stage in stderr
    V, F, _ = _k_surface(raw)
    sj, _ = _check_hex_mesh(out, V, F)  # all hexes, conforming, closed, boundary nodes on the surface
    assert sj.min() > 0
    assert report["hex"]["inverted"] == 0
    assert report["hex"]["sj_min"] == pytest.approx(sj.min(), abs=1e-6)


@pytest.mark.parametrize("model", [pytest.param(m, marks=pytest.mark.xfail(strict=True, reason=_RAW_VOLUME[m]))
                                   if m in _RAW_VOLUME else m for m in ["hepta", "mount1", "rockerarm"]])
def test_mesh_paper_model_keeps_the_volume(model, paper_mesh):
    raw, out, _, _ = paper_mesh(model)
    V, F, _ = _k_surface(raw)
    g, _ = oracle.read_legacy_vtk(out)
    assert float(oracle.signed_volumes(g).sum()) == pytest.approx(_enclosed(V, F), rel=0.01)


@pytest.mark.parametrize("model", ["fertility", "ant"])
def test_overlay_path_meshes_the_organic_raw_surfaces(model, paper_mesh):
    # The paper's organic raw surfaces, which the polycube path does not mesh at the default size:
    # the overlay path alone gives all hexes, conforming, every boundary node on the input surface,
    # none inverted (Verdict), the volume within 1%.
    raw, out, report, stderr = paper_mesh(model, "overlay")
    assert "kept: overlay path" in stderr
    V, F, _ = _k_surface(raw)
    sj, volume = _check_hex_mesh(out, V, F)
    assert sj.min() > 0 and report["hex"]["inverted"] == 0
    assert volume == pytest.approx(_enclosed(V, F), rel=0.01)


def test_mesh_refines_the_grid_when_inverted_cells_remain(paper_mesh):
    # rockerarm at level 1 keeps inverted cells (its bore wall is thinner than a block); the polycube
    # path says so and finishes at level 0, where every block is one cell. (Auto keeps the overlay
    # mesh, which meets every target, without the polycube's further candidates.)
    _, out, report, stderr = paper_mesh("rockerarm", "polycube")
    assert "again with level 0" in stderr
    lines = stderr.splitlines()
    blocks = [line for line in lines if line.startswith("hexdom: autopolycube:") and " blocks of " in line]
    cells = [line for line in lines if line.startswith("hexdom: generate:")]
    # Level 0: one generated cell per block.
    assert int(blocks[-1].split(" blocks of ")[0].split()[-1]) == int(cells[-1].split()[2])
    g, _ = oracle.read_legacy_vtk(out)
    assert g.GetNumberOfCells() == report["hex"]["count"]


def test_mesh_segments_again_when_the_labelling_defeats_autopolycube(paper_mesh):
    # mount1's ears at lambda 0.1: the relabelling cascades to one chart; lambda 1 needs no relabel.
    # (Under auto the further edge weights come after the overlay grid: see the next test.)
    _, _, report, stderr = paper_mesh("mount1", "polycube")
    segments = [line for line in stderr.splitlines() if line.startswith("hexdom: segment:") and "labelled" in line]
    assert "(lambda 0.1)" in segments[0] and "(lambda 1)" in segments[-1]
    assert "segmenting again with lambda 1" in stderr
    assert report["hex"]["inverted"] == 0


def test_auto_tries_the_further_edge_weights_after_the_overlay_grid(paper_mesh):
    """Under auto the polycube's first run segments once (lambda 0.1); the further edge weights come
    only when the overlay grid's mesh misses a target too (mount1's: volume -1.6%), after it. On the
    corpus the retries first made a mesh that was kept in 1 part in 221 and cost up to 12 s where
    the overlay met the targets (docs/overlay.md)."""
    _, _, report, stderr = paper_mesh("mount1")
    overlay = stderr.index("hexdom: overlay: spacing")
    assert "segmenting again with lambda" not in stderr[:overlay]
    assert "the polycube again, segmenting with lambda 1" in stderr[overlay:]
    assert "(lambda 1)" in stderr[overlay:]
    assert report["hex"]["inverted"] == 0


def test_mesh_failure_leaves_the_intermediate_files(tmp_path):
    raw = _raw("rockerarm")
    out = tmp_path / "r.vtk"
    r = _run("mesh", raw, "-o", out, "--max-relabels", "0", "--method", "polycube", ok=False)
    assert r.returncode == 1
    assert "problems of the labelling remain" in r.stderr
    assert not out.exists()
    V, F, label = _k_surface(tmp_path / "r_labels.k")
    assert len(F) > 0 and set(label.tolist()) <= set(range(1, 7))


def test_auto_meshes_with_the_overlay_grid_where_the_polycube_fails(tmp_path):
    """The same labelling defeat under --method auto (the default): the overlay grid meshes the
    surface instead, and the log says why and which path made the mesh."""
    raw = _raw("rockerarm")
    out = tmp_path / "r.vtu"
    r = _run("mesh", raw, "-o", out, "--max-relabels", "0", "--allow-inverted")
    assert "the polycube path failed" in r.stderr and "problems of the labelling remain" in r.stderr
    assert "kept: overlay path" in r.stderr
    g = oracle.read_vtu(out)
    assert g.GetNumberOfCells() > 1000
    V, F, _ = _k_surface(raw)
    assert np.sum(oracle.signed_volumes(g)) == pytest.approx(abs(_enclosed(V, F)), rel=0.01)


def test_mesh_missing_input_is_exit_1(tmp_path):
    r = _run("mesh", tmp_path / "none.k", "-o", tmp_path / "x.vtk", ok=False)
    assert r.returncode == 1 and "none.k" in r.stderr
    assert not (tmp_path / "x.vtk").exists()


# ------------------------------------------------------------------------------------------------
# hexdom mesh on CAD parts (size = bounding-box diagonal / 30, the default)

CAD_PARTS = ["s09o_bridge", "s11o_cube_cyl", "s15o_cylinder", "s12o_cube_rounded_1", "s14o_cube_corner_sub_sphere",
             "n11o_limit_cycle", "i10o_simp", "i11o_s1"]
_CAD_DEFECT = {}


def _cad(stem):
    paths = glob.glob(str(DATA / "cad" / f"{stem}.*"))
    if not paths:
        pytest.skip(support.missing(DATA / "cad" / f"{stem}.*"))
    return paths[0]


@pytest.fixture(scope="module")
def cad_mesh(tmp_path_factory, core):
    """hexdom mesh --no-snap on a CAD part, once per part: (part, mesh, tessellation V, F)."""
    runs = {}

    def run(stem):
        if not core._hexdom.has_opencascade():
            pytest.skip("_hexdom built without OpenCASCADE")
        if stem not in runs:
            part = _cad(stem)
            d = tmp_path_factory.mktemp(stem)
            out = d / f"{stem}.vtk"
            # The automatic path itself (either path), boundary on the tessellation it kept;
            # test_snap.py checks the final mesh, whose boundary nodes are on the B-rep instead.
            _run("mesh", part, "-o", out, "--keep", "--no-snap")
            V, F, _ = _k_surface(d / f"{stem}_surface.k")
            runs[stem] = (part, out, V, F)
        return runs[stem]
    return run


@pytest.mark.parametrize("stem", CAD_PARTS)
def test_mesh_cad_part_is_conforming_and_on_the_surface(stem, cad_mesh):
    _, out, V, F = cad_mesh(stem)
    sj, _ = _check_hex_mesh(out, V, F)
    assert sj.min() > 0


@pytest.mark.parametrize("stem", [pytest.param(s, marks=pytest.mark.xfail(strict=True, reason=_CAD_DEFECT[s]))
                                  if s in _CAD_DEFECT else s for s in CAD_PARTS])
def test_mesh_cad_part(stem, cad_mesh, core):
    part, out, V, F = cad_mesh(stem)
    sj, volume = _check_hex_mesh(out, V, F)
    assert sj.min() >= 0.3
    assert volume == pytest.approx(core._hexdom.cad_volume(part), rel=0.01)


# ------------------------------------------------------------------------------------------------
# HexDomWorkbench.core

def _box(core, nx, ny, nz, n=2):
    """Closed surface of an nx x ny x nz box of unit cells, faces split into n x n squares, labels
    from normals: built here with numpy."""
    pts, tris = {}, []

    def vid(p):
        return pts.setdefault(p, len(pts))
    size = (nx, ny, nz)
    for a in range(3):
        b, c = (a + 1) % 3, (a + 2) % 3
        for side in (0, 1):
            for i in range(size[b] * n):
                for j in range(size[c] * n):
                    q = []
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = [0, 0, 0]
                        p[a] = side * size[a] * n
                        p[b], p[c] = i + di, j + dj
                        q.append(vid(tuple(p)))
                    tris += [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] if side else [[q[0], q[2], q[1]], [q[0], q[3], q[2]]]
    V = np.array(sorted(pts, key=pts.get), float) / n
    F = np.array(tris, np.int32)
    nrm = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    axis = np.abs(nrm).argmax(1)
    label = (2 * axis + 1 + (nrm[np.arange(len(F)), axis] < 0)).astype(np.int32)
    return core.Surface(V, F, label)


def test_core_autopolycube_of_a_box(core):
    s = _box(core, 3, 2, 1)
    r = core.autopolycube(s, size=0.5, level=1)
    assert r.info["blocks"] == 6 and r.info["squares"] == 2 * (6 + 3 + 2) and r.info["inverted_blocks"] == 0
    assert r.structure.count(core.HEX) == 6
    m = core.generate(r.patches, r.structure, level=1)
    q = core.quality_report(m)
    assert q["hex"]["count"] == 48 and q["hex"]["sj_min"] == pytest.approx(1.0)
    assert q["total_volume"] == pytest.approx(6.0)


def test_core_autopolycube_rejects_labels_outside_1_to_6(core):
    s = _box(core, 1, 1, 1)
    s.patch[0] = 8
    with pytest.raises(core.GeometryError, match="label 8"):
        core.autopolycube(s)


def test_core_mesh_surface_runs_every_stage(core):
    s = core.read_surface(_raw("hepta"))
    run = core.mesh_surface(s)
    assert list(run.seconds) == list(core.MESH_STAGES)
    assert run.inverted == 0 and run.quality["hex"]["count"] == run.mesh.count(core.HEX)
    assert run.level == 1 and run.edge_weight == pytest.approx(0.1)  # hepta needs no fallback
    assert run.generated.count(core.HEX) == 8 * run.polycube.info["blocks"]
    sj, _ = oracle.verdict_metrics(oracle.vtk_grid(run.mesh.V, run.mesh.cells, run.mesh.types))
    assert sj.min() == pytest.approx(run.quality["hex"]["sj_min"], abs=1e-9)


def test_core_mesh_structure_is_the_pipeline_s_generation_and_improvement(core):
    """core.mesh_structure on the polycube mesh_surface kept (its structure, patch surface and
    level) gives the pipeline's generated and improved meshes exactly: the stage the HexDom Mesh
    calls when it is built from its stages."""
    s = core.read_surface(os.path.join(support.REPO, "examples", "data", "lbracket_patches.k"))
    run = core.mesh_surface(s, method="polycube", polycube_seconds=0)
    assert run.method == "polycube" and run.polycube.structure.count(core.HEX) > 0
    again = core.mesh_structure(run.polycube.patches, run.polycube.structure, level=run.level)
    for a, b in ((run.generated, again.generated), (run.mesh, again.mesh)):
        assert np.array_equal(a.cells, b.cells) and np.array_equal(a.types, b.types)
        assert np.array_equal(a.V, b.V)
    assert again.quality["hex"]["sj_min"] == run.quality["hex"]["sj_min"]
    assert again.level == run.level
    # Without the improvement: the generated mesh as it is.
    plain = core.mesh_structure(run.polycube.patches, run.polycube.structure, level=run.level, improve=False)
    assert np.array_equal(plain.mesh.V, run.generated.V)


def test_core_stages_rebuild_a_thin_part_stretched(core, freecad):
    """A plate 100 x 40 x 1 with its top edges chamfered 0.5 is meshed by the polycube path
    stretched along its thickness (cells of a different length along each axis). core.segment,
    autopolycube and mesh_structure given the run's frame and stretch (what the HexDom Segmentation
    keeps) rebuild its labels, polycube and mesh bit for bit. Unstretched, the chamfers (45 degrees,
    about 79 degrees stretched) take other labels."""
    if not core._hexdom.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE (the plate's tessellation)")
    _, Part = freecad
    plate = Part.makeBox(100, 40, 1.0)
    plate = plate.makeChamfer(0.5, [e for e in plate.Edges if e.BoundBox.ZLength < 1e-9 and e.BoundBox.ZMin > 0.5])
    s = core.mesh_part(plate.exportBrepToString(), method="polycube", polycube_seconds=0).surface
    run = core.mesh_surface(s, method="polycube", polycube_seconds=0)
    assert run.method == "polycube" and run.stretch[2] > 1 and run.stretch[:2] == (1.0, 1.0)
    frame = run.frame["rotation"]
    seg = core.segment(s, edge_weight=run.edge_weight, frame=frame, stretch=run.stretch)
    assert np.array_equal(seg.patch, run.labels.patch)
    assert not np.array_equal(core.segment(s, edge_weight=run.edge_weight, frame=frame).patch, seg.patch)
    cell = run.polycube.info["cell"]  # in the stretched space, as the Polycube's Size
    poly = core.autopolycube(core.Surface(s.V, s.F, seg.patch), size=cell / 2 ** run.level,
                             level=run.level, keep_widths=run.keep_widths,
                             collapse_apexes=run.collapse_apexes, frame=frame, stretch=run.stretch)
    assert np.array_equal(poly.structure.cells, run.polycube.structure.cells)
    assert np.array_equal(poly.structure.V, run.polycube.structure.V)
    again = core.mesh_structure(poly.patches, poly.structure, level=run.level, frame=frame,
                                stretch=run.stretch)
    assert np.array_equal(again.mesh.cells, run.mesh.cells)
    assert np.array_equal(again.mesh.V, run.mesh.V)
    ratio = oracle.edge_ratios(again.mesh.V[again.mesh.cells], oracle.HEX).max()
    assert ratio == pytest.approx(run.quality["hex"]["edge_ratio_max"], rel=1e-9) and ratio < 6
    with pytest.raises(core.InputError, match="finite and positive"):
        core.segment(s, stretch=(1.0, 0.0, 1.0))


def test_core_mesh_surface_takes_the_method(core):
    """HexDomWorkbench.core passes method= through and reports the path: the rockerarm with no label
    repair defeats the polycube ("polycube" raises), "auto" gives the overlay grid's mesh with the
    polycube path's error as polycube_note, "overlay" the same mesh with no note; an unknown method
    is refused before anything runs."""
    s = core.read_surface(_raw("rockerarm"))
    with pytest.raises(core.GeometryError, match="problems of the labelling remain"):
        core.mesh_surface(s, max_relabels=0, method="polycube", allow_inverted=True)
    run = core.mesh_surface(s, max_relabels=0, allow_inverted=True)
    assert run.method == "overlay"
    assert run.polycube_note.startswith("the polycube path failed at stage autopolycube")
    assert run.choice.startswith("overlay grid")
    forced = core.mesh_surface(s, max_relabels=0, method="overlay", allow_inverted=True)
    assert forced.method == "overlay" and forced.polycube_note == ""
    assert forced.mesh.count(core.HEX) == run.mesh.count(core.HEX) > 1000
    V, F, _ = _k_surface(_raw("rockerarm"))
    assert run.quality["total_volume"] == pytest.approx(abs(_enclosed(V, F)), rel=0.01)
    with pytest.raises(core.InputError, match="unknown meshing method 'grid'"):
        core.mesh_surface(s, method="grid")


def test_core_mesh_part_tessellates_first(core):
    if not core._hexdom.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")
    part = _cad("s09o_bridge")
    run = core.mesh_part(part)
    assert list(run.seconds) == ["tessellate", *core.MESH_STAGES, "snap"]
    assert run.quality["total_volume"] == pytest.approx(core._hexdom.cad_volume(part), rel=0.01)


def test_core_mesh_surface_reports_the_candidate_hexdom_mesh_kept(core, tmp_path):
    """mount1 defeats autopolycube at lambda 0.1 and its level-1 mesh misses the volume target, so
    `hexdom mesh --method polycube` segments again with lambda 1 and measures the polycube without
    the widths of holes too. _hexdom's mesh_surface reports the candidate it kept (what the
    workbench's Mesh Part sets on its objects) the same as the CLI's "kept:" line, with the CLI's
    mesh. (With auto the overlay mesh is kept on mount1: the polycube's misses the volume.)"""
    raw = _raw("mount1")
    r = _run("mesh", raw, "-o", tmp_path / "m.vtk", "--report", tmp_path / "q.json", "--method", "polycube")
    stderr = r.stderr
    with open(tmp_path / "q.json") as f:
        report = json.load(f)
    run = core.mesh_surface(core.read_surface(raw), method="polycube")
    kept = [line for line in stderr.splitlines() if line.startswith("hexdom: kept: ")]
    assert kept == ["hexdom: kept: polycube path, " + run.choice]
    assert run.edge_weight == pytest.approx(1.0) and run.level == 1
    assert run.keep_widths and run.collapse_apexes
    assert run.choice == "level 1, lambda 1, widths of holes kept"
    assert run.mesh.count(core.HEX) == report["hex"]["count"]
    assert run.quality["hex"]["sj_min"] == pytest.approx(report["hex"]["sj_min"], abs=1e-9)
    # The kept options rebuild its polycube from its labels; the other width option is another one
    # (mount1's holes: 36 walls moved apart, 71 blocks; 68 with the least-squares offsets).
    h = run.polycube.info["cell"] / 2
    same = core.autopolycube(run.labels, size=h, level=run.level, keep_widths=run.keep_widths)
    other = core.autopolycube(run.labels, size=h, level=run.level, keep_widths=not run.keep_widths)
    assert same.info["blocks"] == run.polycube.info["blocks"] and same.info["widened"] > 0
    assert other.info["widened"] == 0 and other.info["blocks"] != same.info["blocks"]


def _pyramid(core, side=4.0, height=3.0, n=16):
    """Closed surface of a square pyramid (base [0, side]^2, apex above its centre), every face
    split into n x n triangles, labels from normals: built here with numpy."""
    a, b, c, d = (np.array(p, float) for p in ((0, 0, 0), (side, 0, 0), (side, side, 0), (0, side, 0)))
    top = np.array([side / 2, side / 2, height])
    V, F = [], []
    for p, q, r in ((a, d, c), (a, c, b), (a, b, top), (b, c, top), (c, d, top), (d, a, top)):
        ids = {}
        for i in range(n + 1):
            for j in range(n + 1 - i):
                ids[i, j] = len(V)
                V.append(p + (q - p) * i / n + (r - p) * j / n)
        for i in range(n):
            for j in range(n - i):
                F.append([ids[i, j], ids[i + 1, j], ids[i, j + 1]])
                if i + j + 1 < n:
                    F.append([ids[i + 1, j], ids[i + 1, j + 1], ids[i, j + 1]])
    V = np.array(V)
    _, first, inverse = np.unique(np.round(V, 9), axis=0, return_index=True, return_inverse=True)
    V, F = V[first], inverse.reshape(-1)[np.array(F)].astype(np.int32)
    nrm = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    axis = np.abs(nrm).argmax(1)
    label = (2 * axis + 1 + (nrm[np.arange(len(F)), axis] < 0)).astype(np.int32)
    return core.Surface(V, F, label)


def test_core_autopolycube_takes_the_candidates_options(core):
    """autopolycube's collapse_apexes and keep_widths reach the core: the pyramid's tip gets tet
    blocks (two per block under the cap) by default and hex blocks only without the collapse; on a
    pyramid, which has no hole, keep_widths moves no wall (widened 0) either way."""
    s = _pyramid(core)
    assert len(s.F) == 6 * 16 * 16
    tets = core.autopolycube(s, size=0.25, level=1)
    hexes = core.autopolycube(s, size=0.25, level=1, collapse_apexes=False)
    assert tets.info["apexes"] == hexes.info["apexes"] == 1
    assert tets.info["apexes_collapsed"] == 1 and hexes.info["apexes_collapsed"] == 0
    assert tets.structure.count(core.TET) > 0 and tets.structure.count(core.TET) % 2 == 0
    assert hexes.structure.count(core.HEX) == len(hexes.structure.types)
    lsq = core.autopolycube(s, size=0.25, level=1, keep_widths=False)
    assert tets.info["widened"] == lsq.info["widened"] == 0
    assert len(lsq.structure.types) == len(tets.structure.types)
    run = core.mesh_surface(s, size=0.25, level=1)
    assert run.collapse_apexes == (run.mesh.count(core.TET) > 0)
    assert run.choice.endswith("tet blocks at apexes" if run.collapse_apexes else "hex blocks under the caps")


def test_core_mesh_surface_meshes_separate_solids_as_regions(core):
    """Two boxes apart in one surface: each meshed on its own, the mesh's region is the solid; VTK
    measures each region's volume and Verdict the cells."""
    a, b = _box(core, 3, 2, 1), _box(core, 1, 1, 2)
    V = np.vstack([a.V, b.V + [5.0, 0.0, 0.0]])
    F = np.vstack([a.F, b.F + len(a.V)]).astype(np.int32)
    run = core.mesh_surface(core.Surface(V, F, np.concatenate([a.patch, b.patch])), size=0.5)
    assert run.solids == 2 and "2 solids" in run.choice
    g = oracle.vtk_grid(run.mesh.V, run.mesh.cells, run.mesh.types)
    vol = np.asarray(oracle.signed_volumes(g))
    region = np.asarray(run.mesh.region)
    assert sorted(set(region.tolist())) == [1, 2]
    assert vol[region == 1].sum() == pytest.approx(6.0) and vol[region == 2].sum() == pytest.approx(2.0)
    sj, _ = oracle.verdict_metrics(g)
    assert sj.min() > 0
