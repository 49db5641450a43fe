"""Mesh Part on a FreeCAD mesh object (an STL or OBJ opened in FreeCAD): the mesh `hexdom mesh`
gives for the same triangles, with its input checks (issue "Surfaces as other tools export them"):
two boxes in one mesh, the second inside out and touching the first along a face, mesh as two
regions with warnings (the shell turned around, the solids touching); one inside-out box meshes
with the Segmentation filled; two boxes whose faces lie on each other are refused, naming two
triangles, before any meshing stage.

Oracles: the program run on an .obj written here from the triangles FreeCAD holds (its vertex
order kept), its .vtu read by VTK; FreeCAD's FemMesh read through its own API; cell volumes and
Verdict's scaled Jacobian from VTK."""

import os
import subprocess
import sys

import numpy as np
import pytest

import FreeCAD
import Mesh

import HexDomWorkbench as hexdom
from HexDomWorkbench import api

import fc_testdata

_here = os.environ.get("HEXDOM_FC_TEST_DIR") or os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(_here, "app"))
sys.path.insert(0, os.path.join(_here, "..", "python"))
import hexdom_oracles as oracles  # noqa: E402  (VTK's Verdict)
from test_mesh_part_prisms import _verdict_of  # noqa: E402  (FemMesh -> VTK grid, SMDS orders)

CLI = os.environ.get("HEXDOM_CLI", "")

def _box(lo, hi, reverse=False):
    """fc_testdata's box as FreeCAD facets."""
    return [[FreeCAD.Vector(*p) for p in t] for t in fc_testdata.box_triangles(lo, hi, reverse)]


def _mesh_object(doc, facets, name):
    obj = doc.addObject("Mesh::Feature", name)
    obj.Mesh = Mesh.Mesh(facets)
    doc.recompute()
    return obj


def _write_obj(obj, path):
    """The triangles FreeCAD holds, in its vertex order, as an OBJ file."""
    points, facets = obj.Mesh.Topology
    lines = ["v {!r} {!r} {!r}".format(p.x, p.y, p.z) for p in points]
    lines += ["f {} {} {}".format(*(k + 1 for k in f)) for f in facets]
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def _cli_cells(path, tmp_path, *args):
    out = tmp_path / "cli.vtu"
    r = subprocess.run([CLI, "mesh", path, "-o", str(out), "--polycube-seconds", "0"] + list(args),
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    g, sj, types = oracles.vtu_sj_types(str(out))
    P, _, cells = oracles.grid_arrays(g)
    from vtk.util.numpy_support import vtk_to_numpy
    region = vtk_to_numpy(g.GetCellData().GetArray("region"))
    return P, cells, types, np.asarray(oracles.signed_volumes(g)), region, r.stderr


needs_cli = pytest.mark.skipif(not (CLI and os.access(CLI, os.X_OK)),
                               reason="HEXDOM_CLI (the hexdom program; tests/freecad/run.sh sets it) "
                                      "not set or not executable: {!r}".format(CLI))


@needs_cli
def test_touching_boxes_in_a_mesh_object_mesh_as_two_regions_as_hexdom_mesh_meshes_them(doc, tmp_path):
    facets = _box((0, 0, 0), (10, 10, 10)) + _box((10, 2, 2), (20, 8, 8), reverse=True)
    part = _mesh_object(doc, facets, "Boxes")
    cli = _cli_cells(_write_obj(part, tmp_path / "boxes.obj"), tmp_path, "--size", "2.5")
    assert "solids 1 and 2 touch" in cli[5] and "faced inward" in cli[5], cli[5]

    objs = hexdom.mesh_part(doc, part, size=2.5, polycube_seconds=0)
    mesh = objs["mesh"]
    assert mesh.Pipeline and mesh.InvertedCount == 0
    sj, types, g = _verdict_of(mesh)
    P, _, cells = oracles.grid_arrays(g)
    Pc, cells_c, types_c, volume_c, region_c, _ = cli
    assert P.shape == Pc.shape and cells == cells_c and list(types) == list(types_c)
    assert float(np.abs(P - Pc).max(initial=0.0)) <= 1e-12 * 20
    assert np.all(sj > 0)
    region = np.array(mesh.Region)
    assert list(region) == list(region_c) and sorted(set(region.tolist())) == [1, 2]
    volume = np.asarray(oracles.signed_volumes(g))
    assert volume[region == 1].sum() == pytest.approx(1000.0, rel=1e-6)
    assert volume[region == 2].sum() == pytest.approx(360.0, rel=1e-6)
    # The Segmentation and the Polycube hold one solid: empty for two.
    assert objs["segmentation"].FromPipeline and len(objs["segmentation"].Labels) == 0
    # What the run warned of reaches the front end (the report view prints these lines).
    run = api.run_pipeline(objs)
    assert any("solids 1 and 2 touch" in w for w in run.warnings), run.warnings
    assert any("faced inward" in w for w in run.warnings), run.warnings
    assert run.solids == 2 and run.touching == [(1, 2)]


def test_an_inside_out_box_in_a_mesh_object_meshes_with_its_stages(doc):
    part = _mesh_object(doc, _box((0, 0, 0), (10, 10, 10), reverse=True), "InsideOut")
    objs = hexdom.mesh_part(doc, part, size=2.5, polycube_seconds=0)
    mesh = objs["mesh"]
    assert mesh.InvertedCount == 0 and mesh.HexCount == 64
    assert mesh.MeshVolume == pytest.approx(1000.0, rel=1e-9)
    sj, _, _ = _verdict_of(mesh)
    assert np.all(sj > 0.99)
    assert objs["surface"].TriangleCount == 12
    if mesh.MeshingPath == "polycube":  # its labels, one per triangle
        assert len(objs["segmentation"].Labels) == 12


def test_boxes_lying_on_each_other_in_a_mesh_object_are_refused(doc):
    part = _mesh_object(doc, _box((0, 0, 0), (10, 10, 10)) + _box((5, 0, 0), (15, 10, 10)), "Overlap")
    with pytest.raises(hexdom.MeshPartError, match="lies on itself: triangles") as info:
        hexdom.mesh_part(doc, part, size=2.5)
    assert info.value.stage == "check the input"
    assert objs_mesh_is_empty(info.value.objects)
    # The Surface shows the triangles refused, for the user to find the two named.
    assert info.value.objects["surface"].TriangleCount == 24


def objs_mesh_is_empty(objs):
    mesh = objs.get("mesh")
    return mesh is not None and mesh.HexCount == 0 and mesh.PrismCount == 0 and mesh.TetCount == 0
