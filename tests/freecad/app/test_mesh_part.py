"""Mesh Part (issue 9, workbench side): api.mesh_part builds HexDom Surface -> Segmentation ->
Polycube (Mode Automatic) -> Mesh from a Part solid with no manual step; every object stays in the
document, is saved and restored, and can be edited (an automatic Polycube switched to Manual keeps
its blocks). A stage that fails names itself and keeps the finished objects.

Oracles: OpenCASCADE's volume of the part (Part.Shape.Volume), VTK's Verdict on the mesh FreeCAD
itself writes (FemMesh.write, FreeCAD's VTK exporter), CalculiX through the FEM workbench.
"""

import os
import shutil
import sys

import numpy as np
import pytest

import FreeCAD
import Part

import HexDomWorkbench as hexdom
from HexDomWorkbench import api, core, progress
from HexDomWorkbench.objects import hex_mesh, polycube

import fc_testdata
from conftest import reopen

_here = os.environ.get("HEXDOM_FC_TEST_DIR") or os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(_here, "..", "python"))
import hexdom_oracles as oracles  # noqa: E402  (VTK's Verdict)

BRACKET = fc_testdata.example_path("bracket.step")


def _part(doc, shape, name="Part"):
    obj = doc.addObject("Part::Feature", name)
    obj.Shape = shape
    doc.recompute()
    return obj


def _box(doc, L=40.0, W=20.0, H=10.0):
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = L, W, H
    doc.recompute()
    return box


def _verdict_of(obj, tmp_path):
    """Verdict's scaled Jacobian per cell, the VTK cell types and the grid of the mesh as FreeCAD
    writes it itself (FemMesh.write to Abaqus .inp, read back by meshio: node orders of C3D8, C3D6
    and C3D4 are VTK's)."""
    import meshio
    path = str(tmp_path / (obj.Name + ".inp"))
    obj.FemMesh.write(path)
    m = meshio.read(path)
    vtk_type = {"hexahedron": oracles.HEX, "wedge": oracles.WEDGE, "tetra": oracles.TET}
    cells, types = [], []
    for block in m.cells:
        if block.type not in vtk_type:
            continue
        for row in block.data:
            cells.append(list(row) + [-1] * (8 - len(row)))
            types.append(vtk_type[block.type])
    g = oracles.vtk_grid(m.points, np.array(cells, np.int64), np.array(types))
    sj, _ = oracles.verdict_metrics(g)
    return sj, np.array(types), g


def test_mesh_part_bracket_step(doc, tmp_path):
    """The shipped STEP bracket (hole, fillet): four valid objects, an automatic polycube, a mesh
    with no inverted cell, worst hex SJ >= 0.3 by Verdict, volume within 1% of the B-rep's."""
    shape = Part.read(BRACKET)
    part = _part(doc, shape, "Bracket")
    objs = hexdom.mesh_part(doc, part, level=1)
    assert set(objs) == {"surface", "segmentation", "polycube", "mesh"}
    for key, type_name in (("surface", "HexDom::Surface"), ("segmentation", "HexDom::Segmentation"),
                           ("polycube", "HexDom::Polycube"), ("mesh", "HexDom::Mesh")):
        obj = objs[key]
        assert obj.Proxy.Type == type_name
        assert "Invalid" not in obj.State and "Error" not in obj.State, obj.getStatusString()
        assert obj.Label == "Bracket_" + key
    surface, seg, poly, mesh = (objs[k] for k in ("surface", "segmentation", "polycube", "mesh"))
    size = shape.BoundBox.DiagonalLength / 30.0
    assert surface.Source == part and surface.Size.Value == pytest.approx(size)
    assert surface.FaceCount == len(shape.Faces)  # every CAD face has triangles
    assert seg.Method == "Automatic" and seg.PatchCount >= 6
    assert poly.Mode == "Automatic" and poly.Segmentation == seg
    assert poly.HexBlocks > 0 and len(poly.PatchTriangles) > 0
    assert poly.CellSize == pytest.approx(size * 2, rel=1e-6)  # h = size * 2^level
    assert poly.InvertedBlocks == 0
    assert mesh.Polycube == poly and mesh.Segmentation == seg and mesh.Level == poly.Level == 1
    # Independent checks: Verdict on FreeCAD's own export, OCCT's volume.
    sj, types, g = _verdict_of(mesh, tmp_path)
    hexes = types == oracles.HEX
    assert hexes.sum() == mesh.HexCount > 0 and len(types) == mesh.FemMesh.VolumeCount
    assert np.all(sj > 0), "inverted cells: {}".format(int(np.sum(sj <= 0)))
    assert sj[hexes].min() >= 0.3, "worst hex SJ {:.3f}".format(sj[hexes].min())
    assert sj[hexes].min() == pytest.approx(mesh.MinHexSJ, abs=1e-6)
    volume = float(np.sum(oracles.signed_volumes(g)))
    brep = sum(s.Volume for s in shape.Solids)  # Part.read's compound may count it twice
    assert volume == pytest.approx(brep, rel=0.01), (volume, brep)
    FreeCAD.Console.PrintMessage(
        "bracket.step: {} hex, {} prism, {} tet; worst hex SJ {:.3f}, mean {:.3f}; volume "
        "{:+.3f}%\n".format(mesh.HexCount, mesh.PrismCount, mesh.TetCount, mesh.MinHexSJ,
                            mesh.MeanHexSJ, 100.0 * (volume - brep) / brep))


def _wedge():
    # Triangle (0,0)-(40,0)-(0,20) in XZ extruded 30 along Y: a 26.6 degree knife edge at x = 40.
    V = FreeCAD.Vector
    return Part.Face(Part.makePolygon([V(0, 0, 0), V(40, 0, 0), V(0, 0, 20), V(0, 0, 0)])).extrude(V(0, 30, 0))


def _chamfered_box():
    box = Part.makeBox(40, 30, 20)
    return box.makeChamfer(6, [e for e in box.Edges if abs(e.Length - 30) < 1e-6][:2])


@pytest.mark.parametrize("make", [_wedge, _chamfered_box], ids=["wedge", "chamfer"])
def test_mesh_part_wedge_like_features(doc, tmp_path, make):
    """Faces at 26.6 and 45 degrees to the axes: the labelling repair puts a strip of a third axis
    along the knife edge, and the mesh is valid, worst hex SJ >= 0.3 (Verdict), volume within 1%."""
    shape = make()
    objs = hexdom.mesh_part(doc, _part(doc, shape, make.__name__.strip("_")), level=1)
    mesh = objs["mesh"]
    sj, types, g = _verdict_of(mesh, tmp_path)
    assert np.all(sj > 0), "inverted cells: {}".format(int(np.sum(sj <= 0)))
    assert sj[types == oracles.HEX].min() >= 0.3, "worst hex SJ {:.3f}".format(sj[types == oracles.HEX].min())
    assert float(np.sum(oracles.signed_volumes(g))) == pytest.approx(shape.Volume, rel=0.01)


def test_level_follows_the_polycube(doc):
    """Once a stage is edited (the Mesh leaves Pipeline), the Mesh's Level is an expression of
    the Polycube's: the blocks are made for it."""
    objs = api.make_mesh_part(doc, _box(doc), level=2)
    assert objs["polycube"].Level == 2
    objs["polycube"].Level = 1
    doc.recompute()
    assert objs["mesh"].Level == 1


def test_save_reopen_and_switch_to_manual(doc, tmp_path):
    """Saved and reopened, every stage keeps its data; switching the Polycube to Manual keeps
    its blocks and patch surface, and the Mesh recomputes to the same mesh from them."""
    objs = hexdom.mesh_part(doc, _box(doc), size=2.5, level=1)
    names = {k: o.Name for k, o in objs.items()}
    structure = polycube.get_structure(objs["polycube"])
    patches = polycube.get_patch_surface(objs["polycube"])
    labels = list(objs["segmentation"].Labels)
    counts = (objs["mesh"].HexCount, objs["mesh"].PrismCount, objs["mesh"].TetCount)
    nodes = objs["mesh"].FemMesh.NodeCount
    assert counts[0] == 16 * 8 * 4 and objs["mesh"].InvertedCount == 0  # 40x20x10 at 2.5
    doc2 = reopen(doc, str(tmp_path / "mesh_part.FCStd"))
    try:
        o = {k: doc2.getObject(n) for k, n in names.items()}
        assert isinstance(o["polycube"].Proxy, polycube.Polycube)
        assert o["polycube"].Mode == "Automatic" and o["polycube"].Segmentation == o["segmentation"]
        np.testing.assert_array_equal(polycube.get_structure(o["polycube"]).cells, structure.cells)
        np.testing.assert_allclose(polycube.get_structure(o["polycube"]).V, structure.V)
        back = polycube.get_patch_surface(o["polycube"])
        np.testing.assert_array_equal(back.F, patches.F)
        np.testing.assert_array_equal(back.patch, patches.patch)
        assert list(o["segmentation"].Labels) == labels
        assert (o["mesh"].HexCount, o["mesh"].PrismCount, o["mesh"].TetCount) == counts
        assert o["mesh"].FemMesh.NodeCount == nodes
        # The pipeline's Level is the Mesh's own (`hexdom mesh --level`).
        assert o["mesh"].Pipeline and not [e for p, e in o["mesh"].ExpressionEngine
                                           if p == "Level"]
        # Manual: the blocks stay even if the segmentation changes; the Mesh is built from the
        # stages from now on, its Level following the Polycube's.
        o["polycube"].Mode = "Manual"
        o["segmentation"].touch()
        api.recompute_document(doc2)
        assert not o["mesh"].Pipeline and not o["polycube"].FromPipeline
        assert [e for p, e in o["mesh"].ExpressionEngine if p == "Level"] == [
            names["polycube"] + ".Level"]
        np.testing.assert_array_equal(polycube.get_structure(o["polycube"]).cells, structure.cells)
        assert polycube.has_patch_surface(o["polycube"])
        assert (o["mesh"].HexCount, o["mesh"].PrismCount, o["mesh"].TetCount) == counts
        # Back to Automatic: rebuilt from the segmentation, same result for the same input.
        o["polycube"].Mode = "Automatic"
        o["polycube"].Size = 5.0
        api.recompute_document(doc2)
        assert o["polycube"].HexBlocks == 4 * 2 * 1 and o["mesh"].HexCount == 8 * 4 * 2
    finally:
        FreeCAD.closeDocument(doc2.Name)


def test_a_file_structure_clears_the_patch_surface(doc):
    """Reading a structure file into an automatic Polycube (set Manual) drops the automatic
    patch surface: a file's blocks go with the Segmentation's patches."""
    objs = hexdom.mesh_part(doc, _box(doc), size=5.0, level=1)
    poly = objs["polycube"]
    assert polycube.has_patch_surface(poly)
    poly.Mode = "Manual"
    poly.SourceFile = fc_testdata.example_path("lbracket_structure.k")
    poly.recompute()
    assert not polycube.has_patch_surface(poly) and poly.HexBlocks == 3


def test_failure_names_the_stage_and_keeps_the_objects(doc):
    """A part the automatic polycube cannot take, with Method polycube (auto meshes it with the
    overlay grid: test_mesh_part_method.py): the error names the stage and the core's reason,
    the Surface and Segmentation stay valid, nothing is removed."""
    # A tetrahedron: no face is near an axis plane, every corner joins three slanted faces.
    pts = [FreeCAD.Vector(*p) for p in ((0, 0, 0), (10, 1, 2), (3, 9, 1), (4, 3, 11))]
    faces = [Part.Face(Part.makePolygon([pts[a], pts[b], pts[c], pts[a]]))
             for a, b, c in ((0, 2, 1), (0, 1, 3), (1, 2, 3), (2, 0, 3))]
    part = _part(doc, Part.makeSolid(Part.makeShell(faces)), "Tet")
    before = len(doc.Objects)
    with pytest.raises(api.MeshPartError) as info:
        hexdom.mesh_part(doc, part, size=20.0, level=2, method="polycube")
    e = info.value
    FreeCAD.Console.PrintMessage("mesh_part on a tetrahedron: {}\n".format(e))
    assert len(doc.Objects) == before + 4
    assert set(e.objects) == {"surface", "segmentation", "polycube", "mesh"}
    assert e.stage == "automatic polycube"
    assert "Tet failed at automatic polycube (Tet_mesh)" in str(e)
    assert "chart" in str(e)  # the core's reason names the chart at fault
    for key in ("surface", "segmentation"):
        assert "Invalid" not in e.objects[key].State, e.objects[key].getStatusString()
    assert len(e.objects["segmentation"].Labels) == e.objects["surface"].TriangleCount


def test_bad_input_adds_nothing(doc):
    face = _part(doc, Part.makePlane(10, 10), "Sheet")
    before = len(doc.Objects)
    with pytest.raises(ValueError, match="Sheet: select a Part solid"):
        hexdom.mesh_part(doc, face)
    assert len(doc.Objects) == before


def test_progress_cancel_without_gui():
    """Without the GUI, Progress.run calls directly; after cancel() the next stage does not start
    and raises Cancelled (a core.Error), in nested Progress blocks too."""
    calls = []
    with progress.Progress("outer", 2) as outer:
        assert outer.run("a", lambda x: calls.append(x) or x * 2, 21) == 42
        with progress.Progress("inner", 1) as inner:
            assert inner.session is outer
            inner.cancel()
            with pytest.raises(progress.Cancelled, match="cancelled by the user before b"):
                inner.run("b", calls.append, 1)
        assert outer.is_cancelled()
    assert calls == [21] and issubclass(progress.Cancelled, core.Error)
    assert progress.current() is None


@pytest.mark.skipif(not api.core_has("snap_to_brep"),
                    reason="core.snap_to_brep not in this build (issue 9 B-rep snapping pending)")
def test_boundary_nodes_snapped_onto_the_cad_faces(doc):
    """With core.snap_to_brep, the final boundary nodes of a curved part lie on its CAD faces:
    within 1e-7 of the bounding-box diagonal, measured by OCCT's distance to the faces."""
    part = _part(doc, Part.read(BRACKET), "Bracket")
    objs = hexdom.mesh_part(doc, part, level=1)
    mesh = objs["mesh"]
    diag = part.Shape.BoundBox.DiagonalLength
    assert 0 <= mesh.BrepDistance <= 1e-7 * diag
    hole = [f for f in part.Shape.Faces if f.Surface.__class__.__name__ == "Cylinder"]
    assert hole, "the bracket has a cylindrical hole face"
    on_hole = mesh.FemMesh.getNodesByFace(hole[0])  # FEM's own search, 1e-7 tolerance
    assert len(on_hole) > 0


@pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX ccx not on PATH")
def test_mesh_part_bar_solves_in_calculix(doc, tmp_path):
    """A bar meshed by Mesh Part, fixed at x = 0 and pulled at x = L through FEM constraints on
    its CAD faces: CalculiX's end displacement within 2% of F L / (E A)."""
    import fc_fem
    from HexDomWorkbench.convert import fem_setup
    L, W, H, E, F = 100.0, 10.0, 10.0, 210000.0, 1000.0
    box = _box(doc, L, W, H)
    objs = hexdom.mesh_part(doc, box, size=2.5, level=1)
    mesh = objs["mesh"]
    assert mesh.InvertedCount == 0 and mesh.HexCount > 0
    analysis, solver, _ = fc_fem.static_analysis(doc, E, 0.3, [(box, "Face1")], [(box, "Face2")], F,
                                                 (box, ["Face2"]))
    fem_setup.add_to_analysis(analysis, mesh)
    doc.recompute()
    n_fixed = len(mesh.FemMesh.getNodesByFace(box.Shape.Faces[0]))
    n_load = len(mesh.FemMesh.getNodesByFace(box.Shape.Faces[1]))
    assert n_fixed > 0 and n_load > 0
    work = tmp_path / "ccx"
    work.mkdir()
    disp = fc_fem.solve(fc_fem.write_inp(analysis, solver, work), analysis)
    tip = mesh.FemMesh.getNodesByFace(box.Shape.Faces[1])
    u = float(np.mean([disp[n][0] for n in tip]))
    theory = F * L / (E * W * H)
    FreeCAD.Console.PrintMessage("mesh part bar: {} hex, u = {:.6g}, theory {:.6g} ({:+.2f}%), "
                                 "{} fixed / {} loaded nodes\n".format(
                                     mesh.HexCount, u, theory, 100 * (u - theory) / theory,
                                     n_fixed, n_load))
    assert u == pytest.approx(theory, rel=0.02)


def test_snap_to_brep_wiring(doc, monkeypatch):
    """Until core.snap_to_brep lands the Mesh does not snap (BrepDistance -1); with it, the Mesh
    hands it its final mesh, the Part's BREP text and the Surface's tessellation with the CAD face
    ids, uses the mesh it returns and reports its max_distance. A stand-in records the call."""
    box = _box(doc)
    if not api.core_has("snap_to_brep"):
        objs = hexdom.mesh_part(doc, box, size=5.0, level=1)
        assert objs["mesh"].BrepDistance == -1.0
    calls, ratios = [], []

    def fake_snap(mesh, source, surface, solid=0, max_edge_ratio=0.0):
        calls.append((mesh, source, surface, solid))
        ratios.append(max_edge_ratio)
        moved = core.Mesh(mesh.V + 0.0, mesh.cells, mesh.types, mesh.region)
        moved.V[0] += 1e-3  # so the test sees that the returned mesh is the one stored
        return moved, {"max_distance": 2.5e-9}

    monkeypatch.setattr(core, "snap_to_brep", fake_snap, raising=False)
    monkeypatch.setattr(core._hexdom, "snap_to_brep", fake_snap, raising=False)
    assert api.core_has("snap_to_brep")
    # Stage by stage (the pipeline snaps inside the core): the Mesh out of Pipeline.
    objs = api.make_mesh_part(doc, box, size=5.0, level=1)
    objs["mesh"].Pipeline = False
    objs["surface"].Size = objs["polycube"].Size = 5.0
    api.recompute_document(doc, list(objs.values()))
    mesh = objs["mesh"]
    assert len(calls) == 1
    assert ratios == [core.TARGET_EDGE_RATIO]  # the pipeline's edge-ratio target, as `hexdom mesh` snaps
    given, source, surface, solid = calls[0]
    assert "CASCADE Topology" in source and solid == 0
    assert sorted(set(np.asarray(surface.patch).tolist())) == list(range(1, 7))  # Face1..Face6
    assert len(surface.F) == objs["surface"].TriangleCount
    assert mesh.BrepDistance == pytest.approx(2.5e-9)
    stored = hex_mesh.get_mesh(mesh)
    np.testing.assert_allclose(stored.V[0], given.V[0] + 1e-3, atol=1e-12)
    mesh.SnapToCAD = False
    mesh.touch()
    api.recompute_document(doc, [mesh])
    assert len(calls) == 1 and mesh.BrepDistance == -1.0
