"""Mesh formats against independent readers and writers: VTK (vtkUnstructuredGridReader/Writer,
vtkXMLUnstructuredGridReader), meshio, and a small pure-Python LS-DYNA keyword parser.

Round trips must keep every node (coordinates to 1e-12, in practice exactly), every cell (type and
connectivity) and every region id."""

import subprocess
import warnings

import meshio
import numpy as np
import pytest
import vtk

import hexdom_oracles as O
from hexdom_test_support import data_file, data_params

# fertility_hex.vtk is an LS-DYNA file with a .vtk name: the readers sniff it.
K_FILES = data_params("**/*.k") + data_params("fertility/fertility_hex.vtk")
STRUCTURES = [p for pat in ("**/*_withtet.k", "**/*_withouttet.k", "**/*_notet.k", "**/*_hex_edit.k",
                            "rod_demo/rod_polycube_structure_hex.k", "joint/*_structure_hex.k")
              for p in data_params(pat)]
MESHIO_TYPES = {"triangle": O.TRIANGLE, "quad": O.QUAD, "tetra": O.TET, "hexahedron": O.HEX,
                "wedge": O.WEDGE}


def meshio_read(path, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return meshio.read(str(path), **kw)


# meshio numbers wedges as Gmsh and Abaqus do (first triangle's normal pointing inward) and
# permutes VTK files' wedges on reading and writing; this permutation converts either way.
MESHIO_WEDGE = [0, 2, 1, 3, 5, 4]


def meshio_cells(m):
    """(types, list of node lists in VTK order) of a meshio mesh, in file order of the blocks."""
    types, conn = [], []
    for block in m.cells:
        for row in block.data:
            types.append(MESHIO_TYPES[block.type])
            n = [int(i) for i in row]
            conn.append([n[i] for i in MESHIO_WEDGE] if block.type == "wedge" else n)
    return np.array(types), conn


def cells_of(mesh):
    return [mesh.cells[c, :O.NODES[int(t)]].tolist() for c, t in enumerate(mesh.types)]


def assert_same_mesh(a, b, what):
    assert a.V.shape == b.V.shape, what
    assert np.abs(a.V - b.V).max(initial=0) <= 1e-12, what
    assert np.array_equal(a.types, b.types), what
    assert np.array_equal(a.cells, b.cells), what
    assert np.array_equal(a.region, b.region), what


def run(hexdom_bin, *args):
    return subprocess.run([str(hexdom_bin), *map(str, args)], capture_output=True, text=True)


# ---------------------------------------------------------------------------------------------
# LS-DYNA keyword files

def expected_from_k(k):
    """Cells the keyword parser implies, as (VTK type, node ids, part id)."""
    out = []
    for _, pid, n in k["shells"]:
        tri = n[3] == n[2] or n[3] == 0
        out.append((O.TRIANGLE if tri else O.QUAD, n[:3] if tri else n, pid))
    for _, pid, n in k["solids"]:
        distinct = list(dict.fromkeys(n))
        t = {8: O.HEX, 6: O.WEDGE, 4: O.TET}[len(distinct)]
        out.append((t, n if t == O.HEX else distinct, pid))
    return out


@pytest.mark.parametrize("path", K_FILES)
def test_every_k_file_loads(core, path):
    """Nodes, ids, cell types, connectivity and part ids as a pure-Python parser reads them."""
    k = O.parse_k(path)
    V, cells, types, region, node_ids, element_ids = core._hexdom.read_k(str(path))
    mesh = core.read_mesh(path)
    assert np.array_equal(mesh.V, V) and np.array_equal(mesh.cells, cells)
    ids = list(k["nodes"])
    assert node_ids.tolist() == ids
    assert np.array_equal(V, np.array([k["nodes"][i] for i in ids]))
    assert element_ids.tolist() == [e[0] for e in k["shells"]] + [e[0] for e in k["solids"]]
    index = {nid: i for i, nid in enumerate(ids)}
    expected = expected_from_k(k)
    assert len(types) == len(expected) > 0
    for c, (t, n, pid) in enumerate(expected):
        assert types[c] == t and region[c] == pid, f"cell {c}"
        ours = cells[c, :O.NODES[t]].tolist()
        want = [index[i] for i in n]
        if t == O.WEDGE:  # reordered into a VTK wedge: same nodes, orientation checked below
            assert sorted(ours) == sorted(want), f"cell {c}"
        else:
            assert ours == want, f"cell {c}"
        assert np.all(cells[c, O.NODES[t]:] == -1)


@pytest.mark.parametrize("path", STRUCTURES)
def test_structure_blocks_are_positively_oriented(core, path):
    """Every block of every structure in the data is positively oriented (REFERENCE.md): VTK's
    signed volumes of the cells as we read them are all positive, and so are ours."""
    mesh = core.read_mesh(path)
    vtk_vol = O.signed_volumes(O.vtk_grid(mesh.V, mesh.cells, mesh.types))
    _, _, vol = core.cell_metrics(mesh)
    assert np.all(vtk_vol > 0), np.flatnonzero(vtk_vol <= 0)
    assert np.all(vol > 0)
    # Ours is the exact volume of the trilinear (hex) / bilinear-linear (wedge) map; VTK integrates
    # over a triangulation. They differ by the faces' non-planarity: about 1% for rockerarm.
    assert vol.sum() == pytest.approx(vtk_vol.sum(), rel=2e-2)
    ind = np.array([O.cell_volume(mesh.V[mesh.cells[c, :O.NODES[int(t)]]], int(t))
                    for c, t in enumerate(mesh.types)])
    assert np.allclose(vol, ind, rtol=1e-12, atol=1e-15 * np.abs(ind).max())


@pytest.mark.parametrize("binary", [False, True], ids=["ascii", "binary"])
@pytest.mark.parametrize("path", K_FILES)
def test_k_vtk_k_round_trip(core, path, binary, tmp_path):
    original = core.read_mesh(path)
    core.write_mesh(tmp_path / "a.vtk", original, binary=binary)
    via_vtk = core.read_mesh(tmp_path / "a.vtk")
    assert_same_mesh(original, via_vtk, ".k -> .vtk")
    core.write_mesh(tmp_path / "b.k", via_vtk)
    back = core.read_mesh(tmp_path / "b.k")
    assert_same_mesh(original, back, ".k -> .vtk -> .k")
    assert np.array_equal(back.V, original.V)  # %.17g: exact


# ---------------------------------------------------------------------------------------------
# The rockerarm structure through the program, read by VTK and meshio

def independent_volumes(points, types, conn):
    return np.array([O.cell_volume(points[n], int(t)) for t, n in zip(types, conn)])


def test_rockerarm_structure_converts_to_vtk_cells(hexdom_bin, tmp_path):
    src = data_file("rockerarm/rockerarm_polycube_withtet.k")
    out = tmp_path / "s.vtk"
    r = run(hexdom_bin, "convert", "-i", src, "-o", out)
    assert r.returncode == 0, r.stderr
    g, dtype = O.read_legacy_vtk(out)
    assert O.cell_type_counts(g) == {O.HEX: 60, O.WEDGE: 11, O.TET: 2}
    assert g.GetNumberOfPoints() == 153 and dtype == np.float64
    assert np.all(O.signed_volumes(g) > 0)
    P, types, conn = O.grid_arrays(g)
    assert np.all(independent_volumes(P, types, conn) > 0)

    m = meshio_read(out)
    mtypes, mconn = meshio_cells(m)
    assert {t: int(np.sum(mtypes == t)) for t in set(mtypes.tolist())} == {O.HEX: 60, O.WEDGE: 11, O.TET: 2}
    assert np.array_equal(m.points, P)
    assert np.all(independent_volumes(m.points, mtypes, mconn) > 0)
    regions = np.concatenate([np.ravel(a) for a in m.cell_data["region"]])
    assert len(regions) == 73 and set(regions.tolist()) == {1}  # the file's only part id


FORMATS = ["vtk", "vtk-binary", "vtu", "inp"]


def read_with_meshio(path):
    # For .inp, meshio keeps the file's C3D6 order, which is its own wedge order: meshio_cells'
    # permutation then checks that we wrote VTK's [a b c d e f] as Abaqus' a c b d f e.
    m = meshio_read(path)
    types, conn = meshio_cells(m)
    return m, types, conn


@pytest.mark.parametrize("fmt", FORMATS)
@pytest.mark.parametrize("rel", ["rockerarm/rockerarm_polycube_withtet.k", "rockerarm/rockerarm3_hex.vtk",
                                 "hepta/hepta_initial_polycube.k"])
def test_written_formats_read_by_meshio(core, rel, fmt, tmp_path):
    mesh = core.read_mesh(data_file(rel))
    ext = "vtk" if fmt.startswith("vtk") else fmt
    out = tmp_path / f"mesh.{ext}"
    core.write_mesh(out, mesh, binary=fmt == "vtk-binary")
    m, types, conn = read_with_meshio(out)
    # meshio groups cells into blocks by type; compare as multisets keyed by type and nodes.
    ours = sorted((int(t), tuple(n)) for t, n in zip(mesh.types, cells_of(mesh)))
    theirs = sorted((int(t), tuple(n)) for t, n in zip(types, conn))
    assert theirs == ours
    assert np.abs(m.points - mesh.V).max() <= 1e-12
    if fmt != "inp":
        regions = np.concatenate([np.ravel(a) for a in m.cell_data["region"]])
        assert np.array_equal(np.sort(regions), np.sort(mesh.region))
    else:
        # Element sets: one per region, and EALL holding every volume element.
        volume = int(np.isin(mesh.types, [O.HEX, O.WEDGE, O.TET]).sum())
        sets = {k.upper(): sum(len(a) for a in v) for k, v in m.cell_sets.items()}
        for r in set(mesh.region.tolist()):
            assert sets[f"REGION_{r}"] == int(np.sum(mesh.region == r))
        if volume:
            assert sets["EALL"] == volume
    solid = [i for i, t in enumerate(types) if t in (O.HEX, O.WEDGE, O.TET)]
    if "withtet" in rel:
        assert np.all(independent_volumes(m.points, types[solid], [conn[i] for i in solid]) > 0)


@pytest.mark.parametrize("binary", [False, True], ids=["ascii", "binary"])
def test_vtk_reader_reads_our_files_exactly(core, binary, tmp_path):
    mesh = core.read_mesh(data_file("rockerarm/rockerarm_polycube_withtet.k"))
    core.write_mesh(tmp_path / "m.vtk", mesh, binary=binary)
    g, dtype = O.read_legacy_vtk(tmp_path / "m.vtk")
    P, types, conn = O.grid_arrays(g)
    assert dtype == np.float64 and np.array_equal(P, mesh.V)
    assert np.array_equal(types, mesh.types) and conn == cells_of(mesh)
    region = vtk.util.numpy_support.vtk_to_numpy(g.GetCellData().GetArray("region"))
    assert np.array_equal(region, mesh.region)
    core.write_mesh(tmp_path / "m.vtu", mesh)
    P, types, conn = O.grid_arrays(O.read_vtu(tmp_path / "m.vtu"))
    assert np.array_equal(P, mesh.V) and np.array_equal(types, mesh.types) and conn == cells_of(mesh)


@pytest.mark.parametrize("writer", ["vtk-ascii", "vtk-binary", "meshio-ascii", "meshio-binary"])
def test_reads_vtk_files_written_by_others(core, writer, tmp_path):
    """Files from VTK's own writer (5.1 layout: OFFSETS/CONNECTIVITY, vtktypeint64) and meshio."""
    mesh = core.read_mesh(data_file("rockerarm/rockerarm_polycube_withtet.k"))
    g = O.vtk_grid(mesh.V, mesh.cells, mesh.types)
    arr = vtk.util.numpy_support.numpy_to_vtk(mesh.region.astype(np.int32), deep=True)
    arr.SetName("region")
    g.GetCellData().AddArray(arr)
    path = tmp_path / "other.vtk"
    if writer.startswith("vtk"):
        w = vtk.vtkUnstructuredGridWriter()
        w.SetFileName(str(path))
        w.SetInputData(g)
        w.SetFileTypeToBinary() if writer.endswith("binary") else w.SetFileTypeToASCII()
        w.Write()
    else:
        P, types, conn = O.grid_arrays(g)
        blocks = [(name, np.array([[n[i] for i in MESHIO_WEDGE] if code == O.WEDGE else n
                                   for t, n in zip(types, conn) if t == code], dtype=np.int64))
                  for name, code in MESHIO_TYPES.items() if code in types]
        order = [np.flatnonzero(types == MESHIO_TYPES[name]) for name, _ in blocks]
        m = meshio.Mesh(P, blocks, cell_data={"region": [mesh.region[o] for o in order]})
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            meshio.write(str(path), m, file_format="vtk", binary=writer.endswith("binary"))
        perm = np.concatenate(order)
        mesh = type(mesh)(mesh.V, mesh.cells[perm], mesh.types[perm], mesh.region[perm])
    back = core.read_mesh(path)
    assert np.abs(back.V - mesh.V).max() == 0
    assert np.array_equal(back.types, mesh.types) and np.array_equal(back.cells, mesh.cells)
    assert np.array_equal(back.region, mesh.region)


# ---------------------------------------------------------------------------------------------
# Surfaces: STL and OBJ

def triangles(surface):
    return surface.V[surface.F]


def test_surface_round_trips(core, tmp_path):
    s = core.read_surface(data_file("rockerarm/rockerarm.k"))
    assert s.F.shape == (23312, 3)
    T = triangles(s)
    # STL: binary, single precision, no patch ids.
    core.write_surface(tmp_path / "s.stl", s)
    stl = core.read_surface(tmp_path / "s.stl")
    assert stl.F.shape == s.F.shape and stl.V.shape == s.V.shape
    assert np.array_equal(triangles(stl), T.astype(np.float32).astype(np.float64))
    # OBJ: full precision, one group per patch (triangles come back grouped by patch).
    core.write_surface(tmp_path / "s.obj", s)
    obj = core.read_surface(tmp_path / "s.obj")
    key = lambda tris, patch: sorted((int(p),) + tuple(t.ravel()) for t, p in zip(tris, patch))
    assert key(triangles(obj), obj.patch) == key(T, s.patch)
    # VTK and .k keep order, coordinates and patches exactly.
    for ext in ("vtk", "k"):
        core.write_surface(tmp_path / f"s.{ext}", s)
        back = core.read_surface(tmp_path / f"s.{ext}")
        assert np.array_equal(triangles(back), T) and np.array_equal(back.patch, s.patch), ext
    # meshio reads what we wrote.
    for ext in ("stl", "obj", "vtk"):
        m = meshio_read(tmp_path / f"s.{ext}")
        types, conn = meshio_cells(m)
        assert len(conn) == len(s.F) and set(types.tolist()) == {O.TRIANGLE}, ext
        assert np.allclose(np.sort(m.points[np.array(conn)].reshape(-1, 9), axis=0),
                           np.sort(T.reshape(-1, 9), axis=0), rtol=0, atol=1e-6), ext


def test_patches_survive_obj_and_vtk(core, tmp_path):
    s = core.read_surface(data_file("rockerarm/rockerarm_indexPatch_hexdom.k"))
    assert len(set(s.patch.tolist())) > 10
    for ext in ("obj", "vtk"):
        core.write_surface(tmp_path / f"p.{ext}", s)
        back = core.read_surface(tmp_path / f"p.{ext}")
        for p in set(s.patch.tolist()):
            assert np.sum(back.patch == p) == np.sum(s.patch == p), (ext, p)


@pytest.mark.parametrize("fmt", ["stl-ascii", "stl-binary", "obj"])
def test_reads_surfaces_written_by_meshio(core, fmt, tmp_path):
    s = core.read_surface(data_file("hepta/hepta.k"))
    path = tmp_path / ("m.stl" if fmt.startswith("stl") else "m.obj")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        meshio.write(str(path), meshio.Mesh(s.V, [("triangle", s.F)]),
                     **({"binary": fmt == "stl-binary"} if fmt.startswith("stl") else {}))
    back = core.read_surface(path)
    assert back.F.shape == s.F.shape
    tol = 1e-6 * np.abs(s.V).max() if fmt.startswith("stl") else 1e-12
    assert np.abs(triangles(back) - triangles(s)).max() <= tol  # same order, merged vertices


def test_volume_mesh_cannot_be_written_as_surface(core, tmp_path):
    mesh = core.read_mesh(data_file("rockerarm/rockerarm_polycube_withtet.k"))
    for ext in ("stl", "obj"):
        with pytest.raises(core.InputError, match=rf"v\.{ext}"):
            core.write_mesh(tmp_path / f"v.{ext}", mesh)
        assert not (tmp_path / f"v.{ext}").exists()
    assert list(tmp_path.iterdir()) == []


def test_python_errors_name_file_and_line(core, tmp_path):
    bad = tmp_path / "bad.k"
    bad.write_text("*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,nan\n*END\n")
    with pytest.raises(core.InputError, match=r"bad\.k:4: "):
        core.read_mesh(bad)
    with pytest.raises(core.InputError, match=r"unknown file format"):
        core.write_mesh(tmp_path / "x.xyz", core.read_mesh(data_file("hepta/hepta.k")))
    assert not (tmp_path / "x.xyz").exists()
