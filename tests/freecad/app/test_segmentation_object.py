"""HexDom Segmentation: patch files, CAD faces as patches, user edits, save and reopen."""

import os

import numpy as np
import pytest

import FreeCAD

from HexDomWorkbench import api, core, make
from HexDomWorkbench.objects import segmentation, tessellation

import fc_testdata
from conftest import reopen

PATCHES = fc_testdata.example_path("lbracket_patches.k")


def box_segmentation(doc, size=2.5):
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = 20.0, 10.0, 5.0
    surf = make.make_surface(doc, source=box, size=size)
    seg = make.make_segmentation(doc, surf, method="Surface patches", name="Seg")
    api.recompute_document(doc, [surf, seg])
    return box, surf, seg


def test_patch_file_loads_the_papers_format(doc):
    seg = api.import_patches(PATCHES, doc)
    assert seg.Proxy.Type == "HexDom::Segmentation" and segmentation.is_segmentation(seg)
    assert seg.Method == "Patch file" and seg.PatchFile == os.path.abspath(PATCHES)
    expected = core.read_surface(PATCHES)
    patches = np.array(seg.Patches)
    labels = segmentation.get_labels(seg)
    np.testing.assert_array_equal(patches, expected.patch)
    assert seg.PatchCount == 17 and seg.TriangleCount == len(expected.F)
    assert sorted(set(labels.tolist())) == [1, 2, 3, 4, 5, 6]
    normals, areas = api.triangle_normals(expected.V, expected.F)
    for p in np.unique(patches).tolist():
        rows = patches == p
        assert len(set(labels[rows].tolist())) == 1, "one label per patch"
        mean = (normals[rows] * areas[rows, None]).sum(axis=0)
        mean /= np.linalg.norm(mean)
        # The axis nearest the patch's mean normal (the ramp of the prism block sits at 45 deg).
        assert mean @ api.AXES[labels[rows][0] - 1] == pytest.approx((api.AXES @ mean).max())
        assert mean @ api.AXES[labels[rows][0] - 1] > 0.7
    s = segmentation.get_surface(seg)
    np.testing.assert_array_equal(s.patch, expected.patch)
    assert list(seg.Issues) == []


def test_cad_faces_as_patches_label_the_box_faces(doc):
    box, surf, seg = box_segmentation(doc)
    s = tessellation.get_surface(surf)
    labels = segmentation.get_labels(seg)
    patches = np.array(seg.Patches)
    assert seg.PatchCount == 6
    np.testing.assert_array_equal(patches, s.patch)
    for k, face in enumerate(box.Shape.Faces, 1):
        n = face.normalAt(0, 0)
        expected = int(api.nearest_label(np.array([[n.x, n.y, n.z]]))[0])
        assert set(labels[s.patch == k].tolist()) == {expected}, "Face{}".format(k)


def adjacent_pair(F, patches):
    """A triangle t and a neighbour u in another patch."""
    for a, b in api.triangle_adjacency(F).tolist():
        if patches[a] != patches[b]:
            return a, b
    raise AssertionError("no patch boundary")


def test_edits_join_the_neighbouring_patch_and_survive_recompute_and_reopen(doc, tmp_path):
    box, surf, seg = box_segmentation(doc)
    s = tessellation.get_surface(surf)
    t, u = adjacent_pair(s.F, s.patch)
    label_u = int(seg.Labels[u])
    api.set_labels(seg, [t], label_u)
    api.recompute_document(doc, [seg])
    assert seg.Labels[t] == label_u and seg.Patches[t] == seg.Patches[u]
    assert seg.EditCount == 1 and list(seg.EditedTriangles) == [t]
    # Setting the same triangle again replaces its edit (labels also by name).
    api.set_labels(seg, [t], api.LABEL_NAMES[label_u])
    seg.touch()
    api.recompute_document(doc, [seg])
    assert list(seg.EditedTriangles) == [t] and seg.Labels[t] == label_u
    labels, patches = list(seg.Labels), list(seg.Patches)
    surf_name = surf.Name
    doc2 = reopen(doc, str(tmp_path / "seg.FCStd"))
    try:
        seg2 = doc2.getObject("Seg")
        assert isinstance(seg2.Proxy, segmentation.Segmentation)
        assert seg2.Surface is doc2.getObject(surf_name)
        assert list(seg2.EditedTriangles) == [t] and list(seg2.EditedLabels) == [label_u]
        assert list(seg2.Labels) == labels and list(seg2.Patches) == patches
        seg2.Surface.touch()
        api.recompute_document(doc2, [seg2.Surface, seg2])
        assert list(seg2.Labels) == labels and list(seg2.Patches) == patches
        api.clear_edits(seg2)
        api.recompute_document(doc2, [seg2])
        assert seg2.Labels[t] != label_u and seg2.EditCount == 0
    finally:
        FreeCAD.closeDocument(doc2.Name)


def test_edit_without_a_neighbour_of_its_label_makes_a_new_patch(doc):
    _, surf, seg = box_segmentation(doc)
    s = tessellation.get_surface(surf)
    labels = segmentation.get_labels(seg)
    # A triangle in the middle of Face1 (-X): no neighbour is +X.
    centroids = s.V[s.F].mean(axis=1)
    rows = np.flatnonzero(s.patch == 1)
    t = int(rows[np.argmin(np.linalg.norm(centroids[rows] - centroids[rows].mean(axis=0),
                                          axis=1))])
    assert labels[t] == 2
    api.set_labels(seg, [t], "+X")
    api.recompute_document(doc, [seg])
    assert seg.Labels[t] == 1 and seg.PatchCount == 7
    assert seg.Patches[t] == 7


def test_stale_edits_are_reported_not_fatal(doc):
    _, surf, seg = box_segmentation(doc)
    seg.EditedTriangles = [10 ** 6]
    seg.EditedLabels = [2]
    api.recompute_document(doc, [seg])
    assert seg.EditCount == 0
    assert any("edits ignored" in issue for issue in seg.Issues)
    seg.EditedLabels = [2, 3]
    with pytest.raises(api.RecomputeError, match="edited labels"):
        api.recompute_document(doc, [seg])
    with pytest.raises(ValueError):
        api.set_labels(seg, [0], 9)
    with pytest.raises(ValueError):
        api.set_labels(seg, [0], "+W")


def test_patch_file_transfers_to_another_triangulation(doc):
    fine = core.read_surface(PATCHES)
    V, F, ids = api.remesh_to_size(fine.V, fine.F, fine.patch, 0.9)
    assert len(F) > 2 * len(fine.F)
    surf = make.make_surface(doc, surface=core.Surface(V, F, np.zeros(len(F), np.int32)))
    seg = make.make_segmentation(doc, surf, method="Patch file", patch_file=PATCHES)
    api.recompute_document(doc, [surf, seg])
    agree = np.mean(np.array(seg.Patches) == ids)
    assert agree > 0.97, agree
    assert seg.PatchCount == 17


def test_automatic_method(doc):
    box, surf, seg = box_segmentation(doc)
    seg.Method = "Automatic"
    if not api.has_segmentation():
        with pytest.raises(api.RecomputeError, match="segmentation not available in this build"):
            api.recompute_document(doc, [seg])
        with pytest.raises(core.Error, match="segmentation not available in this build"):
            api.segment(tessellation.get_surface(surf))
        return
    api.recompute_document(doc, [seg])
    labels = segmentation.get_labels(seg)
    assert labels.min() >= 1 and labels.max() <= 6 and seg.PatchCount == 6
    # A box: every CAD face is one patch with the label of its normal.
    s = tessellation.get_surface(surf)
    for k, face in enumerate(box.Shape.Faces, 1):
        n = face.normalAt(0, 0)
        expected = int(api.nearest_label(np.array([[n.x, n.y, n.z]]))[0])
        assert set(labels[s.patch == k].tolist()) == {expected}, "Face{}".format(k)
    # Edits are fixed labels for the CVT and survive the recompute.
    t = int(np.flatnonzero(s.patch == 1)[0])
    api.set_labels(seg, [t], "+Z")
    api.recompute_document(doc, [seg])
    assert seg.Labels[t] == 5 and seg.EditCount == 1


def test_missing_surface_link_fails_with_a_message(doc):
    seg = doc.addObject("App::FeaturePython", "Lonely")
    segmentation.Segmentation(seg)
    with pytest.raises(api.RecomputeError, match="link a HexDom Surface"):
        api.recompute_document(doc, [seg])


def test_add_properties_is_idempotent(doc):
    _, surf, seg = box_segmentation(doc)
    for obj in (surf, seg):
        names = sorted(obj.PropertiesList)
        obj.Proxy.add_properties(obj)
        assert sorted(obj.PropertiesList) == names
