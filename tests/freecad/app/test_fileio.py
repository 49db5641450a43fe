"""Import / export through HexDomWorkbench.fileio (what Init.py registers and the commands use)."""

import base64
import os

import numpy as np
import pytest

import FreeCAD

from HexDomWorkbench import core, fileio
from HexDomWorkbench.objects import hex_mesh

import fc_testdata


def sample():
    return core.Mesh(*fc_testdata.mixed_sample())


@pytest.mark.parametrize("ext", [".k", ".vtk", ".vtu"])
def test_insert_reads_each_format(doc, tmp_path, ext):
    path = str(tmp_path / ("sample" + ext))
    core.write_mesh(path, sample())
    fileio.insert(path, doc.Name)
    objs = [o for o in doc.Objects if hex_mesh.is_hex_mesh(o)]
    assert len(objs) == 1
    obj = objs[0]
    assert obj.Label == "sample" and obj.SourceFile == os.path.abspath(path)
    assert (obj.HexCount, obj.PrismCount, obj.TetCount) == (1, 2, 6)
    np.testing.assert_allclose(hex_mesh.get_mesh(obj).V, sample().V, atol=1e-12)


def test_open_makes_a_new_document(tmp_path):
    path = str(tmp_path / "opened.vtk")
    core.write_mesh(path, sample())
    doc = fileio.open(path)
    try:
        assert doc.Label == "opened"
        assert [o.TetCount for o in doc.Objects if hex_mesh.is_hex_mesh(o)] == [6]
    finally:
        FreeCAD.closeDocument(doc.Name)


@pytest.mark.parametrize("ext", [".vtk", ".vtu", ".k", ".inp", ".msh"])
def test_export_writes_what_core_reads_back(doc, tmp_path, ext):
    from HexDomWorkbench import make
    obj = make.make_hex_mesh(doc, sample())
    path = str(tmp_path / ("out" + ext))
    fileio.export([obj], path)
    assert os.path.getsize(path) > 0
    if ext == ".inp":
        text = open(path).read().upper()
        assert "C3D8" in text and "C3D6" in text and "C3D4" in text
    back, expected = fileio.read_mesh(path), sample()
    np.testing.assert_allclose(back.V, expected.V, atol=1e-9)
    np.testing.assert_array_equal(back.types, expected.types)
    # Formats may start a cell at another corner (.k stores prisms as collapsed hexes): compare
    # node sets and orientation-sensitive quality.
    assert [sorted(c) for c in back.cells.tolist()] == [sorted(c) for c in expected.cells.tolist()]
    np.testing.assert_allclose(core.cell_metrics(back)[0], core.cell_metrics(expected)[0])


def test_import_error_raises_core_error_and_adds_nothing(doc, tmp_path):
    bad = tmp_path / "bad.k"
    bad.write_text("*KEYWORD\n*ELEMENT_SOLID\n1 1 1 2\n*END\n")
    with pytest.raises(core.InputError):
        fileio.insert(str(bad), doc.Name)
    with pytest.raises(core.InputError):
        fileio.insert(str(tmp_path / "missing.vtk"), doc.Name)
    assert [o for o in doc.Objects if hex_mesh.is_hex_mesh(o)] == []


def test_export_error_leaves_no_file(doc, tmp_path):
    from HexDomWorkbench import make
    obj = make.make_hex_mesh(doc, sample())
    path = tmp_path / "out.xyz"
    with pytest.raises(core.Error):
        fileio.export([obj], str(path))
    assert not path.exists()
    with pytest.raises(ValueError, match="exactly one mesh"):
        fileio.export([], str(tmp_path / "none.vtk"))


def _vtu_text(fmt):
    mesh = sample()
    conn = np.concatenate([c[:core.NODE_COUNT[t]] for c, t in zip(mesh.cells, mesh.types)])
    offsets = np.cumsum([core.NODE_COUNT[t] for t in mesh.types])

    def arr(values, vtype, name, ncomp=1):
        if fmt == "ascii":
            body = " ".join(str(v) for v in np.ravel(values))
        else:
            raw = np.asarray(values, dtype={"Float64": "<f8", "Int32": "<i4",
                                            "UInt8": "u1"}[vtype]).tobytes()
            body = base64.b64encode(np.uint32(len(raw)).tobytes() + raw).decode()
        return ('<DataArray type="{}" Name="{}" NumberOfComponents="{}" format="{}">{}'
                '</DataArray>'.format(vtype, name, ncomp, fmt, body))

    return ('<?xml version="1.0"?><VTKFile type="UnstructuredGrid" version="0.1" '
            'byte_order="LittleEndian"><UnstructuredGrid><Piece NumberOfPoints="{}" '
            'NumberOfCells="{}"><Points>{}</Points><Cells>{}{}{}</Cells><CellData>{}</CellData>'
            '</Piece></UnstructuredGrid></VTKFile>').format(
                len(mesh.V), len(mesh.types), arr(mesh.V, "Float64", "Points", 3),
                arr(conn, "Int32", "connectivity"), arr(offsets, "Int32", "offsets"),
                arr(mesh.types, "UInt8", "types"), arr(mesh.region, "Int32", "region"))


@pytest.mark.parametrize("fmt", ["ascii", "binary"])
def test_vtu_reader_handles_ascii_and_uint32_headers(tmp_path, fmt):
    path = tmp_path / "hand.vtu"
    path.write_text(_vtu_text(fmt))
    mesh = fileio.read_mesh(str(path))
    np.testing.assert_allclose(mesh.V, sample().V)
    np.testing.assert_array_equal(mesh.cells, sample().cells)
    np.testing.assert_array_equal(mesh.region, sample().region)


def test_vtu_reader_refuses_other_compressors_and_broken_files(tmp_path):
    path = tmp_path / "lz4.vtu"
    path.write_text(_vtu_text("ascii").replace('byte_order=', 'compressor="vtkLZ4DataCompressor" '
                                                             'byte_order='))
    with pytest.raises(core.InputError, match="lz4.vtu:1: compressor vtkLZ4DataCompressor is not supported"):
        fileio.read_mesh(str(path))
    broken = tmp_path / "broken.vtu"
    broken.write_text("<VTKFile")
    with pytest.raises(core.InputError, match="broken.vtu:1: tag <VTKFile> is not closed"):
        fileio.read_mesh(str(broken))
