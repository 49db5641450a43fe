"""`hexdom convert` reading .inp and .vtu files written by other programs.

Oracles: Gmsh (python3-gmsh) writes the .inp meshes and knows their element counts; VTK's own
vtkXMLUnstructuredGridWriter writes the .vtu files in every data mode, header type, byte order and
compressor; meshio writes .vtu too and reads our output back; VTK's vtkCellSizeFilter measures the
cells' signed volumes."""

import itertools
import re
import subprocess

import meshio
import numpy as np
import pytest
import vtk

import hexdom_oracles as oracles

gmsh = pytest.importorskip("gmsh")

BOX = (1.0, 2.0, 3.0)
VTK_TYPES = {"tet": 10, "prism": 13, "hex": 12, "tet10": 24}


def _convert(hexdom_bin, src, out):
    return subprocess.run([str(hexdom_bin), "convert", "-i", str(src), "-o", str(out)], capture_output=True, text=True)


def _gmsh_box(path, kind):
    """A box meshed by Gmsh (tets, second-order tets, hexes, or prisms extruded from triangles),
    written as .inp with a physical volume; returns Gmsh's count of 3D elements."""
    gmsh.clear()
    gmsh.model.add(kind)
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.6)
    if kind in ("hex", "prism"):
        oracles.gmsh_structured_box(gmsh, kind, BOX, 3 if kind == "hex" else 4)
    else:
        gmsh.model.occ.addBox(0, 0, 0, *BOX)
        gmsh.model.occ.synchronize()
    gmsh.model.addPhysicalGroup(3, [1], 7)
    gmsh.model.mesh.generate(3)
    if kind == "tet10":
        gmsh.model.mesh.setOrder(2)
    gmsh.write(str(path))
    types, tags, _ = gmsh.model.mesh.getElements(3)
    return sum(len(t) for t in tags)


@pytest.fixture(scope="module")
def gmsh_inp(tmp_path_factory):
    d = tmp_path_factory.mktemp("gmsh_inp")
    gmsh.initialize()
    gmsh.option.setNumber("General.Verbosity", 0)
    try:
        return {k: (d / f"{k}.inp", _gmsh_box(d / f"{k}.inp", k)) for k in VTK_TYPES}
    finally:
        gmsh.finalize()


@pytest.mark.parametrize("kind", list(VTK_TYPES))
def test_inp_written_by_gmsh_reads_with_positive_cells_filling_the_box(hexdom_bin, gmsh_inp, tmp_path, kind):
    src, count = gmsh_inp[kind]
    out = tmp_path / f"{kind}.vtu"
    r = _convert(hexdom_bin, src, out)
    assert r.returncode == 0, r.stderr
    g = oracles.read_vtu(out)
    assert oracles.cell_type_counts(g) == {VTK_TYPES[kind]: count}
    vol = oracles.signed_volumes(g)
    assert vol.min() > 0, f"{(vol <= 0).sum()} cells of Gmsh's {kind} mesh read inverted"
    assert vol.sum() == pytest.approx(np.prod(BOX), rel=1e-9)
    region = meshio.read(out).cell_data["region"][0]
    assert set(np.ravel(region).tolist()) == {1}  # Gmsh's ELSET=Volume1, the file's first element set


@pytest.fixture(scope="module")
def sources(tmp_path_factory, hexdom_bin, gmsh_inp):
    """Legacy .vtk meshes: Gmsh's prisms and second-order tets (through our .inp reader) and a
    hex / prism / tet mesh with several regions written by hand."""
    d = tmp_path_factory.mktemp("vtu_sources")
    out = {}
    for kind in ("prism", "tet10"):
        out[kind] = d / f"{kind}.vtk"
        assert _convert(hexdom_bin, gmsh_inp[kind][0], out[kind]).returncode == 0
    mixed = meshio.Mesh(
        np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1],
                  [2, 0, 0], [2, 1, 0], [0.5, 0.5, 2.0]], dtype=float),
        [("hexahedron", np.array([[0, 1, 2, 3, 4, 5, 6, 7]])), ("wedge", np.array([[1, 8, 2, 5, 9, 6]])),
         ("tetra", np.array([[4, 5, 6, 10]]))],
        cell_data={"region": [np.array([3], np.int32), np.array([-4], np.int32), np.array([5], np.int32)]})
    mixed.write(d / "mixed_meshio.vtk", binary=False)
    out["mixed"] = d / "mixed.vtk"  # VTK 9.1 does not read the region of meshio's VTK 5.1 file: ours is 4.2
    assert _convert(hexdom_bin, d / "mixed_meshio.vtk", out["mixed"]).returncode == 0
    return out


def _same(a, b):
    ma, mb = meshio.read(a), meshio.read(b)
    assert np.array_equal(ma.points, mb.points)
    assert [c.type for c in ma.cells] == [c.type for c in mb.cells]
    for ca, cb in zip(ma.cells, mb.cells):
        assert np.array_equal(ca.data, cb.data)
    for ra, rb in zip(ma.cell_data["region"], mb.cell_data["region"]):
        assert np.array_equal(ra, rb)


MODES = ["ascii", "binary", "appended_raw", "appended_base64"]


@pytest.mark.parametrize("source", ["prism", "tet10", "mixed"])
def test_vtu_in_every_layout_vtk_writes_reads_as_the_source(hexdom_bin, sources, tmp_path, source):
    r = vtk.vtkUnstructuredGridReader()
    r.SetFileName(str(sources[source]))
    r.Update()
    for mode, zlib, uint64, big in itertools.product(MODES, (False, True), (False, True), (False, True)):
        if big and (zlib or uint64):
            continue  # big-endian files once per data mode
        w = vtk.vtkXMLUnstructuredGridWriter()
        w.SetInputData(r.GetOutput())
        name = tmp_path / f"{mode}_{'zlib' if zlib else 'raw'}_{64 if uint64 else 32}_{'be' if big else 'le'}.vtu"
        w.SetFileName(str(name))
        if mode == "ascii":
            w.SetDataModeToAscii()
        elif mode == "binary":
            w.SetDataModeToBinary()
        else:
            w.SetDataModeToAppended()
            w.SetEncodeAppendedData(mode == "appended_base64")
        w.SetCompressorTypeToZLib() if zlib else w.SetCompressorTypeToNone()
        w.SetHeaderTypeToUInt64() if uint64 else w.SetHeaderTypeToUInt32()
        w.SetByteOrderToBigEndian() if big else w.SetByteOrderToLittleEndian()
        assert w.Write() == 1
        back = tmp_path / "back.vtk"
        res = _convert(hexdom_bin, name, back)
        assert res.returncode == 0, f"{name.name}: {res.stderr}"
        _same(sources[source], back)


def test_vtu_written_by_meshio_reads_as_the_source(hexdom_bin, sources, tmp_path):
    m = meshio.read(sources["mixed"])
    for binary, compression in ((False, None), (True, None), (True, "zlib")):
        name = tmp_path / f"meshio_{binary}_{compression}.vtu"
        meshio.vtu.write(name, m, binary=binary, compression=compression)
        back = tmp_path / "back.vtk"
        res = _convert(hexdom_bin, name, back)
        assert res.returncode == 0, f"{name.name}: {res.stderr}"
        _same(sources["mixed"], back)


def _fails_cleanly(hexdom_bin, src, tmp_path, *texts):
    out = tmp_path / "never.vtk"
    r = _convert(hexdom_bin, src, out)
    assert r.returncode == 1, r.stderr
    assert str(src) in r.stderr
    for t in texts:
        assert t in r.stderr, r.stderr
    assert not out.exists()


def test_malformed_vtu_and_inp_fail_with_file_and_line(hexdom_bin, sources, tmp_path):
    m = meshio.read(sources["mixed"])
    ok = tmp_path / "ok.vtu"
    meshio.vtu.write(ok, m, binary=False)
    text = ok.read_text()
    bad = tmp_path / "truncated.vtu"
    bad.write_text(text[: len(text) // 2])
    _fails_cleanly(hexdom_bin, bad, tmp_path, "truncated.vtu:")
    lzma = tmp_path / "lzma.vtu"
    meshio.vtu.write(lzma, m, binary=True, compression="lzma")
    _fails_cleanly(hexdom_bin, lzma, tmp_path, "lzma.vtu:", "vtkLZMADataCompressor is not supported")
    wrong_point = tmp_path / "wrong_point.vtu"
    at = text.index(">", text.index('Name="connectivity"')) + 1
    wrong_point.write_text(text[:at] + re.sub(r"\d+", "70", text[at:], count=1))  # the first node: no such point
    _fails_cleanly(hexdom_bin, wrong_point, tmp_path, "refers to point 70")
    wrong_count = tmp_path / "wrong_count.vtu"
    wrong_count.write_text(text[:at] + "\n0 " + text[at:])
    _fails_cleanly(hexdom_bin, wrong_count, tmp_path, "wrong_count.vtu:", "connectivity: 19 values, expected 18")
    inp = tmp_path / "bad.inp"
    inp.write_text("*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4\n")
    _fails_cleanly(hexdom_bin, inp, tmp_path, "bad.inp:6:", "element 1 refers to node 4")
