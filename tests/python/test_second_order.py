"""Second-order meshes through `_hexdom` (HexDomWorkbench.core): the program's mesh from
mesh_part(order=2), the same mesh from the stage functions (snap_to_brep then second_order), a
surface's second order on the surface, and the boundary's mid-edge nodes on the B-rep of the 9 CAD
parts of the shared data.

Oracles: meshio reads the program's files; VTK's cell locator measures distances to a triangle
surface; FreeCAD's distToShape distances to the B-rep."""

import glob
import subprocess
from pathlib import Path

import numpy as np
import pytest

import hexdom_oracles as oracles
import hexdom_test_support as support

BRACKET = Path(__file__).resolve().parents[2] / "examples" / "data" / "bracket.step"
CAD_PARTS = ["s09o_bridge", "s11o_cube_cyl", "s15o_cylinder", "s12o_cube_rounded_1", "s14o_cube_corner_sub_sphere",
             "n11o_limit_cycle", "i10o_simp", "i11o_s1", "i01o_m1"]
TABLES = oracles.QUADRATIC


def boundary_mid_nodes(mesh):
    """The mid-edge nodes of the boundary edges of a second-order core.Mesh (from its faces used
    by one cell)."""
    count = {}
    for cell, t in zip(mesh.cells, mesh.types):
        n, _, faces = TABLES[int(t)]
        for f in faces:
            key = tuple(sorted(cell[list(f)]))
            count[key] = count.get(key, 0) + 1
    boundary = {k for k, c in count.items() if c == 1}
    mids = set()
    for cell, t in zip(mesh.cells, mesh.types):
        n, edges, faces = TABLES[int(t)]
        for k, (i, j) in enumerate(edges):
            if any(i in f and j in f and tuple(sorted(cell[list(f)])) in boundary for f in faces):
                mids.add(int(cell[n + k]))
    return sorted(mids)


@pytest.fixture(scope="module")
def cad(core):
    if not core.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")
    return core


def test_mesh_part_order_2_is_the_program_s_mesh(cad, hexdom_bin, tmp_path):
    import meshio
    run = cad.mesh_part(str(BRACKET), order=2)
    assert run.mesh.order == 2 and run.mesh.cells.shape[1] == 20 and run.inverted == 0
    assert run.quality["order"] == 2 and run.quality["hex20"]["count"] == len(run.mesh.types)
    out = tmp_path / "bracket2.vtu"
    r = subprocess.run([str(hexdom_bin), "mesh", str(BRACKET), "-o", str(out), "--order", "2"], capture_output=True,
                       text=True)
    assert r.returncode == 0, r.stderr
    m = meshio.read(out)
    assert np.array_equal(m.cells_dict["hexahedron20"], run.mesh.cells)
    assert np.abs(m.points - run.mesh.V).max() <= 1e-12 * np.abs(run.mesh.V).max()
    so = run.second_order
    assert so["boundary_mid_nodes"] == len(boundary_mid_nodes(run.mesh)) == so["placed"]
    assert f"second order: {so['boundary_mid_nodes']} boundary mid-edge nodes" in r.stderr


def test_the_stage_functions_give_the_pipeline_s_second_order(cad):
    # snap_to_brep's report says which CAD edge or vertex each node is on; second_order takes it.
    first = cad.mesh_part(str(BRACKET))
    assert first.mesh.order == 1 and first.second_order is None
    mesh, report = cad.second_order(first.mesh, first.surface, str(BRACKET), first.snap)
    second = cad.mesh_part(str(BRACKET), order=2)
    assert np.array_equal(mesh.cells, second.mesh.cells) and np.array_equal(mesh.V, second.mesh.V)
    assert report["placed"] == second.second_order["placed"]
    with pytest.raises(cad.InputError, match="snap report"):
        cad.second_order(first.mesh, first.surface, str(BRACKET))
    with pytest.raises(cad.InputError, match="first-order cells"):
        cad.improve(mesh)
    with pytest.raises(cad.InputError, match="order is 1 or 2"):
        cad.mesh_part(str(BRACKET), order=3)


def test_a_surface_s_second_order_has_its_mid_edge_nodes_on_the_surface(core, tmp_path):
    import vtk
    from vtk.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    # A closed surface: a cylinder's triangles, written by the program's own writer, read back.
    n, r, h = 48, 10.0, 20.0
    a = 2 * np.pi * np.arange(n) / n
    V = np.vstack([np.c_[r * np.cos(a), r * np.sin(a), np.zeros(n)], np.c_[r * np.cos(a), r * np.sin(a), np.full(n, h)],
                   [[0, 0, 0], [0, 0, h]]])
    F = []
    for i in range(n):
        j = (i + 1) % n
        F += [[i, j, n + j], [i, n + j, n + i], [2 * n, j, i], [2 * n + 1, n + i, n + j]]
    surface = core.Surface(V, np.array(F, np.int32), np.zeros(len(F), np.int32))
    run = core.mesh_surface(surface, order=2, method="overlay")
    assert run.mesh.order == 2 and run.inverted == 0
    mids = boundary_mid_nodes(run.mesh)
    so = run.second_order
    assert so["boundary_mid_nodes"] == len(mids) and so["edge_targets"] == 0
    poly = vtk.vtkPolyData()
    pts = vtk.vtkPoints()
    pts.SetData(numpy_to_vtk(V))
    poly.SetPoints(pts)
    cells = vtk.vtkCellArray()
    cells.SetCells(len(F), numpy_to_vtkIdTypeArray(np.c_[np.full(len(F), 3), np.array(F)].ravel().astype(np.int64)))
    poly.SetPolys(cells)
    loc = vtk.vtkCellLocator()
    loc.SetDataSet(poly)
    loc.BuildLocator()
    d = []
    for v in mids:
        q, cid, sub, d2 = [0.0, 0.0, 0.0], vtk.reference(0), vtk.reference(0), vtk.reference(0.0)
        loc.FindClosestPoint(run.mesh.V[v].tolist(), q, cid, sub, d2)
        d.append(np.sqrt(d2.get()))
    d = np.sort(d)
    # The placed ones lie on the surface; the others were pulled back towards their edges.
    assert d[:so["placed"]].max() <= 1e-9 * so["diagonal"]
    assert so["placed"] >= 0.9 * len(mids)


@pytest.mark.parametrize("stem", CAD_PARTS)
def test_boundary_mid_edge_nodes_lie_on_the_brep_of_the_cad_parts(stem, cad, freecad):
    FreeCAD, Part = freecad
    paths = glob.glob(str(support.DATA_ROOT / "cad" / f"{stem}.*"))
    if not paths:
        pytest.skip(support.missing(support.DATA_ROOT / "cad" / f"{stem}.*"))
    run = cad.mesh_part(paths[0], order=2, allow_inverted=True)
    so = run.second_order
    mids = boundary_mid_nodes(run.mesh)
    assert so["boundary_mid_nodes"] == len(mids)
    assert run.inverted == 0
    shape = Part.read(paths[0]).Solids[0]
    faces = Part.Compound(shape.Faces)
    d = np.sort([faces.distToShape(Part.Vertex(FreeCAD.Vector(*map(float, run.mesh.V[v]))))[0] for v in mids])
    diag = shape.BoundBox.DiagonalLength
    print(f"{stem}: {len(mids)} boundary mid-edge nodes, {so['placed']} placed (B-rep distance max "
          f"{d[:so['placed']].max() / diag:.1e} x diagonal), {so['shortened']} shortened, {so['straight']} straight")
    # Every placed one on the B-rep; those pulled back (cells that would fold) are few.
    assert d[:so["placed"]].max() <= 1e-7 * diag
    assert so["placed"] >= 0.9 * len(mids)
