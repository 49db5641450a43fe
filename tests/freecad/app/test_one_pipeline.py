"""One pipeline behind every front end (issue "Mesh Part gives the mesh `hexdom mesh` gives"): Mesh
Part in FreeCAD and `hexdom mesh` on the same part give the same mesh, with either meshing path,
and changing the Mesh's Level or Size and recomputing gives `hexdom mesh --level / --size`'s.

Parts: the bundled bracket, the 9 CAD parts of HEXDOM_DATA/cad (skipped with the reason when
absent) and 10 parts of our own corpus (bench/make_corpus.py, one of each of 10 families, made
here). The program reads the BREP text FreeCAD holds (shape.exportBrepToString() written to a
file): FreeCAD's STEP import is not bit for bit OCCT's, so the same file would not be the same
shape (test_mesh_part_choice.py). Both run without the polycube path's time budget
(--polycube-seconds 0, PolycubeSeconds 0), whose end depends on the machine's speed.

Oracles: the program's .vtu file read by VTK, Verdict's scaled Jacobian on it and on the FEM mesh
FreeCAD holds (read through FemMesh's API), node coordinates compared to 1e-12 of the part's
size."""

import json
import os
import subprocess
import sys
import tempfile

import numpy as np
import pytest

import FreeCAD
import Part

import HexDomWorkbench as hexdom
from HexDomWorkbench import api, core
from HexDomWorkbench.objects import hex_mesh

import fc_testdata

_here = os.environ.get("HEXDOM_FC_TEST_DIR") or os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(_here, "app"))
sys.path.insert(0, os.path.join(_here, "..", "python"))
import hexdom_oracles as oracles  # noqa: E402  (VTK's Verdict)
from test_mesh_part_prisms import _verdict_of  # noqa: E402  (FemMesh -> VTK grid, SMDS orders)

REPO = os.path.abspath(os.path.join(_here, "..", ".."))
CLI = os.environ.get("HEXDOM_CLI", "")
CAD = os.path.join(fc_testdata.data_root(), "cad")
CAD_PARTS = ["i01o_m1.step", "i10o_simp.step", "i11o_s1.step", "n11o_limit_cycle.stp",
             "s09o_bridge.step", "s11o_cube_cyl.stp", "s12o_cube_rounded_1.stp",
             "s14o_cube_corner_sub_sphere.stp", "s15o_cylinder.stp"]
# One part of each: about a second each, five by the polycube path and five by the overlay grid.
CORPUS_FAMILIES = ["plate_holes", "bracket_l", "bracket_t", "plate_slots", "loft", "angled",
                   "tangent", "cone", "counterbore", "ribbed"]

pytestmark = [
    pytest.mark.skipif(not api.has_cad(), reason="_hexdom built without OpenCASCADE"),
    pytest.mark.skipif(not (CLI and os.access(CLI, os.X_OK)),
                       reason="HEXDOM_CLI (the hexdom program; tests/freecad/run.sh sets it) not "
                              "set or not executable: {!r}".format(CLI)),
]

PATHS_SEEN = set()


@pytest.fixture(scope="module")
def corpus():
    """Directory of the 10 corpus parts (bench/make_corpus.py, seeded: the same parts each run)."""
    out = tempfile.mkdtemp(prefix="hexdom-one-pipeline-")
    subprocess.run([sys.executable if os.path.basename(sys.executable).startswith("python")
                    else "/usr/bin/python3", os.path.join(REPO, "bench", "make_corpus.py"), out,
                    "--count", str(len(CORPUS_FAMILIES)), "--no-fixed",
                    "--families", ",".join(CORPUS_FAMILIES)],
                   check=True, capture_output=True, text=True, timeout=300)
    return out


def _shape_of(spec, corpus_dir):
    kind, name = spec
    if kind == "bracket":
        return Part.read(fc_testdata.example_path("bracket.step"))
    if kind == "cad":
        path = os.path.join(CAD, name)
        if not os.path.isfile(path):
            pytest.skip("{} not found under HEXDOM_DATA ({}): set HEXDOM_DATA".format(name, CAD))
        return Part.read(path)
    return Part.read(os.path.join(corpus_dir, name + ".step"))


def _cli_mesh(shape, tmp_path, *args):
    """`hexdom mesh` on the BREP text of ``shape``: (points, cells as node lists, VTK types,
    Verdict SJ per cell, quality report)."""
    brep = tmp_path / "part.brep"
    brep.write_text(shape.exportBrepToString())
    out, report = tmp_path / "cli.vtu", tmp_path / "cli.json"
    r = subprocess.run([CLI, "mesh", str(brep), "-o", str(out), "--allow-inverted",
                        "--polycube-seconds", "0", "--report", str(report)] + list(args),
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    g, sj, types = oracles.vtu_sj_types(str(out))
    P, _, cells = oracles.grid_arrays(g)
    method = "overlay" if "kept: overlay path" in r.stderr + r.stdout else "polycube"
    return P, cells, types, sj, json.loads(report.read_text()), method


def _fc_mesh(mesh):
    """The FEM mesh FreeCAD holds: (points by node id, cells as node lists in VTK order, VTK
    types, Verdict SJ per cell)."""
    sj, types, g = _verdict_of(mesh)
    P, _, cells = oracles.grid_arrays(g)
    return P, cells, types, sj


def _assert_same(fc, cli, diagonal):
    P, cells, types, sj = fc
    Pc, cells_c, types_c, sj_c = cli[:4]
    for t in (oracles.HEX, oracles.WEDGE, oracles.TET):
        assert int(np.sum(types == t)) == int(np.sum(types_c == t))
    assert P.shape == Pc.shape
    assert float(np.abs(P - Pc).max(initial=0.0)) <= 1e-12 * diagonal
    assert cells == cells_c
    for t in (oracles.HEX, oracles.WEDGE, oracles.TET):
        if np.any(types == t):
            assert sj[types == t].min() == pytest.approx(sj_c[types_c == t].min(), abs=1e-12)


PARTS = ([("bracket", "bracket")] + [("cad", name) for name in CAD_PARTS]
         + [("corpus", family + "_000") for family in CORPUS_FAMILIES])


@pytest.mark.parametrize("spec", PARTS, ids=[name for _, name in PARTS])
def test_mesh_part_is_the_mesh_hexdom_mesh_gives(doc, tmp_path, corpus, spec):
    """Cell counts per type, node coordinates (1e-12 of the diagonal), connectivity and worst SJ
    per type of Mesh Part's mesh are `hexdom mesh`'s; the part is meshed once (the Surface,
    Segmentation and Polycube hold what the pipeline made, none of them recomputed)."""
    shape = _shape_of(spec, corpus)
    part = doc.addObject("Part::Feature", spec[1])
    part.Shape = shape
    doc.recompute()
    cli = _cli_mesh(part.Shape, tmp_path)
    objs = hexdom.mesh_part(doc, part, allow_inverted=True, polycube_seconds=0)
    mesh = objs["mesh"]
    _assert_same(_fc_mesh(mesh), cli, part.Shape.BoundBox.DiagonalLength)
    assert mesh.MeshingPath == cli[5] and mesh.Pipeline
    PATHS_SEEN.add(mesh.MeshingPath)
    for key in ("surface", "segmentation", "polycube"):
        o = objs[key]
        assert o.FromPipeline and "Touched" not in o.State and "Invalid" not in o.State
    assert objs["surface"].TriangleCount > 0
    if mesh.MeshingPath == "polycube":
        assert mesh.Polycube == objs["polycube"] and objs["polycube"].HexBlocks > 0
        assert len(objs["segmentation"].Labels) == objs["surface"].TriangleCount
    else:
        assert mesh.Polycube is None
    inverted = sum(cli[4][t]["inverted"] for t in ("hex", "prism", "tet"))
    assert mesh.InvertedCount == inverted


def test_both_paths_were_compared():
    """The parts above cover the polycube path and the overlay grid (the issue's "either path")."""
    if len(PATHS_SEEN) < 2:
        pytest.skip("the comparisons did not run (or were skipped): {}".format(PATHS_SEEN))
    assert PATHS_SEEN == {"polycube", "overlay"}


def test_level_size_and_method_edits_give_hexdom_mesh_with_those_options(doc, tmp_path):
    """Changing the Mesh's Level, Size or Method and recomputing runs the pipeline again with
    them: the mesh `hexdom mesh --level / --size / --method` gives; the stage objects follow."""
    part = doc.addObject("Part::Feature", "Bracket")
    part.Shape = Part.read(fc_testdata.example_path("bracket.step"))
    doc.recompute()
    diagonal = part.Shape.BoundBox.DiagonalLength
    objs = hexdom.mesh_part(doc, part, allow_inverted=True, polycube_seconds=0)
    mesh = objs["mesh"]
    first = mesh.HexCount
    for name, value, args in (("Level", 0, ["--level", "0"]),
                              ("Size", 4.0, ["--level", "0", "--size", "4"]),
                              ("Method", "overlay", ["--level", "0", "--size", "4",
                                                     "--method", "overlay"])):
        setattr(mesh, name, value)
        api.recompute_document(doc, [mesh])
        assert mesh.Pipeline and "Invalid" not in mesh.State
        cli = _cli_mesh(part.Shape, tmp_path, *args)
        _assert_same(_fc_mesh(mesh), cli, diagonal)
        assert mesh.MeshingPath == cli[5]
        assert all(objs[k].FromPipeline for k in ("surface", "segmentation", "polycube"))
    assert mesh.HexCount != first
    assert mesh.Polycube is None and objs["polycube"].HexBlocks == 0  # no polycube attempt
    # Size 4 reached the Surface's tessellation (triangles of about that size).
    assert objs["surface"].Size.Value == pytest.approx(4.0)


def test_an_edited_stage_rebuilds_the_mesh_from_the_stages(doc):
    """Editing the Polycube (an input property) makes the chain compute stage by stage: the
    Polycube rebuilds from the Segmentation's labels (not segmented again), the Mesh leaves
    Pipeline and is generated from the new blocks; setting Pipeline again gives `hexdom mesh`'s
    mesh back."""
    part = doc.addObject("Part::Feature", "Bracket")
    part.Shape = Part.read(fc_testdata.example_path("bracket.step"))
    doc.recompute()
    objs = hexdom.mesh_part(doc, part, allow_inverted=True, polycube_seconds=0)
    mesh, poly, seg = objs["mesh"], objs["polycube"], objs["segmentation"]
    first = _fc_mesh(mesh)
    labels = list(seg.Labels)
    blocks = poly.HexBlocks
    poly.KeepWidths = not poly.KeepWidths
    poly.Size = 2 * poly.Size.Value
    api.recompute_document(doc, list(objs.values()))
    assert not mesh.Pipeline and not poly.FromPipeline and not seg.FromPipeline
    assert list(seg.Labels) == labels
    assert poly.HexBlocks < blocks and "Invalid" not in mesh.State
    assert mesh.HexCount >= poly.HexBlocks * 8 ** mesh.Level and mesh.HexCount < len(first[2])
    mesh.Pipeline = True
    api.recompute_document(doc, list(objs.values()))
    again = _fc_mesh(mesh)
    assert mesh.Pipeline and poly.HexBlocks == blocks and seg.FromPipeline
    np.testing.assert_array_equal(again[0], first[0])
    assert again[1] == first[1]


def test_a_document_saved_in_pipeline_mode_reopens_without_meshing_again(doc, tmp_path):
    """Saved and reopened, Mesh Part's objects hold their data and are up to date; a recompute of
    the Mesh gives the same mesh (the pipeline again)."""
    from conftest import reopen
    part = doc.addObject("Part::Feature", "Bracket")
    part.Shape = Part.read(fc_testdata.example_path("bracket.step"))
    doc.recompute()
    objs = hexdom.mesh_part(doc, part, polycube_seconds=0)
    names = {k: o.Name for k, o in objs.items()}
    first = hex_mesh.get_mesh(objs["mesh"])
    doc2 = reopen(doc, str(tmp_path / "pipeline.FCStd"))
    try:
        o = {k: doc2.getObject(n) for k, n in names.items()}
        assert o["mesh"].Pipeline and all(o[k].FromPipeline for k in ("surface", "segmentation",
                                                                        "polycube"))
        np.testing.assert_array_equal(hex_mesh.get_mesh(o["mesh"]).V, first.V)
        o["mesh"].touch()
        api.recompute_document(doc2, [o["mesh"]])
        np.testing.assert_array_equal(hex_mesh.get_mesh(o["mesh"]).V, first.V)
        assert o["mesh"].Pipeline
    finally:
        FreeCAD.closeDocument(doc2.Name)


def _max_edge_ratio(fc):
    P, cells, types, _ = fc
    hexes = np.array([c for c, t in zip(cells, types) if t == oracles.HEX])
    return float(oracles.edge_ratios(P[hexes], oracles.HEX).max())


def test_a_thin_part_s_stages_rebuild_it_stretched(doc):
    """A plate 100 x 40 x 1 with its top edges chamfered 0.5 is thin: the pipeline segments it,
    builds its polycube and generates it stretched along its thickness (cells of a different length
    along each axis; docs/sizing.md). The Segmentation holds the stretch (Stretch): the Mesh built
    from the stages, and the Segmentation and Polycube computed again after an edit, give the
    pipeline's mesh. With Stretch (1, 1, 1) the chamfers take other labels and the cells get twice
    as long for their thickness."""
    box = Part.makeBox(100, 40, 1.0)
    part = doc.addObject("Part::Feature", "Plate")
    part.Shape = box.makeChamfer(0.5, [e for e in box.Edges
                                       if e.BoundBox.ZLength < 1e-9 and e.BoundBox.ZMin > 0.5])
    doc.recompute()
    objs = hexdom.mesh_part(doc, part, allow_inverted=True, polycube_seconds=0)
    mesh, seg, poly = objs["mesh"], objs["segmentation"], objs["polycube"]
    assert mesh.MeshingPath == "polycube"
    stretch = tuple(seg.Stretch)
    assert max(stretch) > 2 and min(stretch) == 1.0, stretch
    first = _fc_mesh(mesh)
    diagonal = part.Shape.BoundBox.DiagonalLength
    ratio = _max_edge_ratio(first)
    assert ratio < 7
    # The Mesh out of Pipeline: generated and improved from the Polycube, stretched.
    mesh.Pipeline = False
    mesh.touch()
    api.recompute_document(doc, [mesh])
    _assert_same(_fc_mesh(mesh), first + (None, None), diagonal)
    # The Segmentation edited (an input set again): it and the Polycube compute as stages.
    labels, blocks = list(seg.Labels), poly.HexBlocks
    seg.EdgeWeight = float(seg.EdgeWeight)
    poly.KeepWidths = poly.KeepWidths
    api.recompute_document(doc, list(objs.values()))
    assert not seg.FromPipeline and not poly.FromPipeline and not mesh.Pipeline
    assert list(seg.Labels) == labels and poly.HexBlocks == blocks
    _assert_same(_fc_mesh(mesh), first + (None, None), diagonal)
    # Without the stretch the stages make the long thin cells the stretch avoids.
    seg.Stretch = (1.0, 1.0, 1.0)
    api.recompute_document(doc, list(objs.values()))
    assert list(seg.Labels) != labels
    assert _max_edge_ratio(_fc_mesh(mesh)) > 1.5 * ratio


@pytest.mark.parametrize("name", ["bracket", "cone_000"])
def test_stage_by_stage_on_the_pipeline_s_stages_is_the_pipeline_s_mesh(doc, corpus, name):
    """The Mesh out of Pipeline, recomputed from the stages the pipeline filled (generation,
    improvement and snap from the Polycube; the overlay grid on the Surface), makes the mesh the
    pipeline made: the stages get the options it used. The bracket's mesh comes from the polycube
    path, cone_000's from the overlay grid."""
    spec = ("bracket", "bracket") if name == "bracket" else ("corpus", name)
    part = doc.addObject("Part::Feature", name)
    part.Shape = _shape_of(spec, corpus)
    doc.recompute()
    objs = hexdom.mesh_part(doc, part, allow_inverted=True, polycube_seconds=0)
    mesh = objs["mesh"]
    first, path = _fc_mesh(mesh), mesh.MeshingPath
    assert path == ("polycube" if name == "bracket" else "overlay")
    mesh.Pipeline = False
    mesh.touch()
    api.recompute_document(doc, [mesh])
    assert not mesh.Pipeline and mesh.MeshingPath == path
    _assert_same(_fc_mesh(mesh), first + (None, None), part.Shape.BoundBox.DiagonalLength)


def test_the_time_limit_ends_the_meshing_like_a_stage_failure(doc):
    """TimeLimit (`hexdom mesh --time-limit`, 1800 s by default): a recompute that runs past it
    fails as a stage does, naming the step and the limit, and leaves the mesh it had."""
    part = doc.addObject("Part::Feature", "Bracket")
    part.Shape = Part.read(fc_testdata.example_path("bracket.step"))
    doc.recompute()
    objs = hexdom.mesh_part(doc, part, allow_inverted=True, polycube_seconds=0)
    mesh = objs["mesh"]
    assert mesh.TimeLimit == core.MESH_OPTIONS["time_limit"] == 1800
    before = _fc_mesh(mesh)
    mesh.Method, mesh.Size, mesh.TimeLimit = "overlay", 0.8, 0.5  # several seconds of work
    with pytest.raises(api.RecomputeError, match=r"time limit of the run\): stopped after the time budget of 0.5 s"):
        api.recompute_document(doc, [mesh])
    assert "Invalid" in mesh.State or "Error" in mesh.State
    np.testing.assert_array_equal(_fc_mesh(mesh)[0], before[0])


def test_pillowed_curves_are_the_mesh_hexdom_mesh_pillow_curves_gives(doc, tmp_path):
    """PillowCurves (`hexdom mesh --pillow-curves`) on the bracket with Method overlay: Mesh Part's
    mesh is the program's, with wedges along the CAD edges; recomputed from the stages (Pipeline
    off: the overlay grid on the Surface) it is the same mesh again."""
    part = doc.addObject("Part::Feature", "Bracket")
    part.Shape = Part.read(fc_testdata.example_path("bracket.step"))
    doc.recompute()
    cli = _cli_mesh(part.Shape, tmp_path, "--method", "overlay", "--pillow-curves")
    objs = hexdom.mesh_part(doc, part, allow_inverted=True, polycube_seconds=0, method="overlay")
    mesh = objs["mesh"]
    assert mesh.PillowCurves is False and mesh.PrismCount == 0
    mesh.PillowCurves = True
    api.recompute_document(doc, [mesh])
    diagonal = part.Shape.BoundBox.DiagonalLength
    first = _fc_mesh(mesh)
    _assert_same(first, cli, diagonal)
    assert mesh.MeshingPath == "overlay" and mesh.PrismCount > 0 and mesh.InvertedCount == 0
    mesh.Pipeline = False
    mesh.touch()
    api.recompute_document(doc, [mesh])
    assert not mesh.Pipeline
    _assert_same(_fc_mesh(mesh), first + (None, None), diagonal)
