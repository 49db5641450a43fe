"""Mesh Part and the two meshing paths (issue 19, workbench part): the Mesh object says which path
made it (MeshingPath: polycube or overlay; PolycubeNote: why the core's automatic choice tried the
overlay grid), its Method (auto, polycube, overlay) forces one and recompute honours it; when the
overlay grid made the mesh, the Segmentation and the Polycube stay in the document, editable, and
the Mesh no longer depends on the Polycube (which may fail). Documents saved before Method,
MeshingPath and PolycubeNote load and recompute as before.

Oracles: `_hexdom`'s own path on the shape FreeCAD holds (core.mesh_part on its BREP text: what
`hexdom mesh --method ...` runs), FreeCAD's FemMesh (its own VolumeCount), VTK's Verdict on the
cells read through FemMesh's API, OpenCASCADE's volume.

Measured: a torus (Part.makeTorus(30, 10)) at element size 10: the overlay grid's mesh (47,425 hex,
volume -0.17%, after the snap) is kept by the automatic choice over the polycube's. The tetrahedron
of test_mesh_part.py at size 20, level 2: the automatic polycube fails ("chart 1 ... has no
neighbour with another label to join"), the overlay grid meshes it (with the spreading of crowded
nodes on, OverlayOptions::spread_passes, it kept 5 cells just inverted)."""

import os
import sys

import numpy as np
import pytest

import FreeCAD
import Part

import HexDomWorkbench as hexdom
from HexDomWorkbench import api, core
from HexDomWorkbench.objects import hex_mesh, polycube

import fc_testdata
from conftest import reopen

_here = os.environ.get("HEXDOM_FC_TEST_DIR") or os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(_here, "app"))
sys.path.insert(0, os.path.join(_here, "..", "python"))
import hexdom_oracles as oracles  # noqa: E402  (VTK's Verdict)

BRACKET = fc_testdata.example_path("bracket.step")
TORUS_SIZE = 10.0
NEW_PROPERTIES = ("Method", "MeshingPath", "PolycubeNote")

needs_cad = pytest.mark.skipif(not api.has_cad(), reason="_hexdom built without OpenCASCADE")


def _part(doc, shape, name):
    obj = doc.addObject("Part::Feature", name)
    obj.Shape = shape
    doc.recompute()
    return obj


def _box(doc, L=40.0, W=20.0, H=10.0):
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = L, W, H
    doc.recompute()
    return box


def _tetrahedron():
    # No face near an axis plane, every corner joins three slanted faces (test_mesh_part.py's).
    pts = [FreeCAD.Vector(*p) for p in ((0, 0, 0), (10, 1, 2), (3, 9, 1), (4, 3, 11))]
    faces = [Part.Face(Part.makePolygon([pts[a], pts[b], pts[c], pts[a]]))
             for a, b, c in ((0, 2, 1), (0, 1, 3), (1, 2, 3), (2, 0, 3))]
    return Part.makeSolid(Part.makeShell(faces))


def _counts(mesh):
    return (mesh.HexCount, mesh.PrismCount, mesh.TetCount)


def _run_counts(run):
    return tuple(run.mesh.count(t) for t in (core.HEX, core.WEDGE, core.TET))


def _valid(obj):
    return "Invalid" not in obj.State and "Error" not in obj.State and "Touched" not in obj.State


def _verdict_of(obj):
    """Verdict's scaled Jacobian per cell, the VTK cell types and the VTK grid of the FEM mesh
    FreeCAD holds, read through FemMesh's API as test_mesh_part_prisms reads it (SMDS node orders:
    hexa VTK = smds[0,3,2,1,4,7,6,5], penta = VTK, tetra VTK = smds[0,2,1,3]), with FemMesh.Nodes
    read once (each read builds the whole dict)."""
    fm = obj.FemMesh
    nodes = fm.Nodes
    order = sorted(nodes)
    ids = {nid: i for i, nid in enumerate(order)}
    P = np.array([[nodes[n].x, nodes[n].y, nodes[n].z] for n in order])
    perms = {8: ([0, 3, 2, 1, 4, 7, 6, 5], oracles.HEX), 6: (list(range(6)), oracles.WEDGE),
             4: ([0, 2, 1, 3], oracles.TET)}
    cells, types = [], []
    for e in fm.Volumes:
        element = fm.getElementNodes(e)
        perm, t = perms[len(element)]
        cells.append([ids[element[i]] for i in perm] + [-1] * (8 - len(perm)))
        types.append(t)
    g = oracles.vtk_grid(P, np.array(cells, np.int64), np.array(types))
    sj, _ = oracles.verdict_metrics(g)
    return sj, np.array(types), g


def _check_fem_mesh(mesh, shape, rel=0.01):
    """The FEM mesh FreeCAD holds: one volume per cell the object counts, no inverted cell by
    Verdict, the volume of the part within ``rel``."""
    assert mesh.FemMesh.VolumeCount == sum(_counts(mesh)) > 0
    sj, types, g = _verdict_of(mesh)
    assert len(types) == mesh.FemMesh.VolumeCount
    assert np.all(sj > 0), "inverted cells: {}".format(int(np.sum(sj <= 0)))
    volume = float(np.sum(oracles.signed_volumes(g)))
    assert volume == pytest.approx(shape.Volume, rel=rel), (volume, shape.Volume)
    return sj, types


@needs_cad
def test_method_overlay_on_a_box(doc):
    """Method overlay: no Polycube is made, the Mesh meshes the Segmentation's Surface with the
    overlay grid, says so, and is the mesh `hexdom mesh --method overlay` makes of the shape; a
    recompute makes it again; Method polycube gives `hexdom mesh --method polycube`'s mesh, and
    stage by stage (Pipeline off) forcing the polycube without a Polycube names what is missing."""
    box = _box(doc)
    objs = hexdom.mesh_part(doc, box, size=5.0, method="overlay")
    assert set(objs) == {"surface", "segmentation", "mesh"}
    mesh = objs["mesh"]
    assert mesh.Method == "overlay" and mesh.MeshingPath == "overlay" and mesh.PolycubeNote == ""
    assert mesh.Polycube is None and mesh.Segmentation == objs["segmentation"]
    assert all(_valid(o) for o in objs.values())
    run = core.mesh_part(box.Shape.exportBrepToString(), size=5.0, method="overlay")
    assert run.method == "overlay" and run.polycube_note == ""
    assert _counts(mesh) == _run_counts(run)
    assert mesh.FemMesh.VolumeCount == len(run.mesh.types)
    _check_fem_mesh(mesh, box.Shape)
    assert mesh.InvertedCount == 0 and 0 <= mesh.BrepDistance <= 1e-7 * box.Shape.BoundBox.DiagonalLength
    counts, nodes = _counts(mesh), mesh.FemMesh.NodeCount
    mesh.touch()
    api.recompute_document(doc, [mesh])
    assert _counts(mesh) == counts and mesh.FemMesh.NodeCount == nodes
    # Method polycube: the pipeline's polycube path (`hexdom mesh --method polycube`), with no
    # Polycube object to fill; stage by stage there is none to mesh from.
    mesh.Method = "polycube"
    api.recompute_document(doc, [mesh])
    assert mesh.MeshingPath == "polycube" and mesh.HexCount > 0 and mesh.InvertedCount == 0
    mesh.Pipeline = False
    with pytest.raises(api.RecomputeError, match="link both a Segmentation and a Polycube"):
        api.recompute_document(doc, [mesh])


@needs_cad
def test_method_auto_keeps_the_polycube_on_the_bracket(doc):
    """The shipped bracket: the automatic choice keeps the polycube mesh, as `hexdom mesh` does;
    the Mesh uses the Polycube and says so."""
    shape = Part.read(BRACKET)
    part = _part(doc, shape, "Bracket")
    objs = hexdom.mesh_part(doc, part, level=1)
    mesh, poly = objs["mesh"], objs["polycube"]
    assert mesh.Method == "auto" and mesh.MeshingPath == "polycube"
    assert mesh.Polycube == poly and all(_valid(o) for o in objs.values())
    run = core.mesh_part(shape.exportBrepToString(), size=shape.BoundBox.DiagonalLength / 30.0,
                         allow_inverted=True)
    assert run.method == "polycube"
    assert mesh.PolycubeNote == run.polycube_note
    assert _counts(mesh) == _run_counts(run)
    assert mesh.FemMesh.VolumeCount == sum(_counts(mesh))


@needs_cad
def test_torus_auto_gives_the_overlay_mesh_and_says_so(doc, tmp_path):
    """A torus at element size 8: the polycube mesh misses the volume by 6.75%, the automatic
    choice keeps the overlay grid's. Mesh Part gives that mesh (the one core.mesh_part gives the
    shape), MeshingPath "overlay", PolycubeNote the core's reason; the Polycube stays valid and
    editable but unused. Saved and reopened, a recompute gives the overlay mesh again. Method
    polycube (the Polycube linked again) gives the polycube mesh, Method overlay the overlay
    mesh once more."""
    torus = _part(doc, Part.makeTorus(30, 10), "Torus")
    objs = hexdom.mesh_part(doc, torus, size=TORUS_SIZE)
    mesh, poly, seg = objs["mesh"], objs["polycube"], objs["segmentation"]
    run = core.mesh_part(torus.Shape.exportBrepToString(), size=TORUS_SIZE, allow_inverted=True)
    FreeCAD.Console.PrintMessage("torus at {}: {} {} ({})\n".format(
        TORUS_SIZE, run.method, _run_counts(run), run.polycube_note))
    assert run.method == "overlay" and "volume" in run.polycube_note
    assert mesh.Method == "auto" and mesh.MeshingPath == "overlay"
    assert mesh.PolycubeNote == run.polycube_note
    assert _counts(mesh) == _run_counts(run) and mesh.InvertedCount == 0
    _check_fem_mesh(mesh, torus.Shape)
    assert 0 <= mesh.BrepDistance <= 1e-7 * torus.Shape.BoundBox.DiagonalLength
    # The Polycube is kept, valid and editable, but the Mesh does not depend on it.
    assert poly.Document == doc and _valid(poly) and poly.Segmentation == seg
    assert poly.Mode == "Automatic" and poly.HexBlocks > 0
    assert mesh.Polycube is None and poly not in mesh.OutList
    assert not [e for p, e in mesh.ExpressionEngine if p == "Level"]
    api.check_mesh_part(objs)
    counts = _counts(mesh)
    names = {k: o.Name for k, o in objs.items()}
    doc2 = reopen(doc, str(tmp_path / "torus_overlay.FCStd"))
    try:
        o = {k: doc2.getObject(n) for k, n in names.items()}
        mesh = o["mesh"]
        assert (mesh.Method, mesh.MeshingPath) == ("auto", "overlay")
        assert mesh.PolycubeNote == run.polycube_note and _counts(mesh) == counts
        for obj in o.values():
            obj.touch()
        api.recompute_document(doc2, list(o.values()))
        assert mesh.MeshingPath == "overlay" and _counts(mesh) == counts
        # Forcing the polycube: the Polycube linked again meshes the part.
        mesh.Method = "polycube"
        mesh.Polycube = o["polycube"]
        api.recompute_document(doc2, [mesh])
        assert mesh.MeshingPath == "polycube" and mesh.PolycubeNote == ""
        assert mesh.HexCount > 0 and mesh.InvertedCount == 0 and _counts(mesh) != counts
        assert mesh.MeshVolume < 0.96 * o["surface"].Source.Shape.Volume  # the polycube's loss
        # Forcing the overlay with the Polycube still linked.
        mesh.Method = "overlay"
        api.recompute_document(doc2, [mesh])
        assert mesh.MeshingPath == "overlay" and _counts(mesh) == counts
        # Auto: the pipeline's choice again (`hexdom mesh --method auto`), the Polycube unlinked.
        mesh.Method = "auto"
        api.recompute_document(doc2, [mesh])
        assert mesh.MeshingPath == "overlay" and _counts(mesh) == counts
        assert mesh.Polycube is None
    finally:
        FreeCAD.closeDocument(doc2.Name)


@needs_cad
def test_a_part_the_polycube_fails_on_gets_the_overlay_mesh(doc):
    """The tetrahedron the automatic polycube cannot take: with Method auto Mesh Part gives the
    overlay grid's mesh and says why (the polycube path's error); the Segmentation stays valid, the
    failing Polycube stays in the document (its error names the charts) without holding the Mesh
    back: it holds what the polycube path made (no block). With Method polycube the failure
    names its stage, as before."""
    part = _part(doc, _tetrahedron(), "Tet")
    objs = hexdom.mesh_part(doc, part, size=20.0, level=2)
    mesh, poly = objs["mesh"], objs["polycube"]
    FreeCAD.Console.PrintMessage("tetrahedron: {} ({})\n".format(_counts(mesh), mesh.PolycubeNote))
    assert mesh.MeshingPath == "overlay" and mesh.Method == "auto"
    assert "polycube path failed" in mesh.PolycubeNote and "chart" in mesh.PolycubeNote
    assert _valid(mesh) and _valid(objs["segmentation"]) and mesh.InvertedCount == 0
    assert mesh.Polycube is None and poly.Document == doc
    assert poly.HexBlocks == 0 and poly.FromPipeline
    # Four acute corners at a size of twice the part: the overlay's cells there fall short of the
    # corners (measured -1.03% since the optimiser moves nodes colour by colour; the 1% target of
    # the every-solid issue is for 90% of the parts, docs/overlay.md), so 2% here.
    _check_fem_mesh(mesh, part.Shape, rel=0.02)
    with pytest.raises(api.MeshPartError) as info:
        hexdom.mesh_part(doc, part, size=20.0, level=2, method="polycube")
    assert info.value.stage == "automatic polycube"
    assert info.value.objects["mesh"].Method == "polycube"


@needs_cad
def test_an_old_document_without_method_properties_loads_and_recomputes(doc, tmp_path):
    """A document saved before Method, MeshingPath and PolycubeNote (removed here, as an older
    HexDom wrote it) opens with them added (Method auto) and recomputes to the same polycube
    mesh, which then says so."""
    box = _box(doc)
    objs = hexdom.mesh_part(doc, box, size=2.5, level=1)
    counts = _counts(objs["mesh"])
    names = {k: o.Name for k, o in objs.items()}
    for name in NEW_PROPERTIES:
        objs["mesh"].removeProperty(name)
        assert not hasattr(objs["mesh"], name)
    doc2 = reopen(doc, str(tmp_path / "old_mesh.FCStd"))
    try:
        o = {k: doc2.getObject(n) for k, n in names.items()}
        mesh = o["mesh"]
        assert isinstance(mesh.Proxy, hex_mesh.HexMesh)
        assert mesh.Method == "auto" and mesh.MeshingPath == "" and mesh.PolycubeNote == ""
        assert mesh.getEditorMode("MeshingPath") == ["ReadOnly"]
        assert _counts(mesh) == counts
        for obj in o.values():
            obj.touch()
        api.recompute_document(doc2, list(o.values()))
        assert mesh.MeshingPath == "polycube" and _counts(mesh) == counts
        assert isinstance(o["polycube"].Proxy, polycube.Polycube) and mesh.Polycube == o["polycube"]
    finally:
        FreeCAD.closeDocument(doc2.Name)


def test_unknown_method_is_refused(doc):
    with pytest.raises(ValueError, match="method must be one of auto, polycube, overlay"):
        api.make_mesh_part(doc, _box(doc), method="grid")
