"""What the Edit Patches and Build Polycube panels write into a document, driven without a GUI:
the Segmentation's patch edits that the Edit Patches panel writes on OK, and a structure built
over a Segmentation of a Part. The editors themselves (PatchEditor, PolycubeBuilder) need no
FreeCAD: tests/python/test_workbench_logic.py drives them."""

import os
import sys

import numpy as np

import FreeCAD

from HexDomWorkbench import api, core, make
from HexDomWorkbench.logic.patch_editing import PatchEditor
from HexDomWorkbench.logic.polycube_building import PolycubeBuilder
from HexDomWorkbench.objects import segmentation

import fc_testdata
from conftest import reopen

sys.path.insert(0, os.path.join(os.environ.get("HEXDOM_FC_TEST_DIR") or os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "..", "python"))
import hexdom_test_support as support  # noqa: E402  (the planted island, shared with tests/python)

PATCHES = fc_testdata.example_path("lbracket_patches.k")


# ------------------------------------------------------------------------------------------------
# Edit Patches


def test_patch_edits_of_a_segmentation_survive_recompute_and_reopening(doc, tmp_path):
    seg = api.import_patches(PATCHES, doc)
    s = segmentation.get_surface(seg)
    e = PatchEditor(s.V, s.F, s.patch, seg.Labels)
    planted = support.island(e)
    seg.EditedPatchTriangles = planted.tolist()
    seg.EditedPatchIds = [40] * len(planted)
    seg.EditedTriangles = planted.tolist()
    seg.EditedLabels = [e.patch_label(5)] * len(planted)
    api.recompute_document(doc, [seg])
    patches = np.array(seg.Patches)
    assert set(patches[planted].tolist()) == {40} and seg.PatchCount == 18
    assert len(seg.Issues) == 3
    name = seg.Name
    seg = reopen(doc, str(tmp_path / "edits.FCStd")).getObject(name)
    assert list(seg.EditedPatchIds) == [40] * len(planted)
    seg.touch()
    seg.Document.recompute()
    assert set(np.array(seg.Patches)[planted].tolist()) == {40}
    api.clear_edits(seg)
    seg.Document.recompute()
    assert seg.PatchCount == 17 and list(seg.Issues) == [] and list(seg.EditedPatchIds) == []
    FreeCAD.closeDocument(seg.Document.Name)


def test_bad_patch_edits_are_reported_not_applied(doc):
    seg = api.import_patches(PATCHES, doc)
    seg.EditedPatchTriangles = [0, 10 ** 7]
    seg.EditedPatchIds = [3, 3]
    api.recompute_document(doc, [seg])
    assert any("1 patch edits ignored" in i for i in seg.Issues)
    assert seg.Patches[0] == 3


# ------------------------------------------------------------------------------------------------
# Build Polycube


def test_box_of_eight_blocks_needs_its_centre_vertex(doc):
    """A 2 x 2 x 2 box: every face split in four by its CAD faces; the eight hex blocks share one
    interior vertex, added at the centroid of two opposite corners."""
    import Part
    boxes = [Part.makeBox(5, 5, 5, FreeCAD.Vector(5 * i, 5 * j, 5 * k))
             for i in (0, 1) for j in (0, 1) for k in (0, 1)]
    part = doc.addObject("Part::Feature", "Box8")
    part.Shape = boxes[0].fuse(boxes[1:])
    surf = make.make_surface(doc, source=part, size=1.5)
    seg = make.make_segmentation(doc, surf, method="Surface patches")
    api.recompute_document(doc, [surf, seg])
    assert seg.PatchCount == 24 and list(seg.Issues) == []
    s = segmentation.get_surface(seg)
    b = PolycubeBuilder(s)
    assert b.corner_count == 26

    def at(p):
        v, d = b.nearest_vertex(p)
        assert d < 1e-6
        return v

    centre = b.add_vertex_at_centroid([at((0, 0, 0)), at((10, 10, 10))])
    np.testing.assert_allclose(b.points[centre], (5, 5, 5))
    for i in (0, 1):
        for j in (0, 1):
            for k in (0, 1):
                b.add_block([at((5 * (i + a), 5 * (j + c), 5 * (k + d)))
                             for a in (0, 1) for c in (0, 1) for d in (0, 1)])
    assert b.counts()["hex"] == 8 and b.problems() == []
    assert sum(centre in verts for _, verts in b.blocks) == 8
    mesh = core.improve(core.generate(s, b.structure(), level=1), s)
    assert mesh.count(core.HEX) == 64 and core.quality_report(mesh)["hex"]["inverted"] == 0


