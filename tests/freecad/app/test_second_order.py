"""Second-order meshes in FreeCAD (issue "second-order elements"): the HexDom Mesh's ElementOrder
"2nd" (as FreeCAD's Gmsh mesh object's) gives hex20 / wedge15 / tet10 volumes in FreeCAD's FemMesh,
the mesh `hexdom mesh --order 2` gives, and FreeCAD's CalculiX writer emits C3D20 for them.

Oracles: FreeCAD's FemMesh (element node lists, its own volume of quadratic elements,
getNodesByFace), `_hexdom`'s pipeline on the shape FreeCAD holds (what `hexdom mesh` runs),
CalculiX through FreeCAD's FEM workbench."""

import os
import shutil

import numpy as np
import pytest

import FreeCAD
import Part

import HexDomWorkbench as hexdom
from HexDomWorkbench import api, core
from HexDomWorkbench.convert import femmesh

import fc_fem

TEST_DIR = os.environ.get("HEXDOM_FC_TEST_DIR") or os.path.dirname(
    os.path.dirname(os.path.abspath(__file__)))
REPO = os.path.abspath(os.path.join(TEST_DIR, "..", ".."))
BRACKET = os.path.join(REPO, "examples", "data", "bracket.step")

needs_cad = pytest.mark.skipif(not api.has_cad(), reason="_hexdom built without OpenCASCADE")

HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
WEDGE_EDGES = [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)]
TET_EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]


def _quadratic(corners, edges, vtk_type, bulge=(0, 0, 0)):
    """One second-order cell over the corner points, mid-edge nodes at the midpoints (the first
    one moved by ``bulge``)."""
    corners = np.asarray(corners, float)
    mids = np.array([(corners[a] + corners[b]) / 2 for a, b in edges])
    mids[0] += bulge
    V = np.vstack([corners, mids])
    n = len(V)
    cells = np.full((1, 20), -1, np.int32)
    cells[0, :n] = np.arange(n)
    return core.Mesh(V, cells, np.array([vtk_type], np.int32), np.zeros(1, np.int32))


CUBE = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
WEDGE = [(0, 0, 0), (0, 1, 0), (1, 0, 0), (0, 0, 1), (0, 1, 1), (1, 0, 1)]  # VTK: first normal away
TET = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]


# Abaqus / CalculiX order -> VTK's: C3D20 and C3D10 the same, C3D15 with its corners reversed as C3D6's.
ABAQUS_TO_VTK = {"C3D20": list(range(20)), "C3D10": list(range(10)),
                 "C3D15": [0, 2, 1, 3, 5, 4, 8, 7, 6, 11, 10, 9, 12, 14, 13]}
VTK_CELLS = {"C3D20": "vtkQuadraticHexahedron", "C3D15": "vtkQuadraticWedge", "C3D10": "vtkQuadraticTetra"}


def _freecad_inp_volume(fem, path):
    """The volume of the one element FreeCAD's own CalculiX mesh writer (FemMesh.write) puts in
    ``path``, by VTK's quadratic shape functions at Gauss points (|volume|, and whether every
    Jacobian had one sign): what CalculiX gets from FreeCAD."""
    import vtk
    fem.write(str(path))
    nodes, element, kind = {}, None, None
    lines = iter(open(path).read().splitlines())
    section = ""
    for line in lines:
        if line.startswith("*"):
            section = line.upper()
            if "TYPE=" in section:
                kind = section.split("TYPE=")[1].split(",")[0].strip()
            continue
        fields = [f for f in line.replace(" ", "").split(",") if f]
        if not fields or line.startswith("**"):
            continue
        if section.startswith("*NODE"):
            nodes[int(fields[0])] = [float(v) for v in fields[1:4]]
        elif section.startswith("*ELEMENT"):
            element = (element or []) + [int(v) for v in (fields[1:] if element is None else fields)]
    P = np.array([nodes[n] for n in element])[ABAQUS_TO_VTK[kind]]
    cell = getattr(vtk, VTK_CELLS[kind])()
    n = len(P)
    g = np.sqrt(0.6)
    line_points = [((1 - g) / 2, 5 / 18), (0.5, 8 / 18), ((1 + g) / 2, 5 / 18)]
    if kind == "C3D20":
        rule = [((a, b, c), wa * wb * wc) for a, wa in line_points for b, wb in line_points for c, wc in line_points]
    elif kind == "C3D15":
        rule = [((r, s, t), w / 6) for r, s in ((1 / 6, 1 / 6), (2 / 3, 1 / 6), (1 / 6, 2 / 3)) for t, w in line_points]
    else:
        a, b = 0.5854101966249685, 0.1381966011250105
        rule = [(p, 1 / 24) for p in ((b, b, b), (a, b, b), (b, a, b), (b, b, a))]
    dets = []
    for x, w in rule:
        d = [0.0] * (3 * n)
        cell.InterpolateDerivs(list(x), d)
        dets.append(w * np.linalg.det(np.array(d).reshape(3, n) @ P))
    dets = np.array(dets)
    return abs(dets.sum()), bool((dets > 0).all() or (dets < 0).all())


@pytest.mark.parametrize("corners, edges, vtk_type, volume, out", [
    (CUBE, HEX_EDGES, core.HEX20, 1.0, (0, -0.1, 0)), (WEDGE, WEDGE_EDGES, core.WEDGE15, 0.5, (-0.1, 0, 0)),
    (TET, TET_EDGES, core.TET10, 1 / 6, (0, -0.1, 0))])
def test_one_second_order_cell_reaches_freecad_s_calculix_writer_as_it_is(corners, edges, vtk_type, volume, out,
                                                                           tmp_path):
    mesh = _quadratic(corners, edges, vtk_type)
    fem = femmesh.to_femmesh(mesh)
    assert fem.VolumeCount == 1 and fem.NodeCount == len(mesh.V)
    assert len(fem.getElementNodes(1)) == len(mesh.V)
    back = femmesh.from_femmesh(fem)
    assert back.order == 2 and np.array_equal(back.types, mesh.types)
    assert np.array_equal(back.cells, mesh.cells) and np.allclose(back.V, mesh.V)
    corners_only = femmesh.from_femmesh(fem, corners_only=True)
    assert corners_only.order == 1 and corners_only.cells.shape == (1, 8)
    got, one_sign = _freecad_inp_volume(fem, tmp_path / "straight.inp")
    assert one_sign and got == pytest.approx(volume, rel=1e-9)
    # A curved cell: the element FreeCAD writes for CalculiX is the core's (each mid-edge node on
    # its own edge), the same curved volume.
    curved = _quadratic(corners, edges, vtk_type, bulge=out)  # its first edge bowed outward
    core_volume = core.quality_report(curved)["total_volume"]
    assert core_volume > volume
    got, one_sign = _freecad_inp_volume(femmesh.to_femmesh(curved), tmp_path / "curved.inp")
    assert one_sign and got == pytest.approx(core_volume, rel=1e-9)


def _bracket(doc):
    part = doc.addObject("Part::Feature", "Bracket")
    part.Shape = Part.read(BRACKET)
    doc.recompute()
    return part


def _face(shape, test):
    for i, face in enumerate(shape.Faces, 1):
        if test(face):
            return "Face{}".format(i)
    raise AssertionError("no such face")


def _hole(face):  # the 12 mm hole through the base plate, axis at x 40, y 20
    s = face.Surface
    return isinstance(s, Part.Cylinder) and abs(s.Radius - 6.0) < 1e-9 and abs(s.Center.x - 40) < 1e-9


@needs_cad
def test_mesh_part_second_order_is_the_program_s_and_solves_in_calculix(doc, tmp_path):
    part = _bracket(doc)
    objs = hexdom.mesh_part(doc, part, level=1, order=2)
    mesh = objs["mesh"]
    assert mesh.ElementOrder == "2nd" and mesh.InvertedCount == 0
    run = core.mesh_part(part.Shape.exportBrepToString(), level=1, order=2)
    assert run.mesh.order == 2 and run.second_order["boundary_mid_nodes"] > 0
    fem = mesh.FemMesh
    assert fem.VolumeCount == len(run.mesh.types) and fem.NodeCount == len(run.mesh.V)
    assert {len(fem.getElementNodes(e)) for e in fem.Volumes} == {20}
    got = femmesh.from_femmesh(fem)
    assert np.array_equal(got.cells, run.mesh.cells) and np.abs(got.V - run.mesh.V).max() <= 1e-12
    # The hole's mid-edge nodes are on it too: FreeCAD finds about twice the first order's nodes.
    hole = part.Shape.getElement(_face(part.Shape, _hole))
    first = core.mesh_part(part.Shape.exportBrepToString(), level=1)
    assert len(fem.getNodesByFace(hole)) >= 1.8 * np.count_nonzero(
        np.abs(np.hypot(first.mesh.V[:, 0] - 40, first.mesh.V[:, 1] - 20) - 6) < 1e-7)
    assert mesh.MeshVolume == pytest.approx(run.quality["total_volume"])
    # The README macro's set-up: base fixed, the upright's top pulled up by 1000 N; FreeCAD's writer
    # emits C3D20.
    bottom = _face(part.Shape, lambda f: abs(f.BoundBox.ZMax) < 1e-9)
    top = _face(part.Shape, lambda f: abs(f.BoundBox.ZMin - 50.0) < 1e-9)
    analysis, solver, _ = fc_fem.static_analysis(doc, 210000.0, 0.3, [(part, bottom)], [(part, top)],
                                                 1000.0, (part, [top]))
    analysis.addObject(mesh)
    doc.recompute()
    fea = fc_fem.write_inp(analysis, solver, tmp_path)
    text = open(fea.inp_file_name).read()
    assert "C3D20" in text and "C3D8," not in text
    if shutil.which("ccx") is None:
        pytest.skip("CalculiX ccx not on PATH: the set-up is written, not solved")
    displacement = fc_fem.solve(fea, analysis)
    pulled = fem.getNodesByFace(part.Shape.getElement(top))
    uz = sum(displacement[n].z for n in pulled) / len(pulled)
    stretch = 1000.0 * 40.0 / (210000.0 * 10.0 * 40.0)  # the upright alone, above the base
    assert stretch <= uz <= 10 * stretch, (uz, stretch)


@needs_cad
def test_stage_built_meshes_take_the_element_order_too(doc):
    # Out of the pipeline (a stage edited), the Mesh composes generate, improve and snap itself,
    # then makes the second order on the B-rep with the snap's node kinds.
    part = _bracket(doc)
    objs = hexdom.mesh_part(doc, part, level=1)
    mesh = objs["mesh"]
    first_nodes = mesh.FemMesh.NodeCount
    mesh.Pipeline = False
    mesh.ElementOrder = "2nd"
    api.recompute_document(doc, [mesh])
    fem = mesh.FemMesh
    assert {len(fem.getElementNodes(e)) for e in fem.Volumes} <= {20, 15, 10}
    assert fem.NodeCount > 3 * first_nodes and mesh.InvertedCount == 0
    corners = {n for e in fem.Volumes for n in fem.getElementNodes(e)[:8]}
    hole = part.Shape.getElement(_face(part.Shape, _hole))
    on_hole = fem.getNodesByFace(hole)
    mids = [n for n in on_hole if n not in corners]
    assert len(mids) > 0.4 * len(on_hole), (len(mids), len(on_hole))
