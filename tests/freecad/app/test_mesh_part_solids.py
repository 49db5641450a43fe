"""Mesh Part on a Part whose shape holds two solids (a compound, as a STEP assembly loads): both are
meshed, solid k's cells in region k, and FreeCAD's FEM finds every face of the compound on the
mesh, so an analysis set up on the compound's faces solves in CalculiX.

Two blocks apart: A 20 x 10 x 10 at the origin (the compound's Face1..Face6) and B 10 x 10 x 10 at
x = 40 (Face7..Face12). Oracles: FreeCAD numbers the faces and finds the nodes within 1e-7 of each
(FemMesh.getNodesByFace: every mesh node on the face's plane, counted from the mesh's own
coordinates); CalculiX through FreeCAD's ccxtools solves A and B clamped at x = 0 and x = 40 and
pulled by F / 2 on x = 20 and x = 50 with Poisson's ratio 0: the uniaxial solution u = (F/2) l / (E A)
is exact for linear hexes, so the mean end displacements must match it to 0.1%."""

import shutil

import numpy as np
import pytest

import FreeCAD
import Part

import HexDomWorkbench as hexdom
from HexDomWorkbench import core
from HexDomWorkbench.convert import fem_setup

import fc_fem

E, F, AREA = 210000.0, 1000.0, 100.0

pytestmark = pytest.mark.skipif(not core.has_opencascade(), reason="_hexdom built without OpenCASCADE")


def _planes(shape):
    """For each face of the compound (0-based), the (axis, value) of its plane."""
    out = []
    for f in shape.Faces:
        n = f.normalAt(0, 0)
        axis = int(np.argmax(np.abs([n.x, n.y, n.z])))
        out.append((axis, float(f.CenterOfMass[axis])))
    return out


def test_two_solids_mesh_in_two_regions_and_solve_on_the_compounds_faces(doc, tmp_path):
    shape = Part.makeCompound([Part.makeBox(20, 10, 10), Part.makeBox(10, 10, 10, FreeCAD.Vector(40, 0, 0))])
    part = doc.addObject("Part::Feature", "Blocks")
    part.Shape = shape
    doc.recompute()
    planes = _planes(part.Shape)
    assert planes[0] == (0, 0.0) and planes[1] == (0, 20.0) and planes[6] == (0, 40.0) and planes[7] == (0, 50.0)

    objs = hexdom.mesh_part(doc, part, size=2.5)
    mesh_obj = objs["mesh"]
    doc.recompute()
    assert mesh_obj.InvertedCount == 0
    fem = mesh_obj.FemMesh
    V = np.array([[p.x, p.y, p.z] for p in fem.Nodes.values()])
    assert fem.VolumeCount > 0
    # Every face of the compound: FreeCAD's node search finds the nodes on its plane, inside its box.
    for i, (axis, value) in enumerate(planes):
        face = part.Shape.Faces[i]
        box = face.BoundBox
        inside = (np.abs(V[:, axis] - value) < 1e-9) & (V[:, 0] >= box.XMin - 1e-9) & (V[:, 0] <= box.XMax + 1e-9)
        found = fem.getNodesByFace(face)
        assert len(found) == int(inside.sum()) > 0, ("Face{}".format(i + 1), len(found), int(inside.sum()))

    if shutil.which("ccx") is None:
        pytest.skip("CalculiX ccx not on PATH")
    normal_x = part.Shape.Faces[1].normalAt(0, 0).x
    analysis, solver, _ = fc_fem.static_analysis(
        doc, E, 0.0, [(part, "Face1"), (part, "Face7")], [(part, "Face2"), (part, "Face8")], F,
        (part, ["Face2"]), normal_x < 0)
    fem_setup.add_to_analysis(analysis, mesh_obj)
    doc.recompute()
    work = tmp_path / "ccx"
    work.mkdir()
    fea = fc_fem.write_inp(analysis, solver, work)
    disp = fc_fem.solve(fea, analysis)
    ids = list(fem.Nodes.keys())
    for x_end, length in ((20.0, 20.0), (50.0, 10.0)):
        tip = [ids[k] for k in np.flatnonzero(np.abs(V[:, 0] - x_end) < 1e-9)]
        u = float(np.mean([disp[n].x for n in tip]))
        assert u == pytest.approx(F / 2 * length / (E * AREA), rel=1e-3), (x_end, u)
