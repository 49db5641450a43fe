"""The HexDom Mesh offers FEM mesh groups per CAD face, and per constraint of its analysis, which
FreeCAD's CalculiX writer uses instead of its geometric node search (issue 24).

A Part::Cylinder (radius R, length L along z) meshed by Mesh Part. Oracles: FreeCAD itself: its
node search FemMesh.getNodesByFace (nodes within 1e-7 of the face) must find exactly each Face<k>
group's nodes on the snapped mesh; FreeCAD's ccxtools writes the analysis (its *NSET of each
constraint must be the constraint's group) and CalculiX solves it: the mean axial end displacement
F L / (E A) within 2%. On the mesh left on the tessellation (SnapToCAD off), the node search
misses most of the curved face's nodes while its group still holds every boundary node there."""

import math
import re
import shutil

import numpy as np
import pytest

import FreeCAD

import HexDomWorkbench as hexdom
from HexDomWorkbench import core
from HexDomWorkbench.convert import fem_setup, femmesh

import fc_fem
from conftest import reopen

R, L = 5.0, 60.0
E, NU, F = 210000.0, 0.3, 1000.0

pytestmark = pytest.mark.skipif(not core.has_opencascade(), reason="_hexdom built without OpenCASCADE")


def _faces(shape):
    """0-based indices of the bottom (z = 0), top (z = L) and curved faces."""
    out = {}
    for i, f in enumerate(shape.Faces):
        if type(f.Surface).__name__ == "Cylinder":
            out["side"] = i
        else:
            out["bottom" if abs(f.CenterOfMass.z) < 1e-9 else "top"] = i
    return out["bottom"], out["top"], out["side"]


def _cylinder_mesh(doc, method="polycube"):
    cyl = doc.addObject("Part::Cylinder", "Cylinder")
    cyl.Radius, cyl.Height = R, L
    doc.recompute()
    objs = hexdom.mesh_part(doc, cyl, size=2.5, method=method)
    return cyl, objs["mesh"]


@pytest.mark.parametrize("method", ["polycube", "overlay"])
def test_face_groups_are_the_nodes_freecad_finds_on_each_face(doc, tmp_path, method):
    """Also on the overlay's mesh, whose boundary quads may straddle the rims: each group holds the
    nodes the snap put on that face (before, a straddling quad's cap node joined the side's group)."""
    cyl, mesh_obj = _cylinder_mesh(doc, method)
    if method == "overlay":
        assert mesh_obj.MeshingPath == "overlay"
        # The Mesh's own recompute (the pipeline's stages again) gives the same groups.
        before = femmesh.node_groups(mesh_obj.FemMesh, "Face")
        mesh_obj.touch()
        doc.recompute()
        assert femmesh.node_groups(mesh_obj.FemMesh, "Face") == before
    fem = mesh_obj.FemMesh
    groups = femmesh.node_groups(fem, "Face")
    assert sorted(groups) == ["Face1", "Face2", "Face3"]
    for i, face in enumerate(cyl.Shape.Faces):
        found = sorted(fem.getNodesByFace(face))
        assert groups["Face{}".format(i + 1)] == found, i + 1
    # The groups are saved with the document's FemMesh.
    name = mesh_obj.Name
    again = reopen(doc, str(tmp_path / "groups.FCStd"))
    try:
        assert femmesh.node_groups(again.getObject(name).FemMesh, "Face") == groups
    finally:
        FreeCAD.closeDocument(again.Name)


def test_constraint_on_a_face_group_solves_in_calculix(doc, tmp_path):
    if shutil.which("ccx") is None:
        pytest.skip("CalculiX ccx not on PATH")
    cyl, mesh_obj = _cylinder_mesh(doc)
    bottom, top, _ = _faces(cyl.Shape)
    reversed = cyl.Shape.Faces[top].normalAt(0, 0).z < 0
    analysis, solver, _ = fc_fem.static_analysis(
        doc, E, NU, [(cyl, "Face{}".format(bottom + 1))], [(cyl, "Face{}".format(top + 1))], F,
        (cyl, ["Face{}".format(top + 1)]), reversed)
    doc.recompute()
    fem_setup.add_to_analysis(analysis, mesh_obj)
    assert "Touched" not in mesh_obj.State  # the groups do not ask for a new mesh
    groups = femmesh.node_groups(mesh_obj.FemMesh)
    assert groups["ConstraintFixed_Nodes"] == groups["Face{}".format(bottom + 1)]
    assert groups["ConstraintForce_Nodes"] == groups["Face{}".format(top + 1)]

    work = tmp_path / "ccx"
    work.mkdir()
    fea = fc_fem.write_inp(analysis, solver, work)
    text = open(fea.inp_file_name).read()
    block = re.search(r"\*NSET,NSET=ConstraintFixed\n((?:\d+,\n)+)", text)
    assert block, text[:2000]
    assert sorted(int(n) for n in re.findall(r"(\d+),", block.group(1))) == groups["ConstraintFixed_Nodes"]
    disp = fc_fem.solve(fea, analysis)
    tip = groups["Face{}".format(top + 1)]
    u = float(np.mean([disp[n].z for n in tip]))
    assert u == pytest.approx(F * L / (E * math.pi * R * R), rel=0.02)


def test_face_groups_hold_the_curved_face_where_the_node_search_misses_it(doc, tmp_path):
    cyl, mesh_obj = _cylinder_mesh(doc)
    mesh_obj.SnapToCAD = False
    doc.recompute()
    _, _, side = _faces(cyl.Shape)
    fem = mesh_obj.FemMesh
    group = femmesh.node_groups(fem, "Face")["Face{}".format(side + 1)]
    V = {n: fem.Nodes[n] for n in group}
    # Every node of the group is on the side (radius R within the tessellation's chords, z inside).
    radius = np.array([math.hypot(p.x, p.y) for p in V.values()])
    assert np.all(np.abs(radius - R) < R / 50 + 1e-9)
    found = fem.getNodesByFace(cyl.Shape.Faces[side])
    assert len(found) < 0.9 * len(group), (len(found), len(group))
    # CalculiX's writer takes the constraint's nodes from its group, not from the search.
    if shutil.which("ccx") is None:
        pytest.skip("CalculiX ccx not on PATH")
    bottom, top, side = _faces(cyl.Shape)
    analysis, solver, _ = fc_fem.static_analysis(
        doc, E, NU, [(cyl, "Face{}".format(side + 1))], [(cyl, "Face{}".format(top + 1))], F,
        (cyl, ["Face{}".format(top + 1)]))
    fem_setup.add_to_analysis(analysis, mesh_obj)
    doc.recompute()
    # Recomputed inside the analysis, the mesh stores its face and constraint groups at once.
    mesh_obj.touch()
    doc.recompute()
    groups = femmesh.node_groups(mesh_obj.FemMesh)
    assert groups["ConstraintFixed_Nodes"] == groups["Face{}".format(side + 1)] == group
    work = tmp_path / "ccx"
    work.mkdir()
    text = open(fc_fem.write_inp(analysis, solver, work).inp_file_name).read()
    block = re.search(r"\*NSET,NSET=ConstraintFixed\n((?:\d+,\n)+)", text)
    assert block, text[:2000]
    assert sorted(int(n) for n in re.findall(r"(\d+),", block.group(1))) == group
