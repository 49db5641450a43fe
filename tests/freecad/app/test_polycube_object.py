"""HexDom Polycube: .k structure import and export, save and reopen."""

import os
import shutil

import numpy as np
import pytest

import FreeCAD

from HexDomWorkbench import api, core, make
from HexDomWorkbench.objects import polycube

import fc_testdata
from conftest import reopen

STRUCTURE = fc_testdata.example_path("lbracket_structure.k")


def test_import_structure(doc):
    obj = api.import_structure(STRUCTURE, doc)
    assert obj.Proxy.Type == "HexDom::Polycube" and polycube.is_polycube(obj)
    assert (obj.HexBlocks, obj.PrismBlocks, obj.TetBlocks, obj.PointCount) == (3, 1, 0, 18)
    assert obj.Label == "lbracket_structure"
    expected = core.read_mesh(STRUCTURE)
    got = polycube.get_structure(obj)
    np.testing.assert_array_equal(got.V, expected.V)
    np.testing.assert_array_equal(got.cells, expected.cells)
    np.testing.assert_array_equal(got.types, expected.types)


def test_export_round_trip(doc, tmp_path):
    obj = api.import_structure(STRUCTURE, doc)
    for ext in (".k", ".vtk"):
        out = str(tmp_path / ("s" + ext))
        api.export_structure(obj, out)
        back = core.read_mesh(out)
        np.testing.assert_allclose(back.V, polycube.get_structure(obj).V, rtol=0, atol=1e-9)
        np.testing.assert_array_equal(back.cells, polycube.get_structure(obj).cells)
    with pytest.raises(ValueError, match="not a HexDom Polycube"):
        api.export_structure(make.make_hex_mesh(doc), str(tmp_path / "x.k"))


def test_save_reopen_without_the_file(doc, tmp_path):
    path = str(tmp_path / "copy.k")
    shutil.copy(STRUCTURE, path)
    obj = api.import_structure(path, doc, name="Poly")
    before = polycube.get_structure(obj)
    os.remove(path)  # the document must not need it any more
    doc2 = reopen(doc, str(tmp_path / "poly.FCStd"))
    try:
        obj2 = doc2.getObject("Poly")
        assert isinstance(obj2.Proxy, polycube.Polycube)
        after = polycube.get_structure(obj2)
        np.testing.assert_array_equal(after.V, before.V)
        np.testing.assert_array_equal(after.cells, before.cells)
        np.testing.assert_array_equal(after.types, before.types)
        obj2.touch()
        api.recompute_document(doc2, [obj2])
        assert (obj2.HexBlocks, obj2.PrismBlocks) == (3, 1)
    finally:
        FreeCAD.closeDocument(doc2.Name)


def test_new_source_file_is_read_on_recompute(doc, tmp_path):
    obj = api.import_structure(STRUCTURE, doc)
    other = str(tmp_path / "box.k")
    V, cells, types = fc_testdata.box_structure(2.0, 1.0, 1.0)
    core.write_mesh(other, core.Mesh(V, cells, types, np.ones(1, np.int32)))
    obj.SourceFile = other
    api.recompute_document(doc, [obj])
    assert (obj.HexBlocks, obj.PrismBlocks, obj.PointCount) == (1, 0, 8)


def test_bad_structures_are_refused(doc, tmp_path):
    broken = str(tmp_path / "broken.k")
    with open(broken, "w") as f:
        f.write("*KEYWORD\n*ELEMENT_SOLID\n1 1 1 2\n*END\n")
    with pytest.raises(core.InputError, match="broken.k"):
        api.import_structure(broken, doc)
    with pytest.raises(core.InputError, match="hex, prism and tet blocks only"):
        api.import_structure(fc_testdata.example_path("lbracket_patches.k"), doc)
    obj = make.make_polycube(doc)
    V, cells, types = fc_testdata.box_structure(1.0, 1.0, 1.0)
    with pytest.raises(ValueError, match="outside"):
        polycube.store_structure(obj, core.Mesh(V[:4], cells, types, np.ones(1, np.int32)))
    with pytest.raises(ValueError, match="found type 9"):
        polycube.store_structure(obj, core.Mesh(V, cells, np.array([9], np.int32),
                                                np.ones(1, np.int32)))
