"""Local sizes in FreeCAD (issue "element size that FEM users can steer"): FreeCAD's own FEM mesh
region (ObjectsFem.makeMeshRegion on the HexDom Mesh, as on a Gmsh mesh object) gives cells of its
CharacteristicLength on the faces (and along the edges) it references, the mesh `hexdom mesh --face-size` gives (and
the Mesh's GrowthRate, `--growth-rate`'s); the README macro's FEM set-up (base fixed, upright pulled) still solves on it.

Oracles: `_hexdom`'s pipeline on the shape FreeCAD holds (core.mesh_part on its BREP text, what
`hexdom mesh` runs), FreeCAD's FemMesh (getNodesByFace finds the nodes within 1e-7 of a face),
CalculiX through FreeCAD's FEM workbench."""

import os
import re
import shutil

import numpy as np
import pytest

import FreeCAD
import ObjectsFem
import Part

import HexDomWorkbench as hexdom
from HexDomWorkbench import api, core
from HexDomWorkbench.document import RecomputeError

import fc_fem

TEST_DIR = os.environ.get("HEXDOM_FC_TEST_DIR") or os.path.dirname(
    os.path.dirname(os.path.abspath(__file__)))
REPO = os.path.abspath(os.path.join(TEST_DIR, "..", ".."))
BRACKET = os.path.join(REPO, "examples", "data", "bracket.step")

needs_cad = pytest.mark.skipif(not api.has_cad(), reason="_hexdom built without OpenCASCADE")


def _bracket(doc):
    part = doc.addObject("Part::Feature", "Bracket")
    part.Shape = Part.read(BRACKET)
    doc.recompute()
    return part


def _face(shape, test):
    """Name of the first face of ``shape`` for which test(face) holds."""
    for i, face in enumerate(shape.Faces, 1):
        if test(face):
            return "Face{}".format(i)
    raise AssertionError("no such face")


def _hole(face):  # the 12 mm hole through the base plate, axis at x 40, y 20
    s = face.Surface
    return isinstance(s, Part.Cylinder) and abs(s.Radius - 6.0) < 1e-9 and abs(s.Center.x - 40) < 1e-9


def _points(femmesh, nodes):
    return np.array([[femmesh.Nodes[n].x, femmesh.Nodes[n].y, femmesh.Nodes[n].z] for n in sorted(nodes)])


@needs_cad
def test_a_mesh_region_on_the_hole_refines_there_and_the_fem_set_up_solves(doc, tmp_path):
    part = _bracket(doc)
    hole = _face(part.Shape, _hole)
    objs = hexdom.mesh_part(doc, part, level=1)
    mesh = objs["mesh"]
    plain = len(mesh.FemMesh.getNodesByFace(part.Shape.getElement(hole)))
    region = ObjectsFem.makeMeshRegion(doc, mesh, 1.0, "HoleRegion")
    region.References = [(part, hole)]
    assert list(mesh.MeshRegionList) == [region]
    api.recompute_document(doc, [mesh])
    # Either path may keep it (the polycube's cells on the hole are 0.76 to 0.81 of the length
    # depending on the tessellation, the overlay's 0.84): the Mesh says how near the length its
    # cells on the hole are (the core's measure: the median boundary face's mean edge), the median
    # nearest-node spacing below measuring it too.
    assert mesh.InvertedCount == 0 and mesh.MeshingPath in ("polycube", "overlay"), (mesh.MeshingPath,
                                                                                    mesh.InvertedCount)
    assert len(mesh.LocalSizes) == 1, list(mesh.LocalSizes)
    m = re.fullmatch(hole + r": cells ([\d.]+) of 1 \(within 20%\)", mesh.LocalSizes[0])
    assert m and 0.8 <= float(m.group(1)) <= 1.2, list(mesh.LocalSizes)
    # The program's mesh with the same face size.
    number = int(hole[4:])
    run = core.mesh_part(part.Shape.exportBrepToString(), level=1, face_sizes={number: 1.0})
    assert mesh.FemMesh.VolumeCount == len(run.mesh.types)
    on_hole = mesh.FemMesh.getNodesByFace(part.Shape.getElement(hole))
    assert len(on_hole) > 5 * plain, (len(on_hole), plain)
    # Node spacing on the hole about 1: the second nearest of each node's neighbours among the
    # hole's nodes (a node of a quad grid has its along-row and across-row neighbours near the
    # cell size; the nearest alone is the thin pillow row along a rim on the polycube's mesh).
    P = _points(mesh.FemMesh, on_hole)
    d = np.sqrt(((P[:, None, :] - P[None, :, :]) ** 2).sum(axis=2))
    np.fill_diagonal(d, np.inf)
    second = np.median(np.sort(d, axis=1)[:, 1])
    assert 0.75 <= second <= 1.2, second
    # A faster growth (3: only the cells touching the hole refined): fewer cells, the program's.
    hexes = mesh.HexCount
    mesh.GrowthRate = 3.0
    api.recompute_document(doc, [mesh])
    fast = core.mesh_part(part.Shape.exportBrepToString(), level=1, face_sizes={number: 1.0}, growth_rate=3.0)
    assert mesh.FemMesh.VolumeCount == len(fast.mesh.types) and mesh.HexCount < hexes, (mesh.HexCount, hexes)
    mesh.GrowthRate = 3 ** 0.25
    api.recompute_document(doc, [mesh])
    assert mesh.HexCount == hexes
    # The README macro's FEM set-up: base fixed, the upright's top pulled up by 1000 N.
    bottom = _face(part.Shape, lambda f: abs(f.BoundBox.ZMax) < 1e-9)
    top = _face(part.Shape, lambda f: abs(f.BoundBox.ZMin - 50.0) < 1e-9)
    analysis, solver, _ = fc_fem.static_analysis(doc, 210000.0, 0.3, [(part, bottom)], [(part, top)],
                                                 1000.0, (part, [top]))
    analysis.addObject(mesh)
    doc.recompute()
    if shutil.which("ccx") is None:
        pytest.skip("CalculiX ccx not on PATH: the set-up is written, not solved")
    fea = fc_fem.write_inp(analysis, solver, tmp_path)
    displacement = fc_fem.solve(fea, analysis)
    fixed = mesh.FemMesh.getNodesByFace(part.Shape.getElement(bottom))
    pulled = mesh.FemMesh.getNodesByFace(part.Shape.getElement(top))
    assert fixed and pulled
    assert max(displacement[n].Length for n in fixed) == 0.0
    uz = sum(displacement[n].z for n in pulled) / len(pulled)
    stretch = 1000.0 * 40.0 / (210000.0 * 10.0 * 40.0)  # the upright alone, above the base
    assert stretch <= uz <= 10 * stretch, (uz, stretch)


@needs_cad
def test_a_mesh_region_on_an_edge_refines_along_it(doc):
    # The hole's top rim (a circle of radius 6 at z = 10): the program's mesh with --edge-size,
    # many more nodes on the rim than without it.
    part = _bracket(doc)
    rim = next("Edge{}".format(i) for i, e in enumerate(part.Shape.Edges, 1)
               if isinstance(e.Curve, Part.Circle) and abs(e.Curve.Radius - 6) < 1e-9
               and abs(e.Curve.Center.x - 40) < 1e-9 and abs(e.Curve.Center.z - 10) < 1e-9)
    objs = hexdom.mesh_part(doc, part, level=1)
    mesh = objs["mesh"]
    plain = len(mesh.FemMesh.getNodesByEdge(part.Shape.getElement(rim)))
    region = ObjectsFem.makeMeshRegion(doc, mesh, 1.0, "RimRegion")
    region.References = [(part, rim)]
    api.recompute_document(doc, [mesh])
    assert mesh.MeshingPath == "overlay" and mesh.InvertedCount == 0
    run = core.mesh_part(part.Shape.exportBrepToString(), level=1, edge_sizes={int(rim[4:]): 1.0})
    assert mesh.FemMesh.VolumeCount == len(run.mesh.types)
    on_rim = len(mesh.FemMesh.getNodesByEdge(part.Shape.getElement(rim)))
    # 37.7 long: 29 to 54 nodes for a node spacing within 30% of 1 (16 without the region).
    assert on_rim > 2 * plain and 29 <= on_rim <= 54, (on_rim, plain)


@needs_cad
def test_a_mesh_region_refines_the_polycube_mesh_when_that_path_is_asked_for(doc):
    # Method Polycube with a region on the hole at 0.5: the polycube path's mesh refined by
    # thirds there (the program's mesh with --method polycube --face-size), many more nodes on
    # the hole, none inverted.
    part = _bracket(doc)
    hole = _face(part.Shape, _hole)
    objs = hexdom.mesh_part(doc, part, level=1)
    mesh = objs["mesh"]
    mesh.Method = "polycube"
    api.recompute_document(doc, [mesh])
    plain = len(mesh.FemMesh.getNodesByFace(part.Shape.getElement(hole)))
    region = ObjectsFem.makeMeshRegion(doc, mesh, 0.5, "HoleRegion")
    region.References = [(part, hole)]
    api.recompute_document(doc, [mesh])
    assert mesh.MeshingPath == "polycube" and mesh.InvertedCount == 0, (mesh.MeshingPath, mesh.InvertedCount)
    run = core.mesh_part(part.Shape.exportBrepToString(), level=1, face_sizes={int(hole[4:]): 0.5}, method="polycube")
    assert mesh.FemMesh.VolumeCount == len(run.mesh.types)
    on_hole = len(mesh.FemMesh.getNodesByFace(part.Shape.getElement(hole)))
    assert on_hole > 10 * plain, (on_hole, plain)


@needs_cad
def test_a_mesh_region_on_a_vertex_or_another_part_is_refused_naming_it(doc):
    part = _bracket(doc)
    other = doc.addObject("Part::Box", "Other")
    doc.recompute()
    objs = hexdom.mesh_part(doc, part, level=1)
    mesh = objs["mesh"]
    region = ObjectsFem.makeMeshRegion(doc, mesh, 1.0, "BadRegion")
    region.References = [(part, "Vertex3")]
    with pytest.raises(RecomputeError, match="mesh region BadRegion: Vertex3 of Bracket: HexDom takes sizes on faces and edges only"):
        api.recompute_document(doc, [mesh])
    region.References = [(other, "Face1")]
    with pytest.raises(RecomputeError, match="mesh region BadRegion: Face1 of Other is not a face of the part meshed"):
        api.recompute_document(doc, [mesh])
    region.CharacteristicLength = 0.0
    region.References = [(part, "Face1")]
    with pytest.raises(RecomputeError, match="mesh region BadRegion: its CharacteristicLength must be positive"):
        api.recompute_document(doc, [mesh])
    region.CharacteristicLength = 2.0
    api.recompute_document(doc, [mesh])
    assert mesh.InvertedCount == 0 and mesh.HexCount > 0
