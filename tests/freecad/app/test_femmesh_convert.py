"""core.Mesh <-> Fem.FemMesh: SMDS node order, ids, counters, round trips."""

import numpy as np
import pytest

import Fem

from HexDomWorkbench import core
from HexDomWorkbench.convert import femmesh

import fc_testdata


def sample():
    V, cells, types, region = fc_testdata.mixed_sample()
    return core.Mesh(V, cells, types, region)


def test_counters_match_the_cell_types():
    fem = femmesh.to_femmesh(sample())
    assert (fem.NodeCount, fem.HexaCount, fem.PrismCount, fem.TetraCount) == (16, 1, 2, 6)
    assert fem.VolumeCount == 9


def test_smds_order_of_each_type():
    mesh = sample()
    fem = femmesh.to_femmesh(mesh)
    hex_vtk = mesh.cells[0] + 1
    assert fem.getElementNodes(1) == tuple(hex_vtk[[0, 3, 2, 1, 4, 7, 6, 5]].tolist())
    wedge_vtk = mesh.cells[1, :6] + 1
    assert fem.getElementNodes(2) == tuple(wedge_vtk.tolist())
    tet_vtk = mesh.cells[3, :4] + 1
    assert fem.getElementNodes(4) == tuple(tet_vtk[[0, 2, 1, 3]].tolist())


def test_node_and_cell_ids_follow_rows():
    mesh = sample()
    fem = femmesh.to_femmesh(mesh)
    assert sorted(fem.Nodes) == list(range(1, 17))
    assert sorted(fem.Volumes) == list(range(1, 10))
    for i, p in enumerate(mesh.V):
        assert tuple(fem.Nodes[i + 1]) == pytest.approx(tuple(p))


def test_round_trip_is_exact():
    mesh = sample()
    back = femmesh.from_femmesh(femmesh.to_femmesh(mesh))
    np.testing.assert_array_equal(back.V, mesh.V)
    np.testing.assert_array_equal(back.cells, mesh.cells)
    np.testing.assert_array_equal(back.types, mesh.types)


def test_quality_survives_the_round_trip():
    mesh = sample()
    back = femmesh.from_femmesh(femmesh.to_femmesh(mesh))
    np.testing.assert_allclose(core.cell_metrics(back)[0], core.cell_metrics(mesh)[0])
    assert min(core.cell_metrics(back)[0]) > 0.5


def test_surface_cells_become_faces():
    V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
    cells = np.array([[0, 1, 2, 3, -1, -1, -1, -1], [0, 1, 2, -1, -1, -1, -1, -1]], np.int32)
    mesh = core.Mesh(V, cells, np.array([9, 5], np.int32), np.zeros(2, np.int32))
    fem = femmesh.to_femmesh(mesh)
    assert (fem.QuadrangleCount, fem.TriangleCount, fem.VolumeCount) == (1, 1, 0)
    back = femmesh.from_femmesh(fem)
    np.testing.assert_array_equal(back.types, [9, 5])
    np.testing.assert_array_equal(back.cells, cells)


def test_unsupported_cell_type_is_refused():
    V = np.zeros((5, 3))
    cells = np.array([[0, 1, 2, 3, 4, -1, -1, -1]], np.int32)
    mesh = core.Mesh(V, cells, np.array([14], np.int32), np.zeros(1, np.int32))  # pyramid
    with pytest.raises(ValueError, match="cell 0: VTK cell type 14"):
        femmesh.to_femmesh(mesh)


def test_foreign_ids_and_quadratic_tets_are_read():
    """A FemMesh from elsewhere (Gmsh, Netgen): sparse ids, quadratic elements (SMDS order: the
    corners, then the mid-edge nodes of s0s1, s1s2, s2s0, s0s3, s1s3, s2s3)."""
    fem = Fem.FemMesh()
    pts = {10: (0, 0, 0), 20: (1, 0, 0), 30: (0, 1, 0), 40: (0, 0, 1)}
    for nid, p in pts.items():
        fem.addNode(*p, nid)
    smds_corners = [10, 30, 20, 40]  # VTK tet 10 20 30 40 in SMDS order
    s = smds_corners
    mids = {}
    for k, (a, b) in enumerate([(s[0], s[1]), (s[1], s[2]), (s[2], s[0]), (s[0], s[3]), (s[1], s[3]), (s[2], s[3])]):
        nid = 100 + k
        fem.addNode(*[(pa + pb) / 2 for pa, pb in zip(pts[a], pts[b])], nid)
        mids[(a, b)] = nid
    fem.addVolume(smds_corners + list(mids.values()), 7)
    mesh, node_ids, cell_ids = femmesh.from_femmesh(fem, with_ids=True)
    assert cell_ids.tolist() == [7]
    assert mesh.types.tolist() == [core.TET10]
    ids = [int(node_ids[i]) for i in mesh.cells[0, :10]]
    assert ids[:4] == [10, 20, 30, 40]
    # Each mid-edge node is on its VTK edge: (0,1) (1,2) (2,0) (0,3) (1,3) (2,3).
    for k, (i, j) in enumerate([(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]):
        a, b = ids[i], ids[j]
        assert ids[4 + k] == mids.get((a, b), mids.get((b, a)))
    assert core.quality_report(mesh)["total_volume"] == pytest.approx(1.0 / 6.0)
    corners = femmesh.from_femmesh(fem, corners_only=True)
    assert corners.types.tolist() == [core.TET]
    assert core.cell_metrics(corners)[2][0] == pytest.approx(1.0 / 6.0)


def test_pyramids_from_elsewhere_are_refused():
    fem = Fem.FemMesh()
    for i, p in enumerate([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1)]):
        fem.addNode(*p, i + 1)
    fem.addVolume([1, 2, 3, 4, 5], 1)
    with pytest.raises(ValueError, match="element 1 has 5 nodes"):
        femmesh.from_femmesh(fem)
