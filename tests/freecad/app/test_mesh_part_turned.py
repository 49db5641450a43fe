"""Mesh Part on a part lying at an angle (issue 9): an angle bracket placed 45 degrees about Z, as
it may sit in an assembly. Mesh Part finds the frame its faces fit (core.cube_frame), puts it on the
Segmentation's Frame, and the Segmentation and the automatic Polycube work in it: the Mesh is the one
`hexdom mesh` gives on the same shape, the one the bracket gets square to the axes. Before, the
turned bracket had no polycube (its faces lean between two labels; `hexdom mesh --no-align` still
fails there).

Oracles: `_hexdom`'s own path (core.mesh_part, what `hexdom mesh` runs) on the BREP FreeCAD holds,
VTK's Verdict on the mesh FreeCAD holds (FemMesh read back), FreeCAD's Rotation and volume."""

import os
import sys

import numpy as np
import pytest

import FreeCAD
import Part

import HexDomWorkbench as hexdom
from HexDomWorkbench import api, core
from HexDomWorkbench.objects import segmentation

from conftest import reopen

_here = os.environ.get("HEXDOM_FC_TEST_DIR") or os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(_here, "app"))
sys.path.insert(0, os.path.join(_here, "..", "python"))
import hexdom_oracles as oracles  # noqa: E402  (VTK's Verdict)
from test_mesh_part_prisms import _verdict_of  # noqa: E402  (FemMesh -> VTK grid, SMDS orders)

pytestmark = pytest.mark.skipif(not api.has_cad(), reason="_hexdom built without OpenCASCADE")


def _bracket(turned):
    V = FreeCAD.Vector
    shape = Part.makeBox(60, 40, 8).fuse(Part.makeBox(8, 40, 40)).removeSplitter()
    shape = shape.cut(Part.makeCylinder(6, 20, V(-5, 20, 26), V(1, 0, 0)))
    if turned:
        shape.rotate(V(0, 0, 0), V(0, 0, 1), 45)
    return shape


def _counts(types):
    return tuple(int(np.sum(types == t)) for t in (oracles.HEX, oracles.WEDGE, oracles.TET))


def _mesh_part(doc, shape, name):
    part = doc.addObject("Part::Feature", name)
    part.Shape = shape
    doc.recompute()
    objs = hexdom.mesh_part(doc, part)
    objs["part"] = part
    return objs


def test_mesh_part_meshes_a_turned_bracket_in_the_frame_of_its_faces(doc, tmp_path):
    shape = _bracket(True)
    objs = _mesh_part(doc, shape, "Turned")
    seg, poly, mesh = objs["segmentation"], objs["polycube"], objs["mesh"]
    # The shape as the document holds it (its turn in a location): what the Surface tessellates.
    brep = objs["part"].Shape.exportBrepToString()
    # The frame is on the Segmentation, as an ordinary Rotation: 45 degrees about Z (either sense
    # undoes the turn of a part with a cube's symmetry of its faces).
    assert seg.Frame.Angle == pytest.approx(np.pi / 4, abs=1e-6)
    assert abs(seg.Frame.Axis.z) == pytest.approx(1.0, abs=1e-6)
    # `hexdom mesh`'s path on the same shape at the same size.
    size = float(poly.Size.Value)  # the turned box's diagonal / 30, not the model's box's
    assert size == pytest.approx(api.part_size(shape), rel=1e-4)
    assert size < shape.BoundBox.DiagonalLength / 30.0 * 0.95
    # The Segmentation holds the frame `hexdom mesh` found (a Rotation property: cube_frame's matrix
    # to within 1e-16); meshing in that frame given explicitly labels the same triangles, but the
    # improvement's searches can turn its last bits into a hundredth of worst SJ, so the mesh is
    # compared with `hexdom mesh`'s own run.
    frame = segmentation.frame_matrix(seg)
    cli = core.mesh_part(brep, size=size, allow_inverted=True)
    fit = cli.frame
    assert fit["turned"] and np.allclose(fit["rotation"], frame, rtol=0, atol=1e-12)
    run = core.mesh_part(brep, size=size, allow_inverted=True, frame=frame)
    assert objs["surface"].TriangleCount == len(run.labels.F) == len(cli.labels.F)
    run = cli
    types_cli = np.asarray(run.mesh.types)
    sj_cli, _ = oracles.verdict_metrics(oracles.vtk_grid(run.mesh.V, run.mesh.cells, run.mesh.types))
    sj, types, g = _verdict_of(mesh)
    FreeCAD.Console.PrintMessage("turned bracket: Mesh Part {} worst hex SJ {:.4f}; _hexdom {} {:.4f} ({})\n".format(
        _counts(types), sj[types == oracles.HEX].min(), _counts(types_cli),
        sj_cli[types_cli == oracles.HEX].min(), run.choice))
    assert _counts(types) == _counts(types_cli)
    # The Mesh object generates and improves again from the Polycube the document holds, so its
    # nodes enter the snap's restoration off `hexdom mesh`'s in their last bits; the restoration
    # (one run since d205498, none of the progressive snap's two more that evened it out) carries
    # that into the worst SJ by a few thousandths: measured 0.9362 against 0.9320.
    assert sj[types == oracles.HEX].min() == pytest.approx(sj_cli[types_cli == oracles.HEX].min(), abs=1e-2)
    assert np.all(sj > 0) and mesh.InvertedCount == 0
    assert sj[types == oracles.HEX].min() >= 0.3
    assert float(np.sum(oracles.signed_volumes(g))) == pytest.approx(shape.Volume, rel=0.01)
    # The polycube built in the frame: as many blocks as the bracket square to the axes gets.
    square = _mesh_part(doc, _bracket(False), "Square")
    assert segmentation.frame_matrix(square["segmentation"]) is None
    assert poly.HexBlocks == square["polycube"].HexBlocks
    assert mesh.HexCount == square["mesh"].HexCount
    # The frame is saved with the document.
    name = seg.Name
    doc2 = reopen(doc, str(tmp_path / "turned.FCStd"))
    try:
        assert doc2.getObject(name).Frame.Angle == pytest.approx(np.pi / 4, abs=1e-6)
    finally:
        FreeCAD.closeDocument(doc2.Name)


def test_the_frame_reaches_segment_and_autopolycube(doc, monkeypatch):
    """The Segmentation's Frame reaches core.segment and core.autopolycube; set back to the identity,
    the turned bracket is recomputed in the model's axes, where its faces lean between two labels:
    another polycube (or none: the stage at fault is reported), the objects kept."""
    seen = []
    real_segment, real_auto = core.segment, core.autopolycube

    def spy_segment(surface, **kw):
        seen.append(("segment", kw.get("frame") is not None))
        return real_segment(surface, **kw)

    def spy_auto(labels, **kw):
        seen.append(("autopolycube", kw.get("frame") is not None))
        return real_auto(labels, **kw)

    objs = _mesh_part(doc, _bracket(True), "Turned")
    monkeypatch.setattr(core, "segment", spy_segment)
    monkeypatch.setattr(core, "autopolycube", spy_auto)
    seg = objs["segmentation"]
    objs["mesh"].Pipeline = False  # stage by stage: the objects call the core's stages
    seg.touch()
    api.recompute_document(doc, [o for k, o in objs.items() if k != "part"])
    assert seen == [("segment", True), ("autopolycube", True)]
    assert objs["mesh"].InvertedCount == 0
    blocks = (objs["polycube"].HexBlocks, objs["polycube"].PrismBlocks, objs["polycube"].TetBlocks)
    seen.clear()
    seg.Frame = FreeCAD.Rotation()
    assert segmentation.frame_matrix(seg) is None
    try:
        api.recompute_document(doc, [o for k, o in objs.items() if k != "part"])
        other = (objs["polycube"].HexBlocks, objs["polycube"].PrismBlocks, objs["polycube"].TetBlocks)
        FreeCAD.Console.PrintMessage("turned bracket in the model's axes: blocks {} (in its frame {})\n".format(
            other, blocks))
        assert other != blocks
    except api.RecomputeError as e:
        FreeCAD.Console.PrintMessage("turned bracket in the model's axes: {}\n".format(e))
    assert seen and all(not framed for _, framed in seen)
    assert all(doc.getObject(o.Name) is not None for o in objs.values())
    for key in ("surface", "segmentation"):
        assert "Invalid" not in objs[key].State and "Error" not in objs[key].State



def test_the_stages_rebuild_the_turned_bracket_s_mesh_exactly(doc):
    """The Frame is a quaternion; the Segmentation also keeps the pipeline's rotation to the last
    digit (FrameMatrix): the Segmentation and Polycube edited (an input set again) and computed as
    stages give the pipeline's polycube and mesh exactly (with the quaternion's rotation they
    differed by 1e-5 in the blocks and 0.8 in the mesh: the optimiser spreads the difference). The
    Frame edited by hand is taken as it is."""
    objs = _mesh_part(doc, _bracket(True), "Turned")
    seg, poly, mesh = objs["segmentation"], objs["polycube"], objs["mesh"]
    assert np.array_equal(segmentation.frame_matrix(seg),
                          core.mesh_part(objs["part"].Shape.exportBrepToString()).frame["rotation"])
    points = np.array([tuple(p) for p in poly.Points])
    nodes = mesh.FemMesh.Nodes
    first = np.array([tuple(nodes[n]) for n in sorted(nodes)])
    seg.EdgeWeight = float(seg.EdgeWeight)
    poly.KeepWidths = poly.KeepWidths
    api.recompute_document(doc, [o for k, o in objs.items() if k != "part"])
    assert not seg.FromPipeline and not mesh.Pipeline
    assert np.array_equal(np.array([tuple(p) for p in poly.Points]), points)
    nodes = mesh.FemMesh.Nodes
    assert np.array_equal(np.array([tuple(nodes[n]) for n in sorted(nodes)]), first)
    turned = FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), -40)
    seg.Frame = turned
    m = turned.toMatrix()
    assert np.allclose(segmentation.frame_matrix(seg), [[m.A11, m.A12, m.A13], [m.A21, m.A22, m.A23],
                                                        [m.A31, m.A32, m.A33]], rtol=0, atol=1e-15)
