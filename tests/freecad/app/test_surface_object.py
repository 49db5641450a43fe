"""HexDom Surface: tessellation of Part solids with CAD face ids, files, save and reopen."""

import math

import numpy as np
import pytest

import FreeCAD
import Part

from HexDomWorkbench import api, core, make
from HexDomWorkbench.objects import tessellation

import fc_testdata
from conftest import reopen


def add_box(doc, L=20.0, W=10.0, H=5.0, name="Box"):
    box = doc.addObject("Part::Box", name)
    box.Length, box.Width, box.Height = L, W, H
    doc.recompute()
    return box


def test_box_tessellation_keeps_cad_faces(doc):
    box = add_box(doc)
    obj = make.make_surface(doc, source=box, size=2.0)
    api.recompute_document(doc, [obj])
    assert obj.Proxy.Type == "HexDom::Surface" and tessellation.is_surface(obj)
    assert obj.Method == "core" or obj.Method.startswith("MeshPart")
    surface = tessellation.get_surface(obj)
    assert obj.TriangleCount == len(surface.F) and obj.PointCount == len(surface.V)
    assert obj.FaceCount == 6 and sorted(set(surface.patch.tolist())) == [1, 2, 3, 4, 5, 6]
    # Triangle t lies on Face<FaceId[t]> of the box.
    centroids = surface.V[surface.F].mean(axis=1)
    for k, face in enumerate(box.Shape.Faces, start=1):
        on_face = centroids[surface.patch == k]
        dist = [face.distToShape(Part.Vertex(FreeCAD.Vector(*c)))[0]
                for c in on_face[:: max(1, len(on_face) // 20)]]
        assert max(dist) < 1e-6, "Face{}".format(k)
    uses, volume, area = fc_testdata.closed_surface_checks(surface.V, surface.F)
    assert uses == {2}, "closed and conforming"
    assert volume == pytest.approx(1000.0, rel=1e-9), "outward orientation"
    assert area == pytest.approx(700.0, rel=1e-9)
    lengths = fc_testdata.edge_lengths(surface.V, surface.F)
    assert lengths.max() <= 1.5 * 2.0 and np.median(lengths) > 0.5 * 2.0, "edges near Size"


def test_curved_faces_stay_within_deflection(doc):
    cyl = doc.addObject("Part::Cylinder", "Cylinder")
    cyl.Radius, cyl.Height = 3.0, 10.0
    doc.recompute()
    obj = make.make_surface(doc, source=cyl, size=1.0, deflection=0.02, angle=10.0)
    api.recompute_document(doc, [obj])
    s = tessellation.get_surface(obj)
    lateral = [k for k, f in enumerate(cyl.Shape.Faces, 1)
               if f.Surface.TypeId == "Part::GeomCylinder"]
    assert len(lateral) == 1
    side = s.V[np.unique(s.F[s.patch == lateral[0]])]
    r = np.hypot(side[:, 0], side[:, 1])
    centroids = s.V[s.F[s.patch == lateral[0]]].mean(axis=1)
    rc = np.hypot(centroids[:, 0], centroids[:, 1])
    assert r.max() <= 3.0 + 1e-6 and r.min() >= 3.0 - 0.02 - 1e-6
    assert rc.min() >= 3.0 - 0.02 - 1e-6
    uses, volume, _ = fc_testdata.closed_surface_checks(s.V, s.F)
    assert uses == {2}
    assert volume == pytest.approx(math.pi * 9.0 * 10.0, rel=0.01)
    assert fc_testdata.edge_lengths(s.V, s.F).max() <= 1.5 * 1.0


def test_size_change_retessellates(doc):
    box = add_box(doc)
    obj = make.make_surface(doc, source=box, size=4.0)
    api.recompute_document(doc, [obj])
    coarse = obj.TriangleCount
    obj.Size = 1.0
    api.recompute_document(doc, [obj])
    assert obj.TriangleCount > 4 * coarse
    box.Length = 30.0
    api.recompute_document(doc, [obj])
    s = tessellation.get_surface(obj)
    _, volume, _ = fc_testdata.closed_surface_checks(s.V, s.F)
    assert volume == pytest.approx(1500.0, rel=1e-9), "follows the source part"


def test_save_reopen_keeps_triangles_and_link(doc, tmp_path):
    box = add_box(doc)
    obj = make.make_surface(doc, source=box, size=3.0, name="Surf")
    api.recompute_document(doc, [obj])
    before = tessellation.get_surface(obj)
    doc2 = reopen(doc, str(tmp_path / "surface.FCStd"))
    try:
        obj2 = doc2.getObject("Surf")
        assert isinstance(obj2.Proxy, tessellation.Surface)
        assert obj2.Source is doc2.getObject("Box")
        assert obj2.Size.Value == 3.0 and obj2.Angle.Value == 20.0
        after = tessellation.get_surface(obj2)
        np.testing.assert_array_equal(after.V, before.V)  # doubles, bit for bit
        np.testing.assert_array_equal(after.F, before.F)
        np.testing.assert_array_equal(after.patch, before.patch)
        obj2.touch()
        api.recompute_document(doc2, [obj2])
        assert obj2.TriangleCount == len(before.F)
    finally:
        FreeCAD.closeDocument(doc2.Name)


def test_surface_from_file_uses_part_ids(doc):
    path = fc_testdata.example_path("lbracket_patches.k")
    obj = make.make_surface(doc, path=path)
    api.recompute_document(doc, [obj])
    expected = core.read_surface(path)
    s = tessellation.get_surface(obj)
    assert obj.Method == "file" and obj.FaceCount == 17
    np.testing.assert_array_equal(s.F, expected.F)
    np.testing.assert_array_equal(s.patch, expected.patch)


def test_stored_surface_without_source(doc):
    expected = core.read_surface(fc_testdata.example_path("lbracket_patches.k"))
    obj = make.make_surface(doc, surface=expected)
    api.recompute_document(doc, [obj])
    assert obj.Method == "stored" and obj.TriangleCount == len(expected.F)


def test_source_without_faces_fails_with_a_message(doc):
    empty = doc.addObject("Part::Feature", "Point")
    empty.Shape = Part.Vertex(FreeCAD.Vector(0, 0, 0))
    obj = make.make_surface(doc, source=empty)
    with pytest.raises(api.RecomputeError, match="has no faces"):
        api.recompute_document(doc, [obj])
    with pytest.raises(ValueError, match="no faces"):
        api.tessellate(Part.Shape())


def test_meshpart_triangles_are_well_shaped():
    """The MeshPart fallback gives near-equilateral triangles, also around holes."""
    shape = Part.makeBox(30, 12, 6).cut(Part.makeCylinder(2.5, 6, FreeCAD.Vector(20, 6, 0)))
    s = api.tessellate(shape, size=1.0, method="meshpart")
    V, F = s.V, s.F
    corners = [V[F[:, i]] for i in range(3)]

    def angle(p, q, r):
        u, v = q - p, r - p
        return np.degrees(np.arctan2(np.linalg.norm(np.cross(u, v), axis=1),
                                     np.einsum("ij,ij->i", u, v)))
    smallest = np.minimum.reduce([angle(corners[i], corners[(i + 1) % 3], corners[(i + 2) % 3])
                                  for i in range(3)])
    assert np.median(smallest) > 45.0 and np.percentile(smallest, 5) > 20.0
    uses, volume, _ = fc_testdata.closed_surface_checks(V, F)
    assert uses == {2} and volume == pytest.approx(shape.Volume, rel=2e-3)
    assert sorted(set(s.patch.tolist())) == list(range(1, len(shape.Faces) + 1))


def test_standard_mesher_fallback_remeshes_to_size():
    # MeshPart's standard mesher gives a box 12 needle triangles; the core remeshes them onto
    # themselves: near-equilateral triangles of about the size, each on its own face.
    shape = Part.makeBox(20, 10, 5)
    from HexDomWorkbench import shape_tessellation
    V, F, ids = shape_tessellation._tessellate_standard(shape, 2.0, 0.2, 20.0)
    uses, volume, _ = fc_testdata.closed_surface_checks(V, F)
    assert uses == {2} and volume == pytest.approx(1000.0, rel=1e-9)
    lengths = fc_testdata.edge_lengths(V, F)
    assert lengths.max() <= 1.5 * 2.0 and 1.2 <= np.median(lengths) <= 2.6
    assert sorted(set(ids.tolist())) == [1, 2, 3, 4, 5, 6]
    normals, _ = api.triangle_normals(V, F)
    for k, face in enumerate(shape.Faces, 1):  # every triangle on the plane of its FreeCAD face
        n = face.normalAt(0, 0)
        n = np.array([n.x, n.y, n.z])
        assert np.all(normals[ids == k] @ n > 1 - 1e-9)
        assert np.ptp(V[F[ids == k]].reshape(-1, 3) @ n) < 1e-9
    corners = [V[F[:, i]] for i in range(3)]
    angles = []
    for i in range(3):
        u, w = corners[(i + 1) % 3] - corners[i], corners[(i + 2) % 3] - corners[i]
        angles.append(np.degrees(np.arctan2(np.linalg.norm(np.cross(u, w), axis=1), np.einsum("ij,ij->i", u, w))))
    assert np.min(angles) > 20.0  # the standard mesher's needles are gone


def test_remesh_of_an_open_surface_names_the_edge():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    F = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3]], np.int32)  # a tetrahedron without one face
    with pytest.raises(core.InputError, match=r"open: edge \(\d, \d\) has one triangle"):
        api.remesh_to_size(V, F, np.ones(3, np.int32), 0.2)


def test_too_small_size_is_refused():
    with pytest.raises(ValueError, match="too small"):
        api.tessellate(Part.makeBox(10, 10, 10), size=0.01)


def test_core_and_meshpart_agree_on_face_ids():
    if not api.has_cad():
        pytest.skip("core.tessellate_brep not in this build: MeshPart only")
    shape = Part.makeBox(10, 6, 4)
    a = api.tessellate(shape, size=2.0, method="core")
    b = api.tessellate(shape, size=2.0, method="meshpart")
    for s in (a, b):
        normals, areas = api.triangle_normals(s.V, s.F)
        for k, face in enumerate(shape.Faces, 1):
            n = face.normalAt(0, 0)
            assert np.all(normals[s.patch == k] @ np.array([n.x, n.y, n.z]) > 0.999)
