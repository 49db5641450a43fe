"""HexDom Mesh objects: creation, quality properties, recompute, save and reopen."""

import os

import numpy as np
import pytest

import FreeCAD

from HexDomWorkbench import core, make
from HexDomWorkbench.objects import hex_mesh

import fc_testdata
from conftest import reopen

DATA = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "data")


def sample():
    return core.Mesh(*fc_testdata.mixed_sample())


def test_object_type_and_properties(doc):
    obj = make.make_hex_mesh(doc, sample())
    assert obj.TypeId == "Fem::FemMeshObjectPython"
    assert obj.Proxy.Type == "HexDom::Mesh"
    assert hex_mesh.is_hex_mesh(obj)
    import HexDomWorkbench
    assert obj.Version == HexDomWorkbench.__version__
    for name in ["Level", "Region", "SourceFile"] + hex_mesh.QUALITY_PROPERTIES:
        assert hasattr(obj, name), name
    for name in hex_mesh.QUALITY_PROPERTIES:
        assert "ReadOnly" in obj.getEditorMode(name), name


def test_quality_properties_and_counters(doc):
    obj = make.make_hex_mesh(doc, sample())
    doc.recompute()
    assert obj.State == ["Up-to-date"] or "Invalid" not in obj.State
    assert (obj.HexCount, obj.PrismCount, obj.TetCount, obj.InvertedCount) == (1, 2, 6, 0)
    fem = obj.FemMesh
    assert (fem.HexaCount, fem.PrismCount, fem.TetraCount) == (1, 2, 6)
    assert obj.MinHexSJ == pytest.approx(1.0)
    assert obj.MinPrismSJ == pytest.approx(np.sqrt(2.0 / 3.0))
    assert obj.MinTetSJ == pytest.approx(1.0 / np.sqrt(3.0))
    assert obj.MeanTetSJ == pytest.approx(1.0 / np.sqrt(3.0))
    assert obj.MeshVolume == pytest.approx(3.0)
    assert obj.MaxEdgeRatio == pytest.approx(np.sqrt(3.0))
    assert list(obj.Region) == [1, 2, 2] + [3] * 6


def test_empty_types_report_zero_not_nan(doc):
    V, cells, types = fc_testdata.box_mesh(2.0, 1.0, 1.0, 2, 1, 1)
    obj = make.make_hex_mesh(doc, core.Mesh(V, cells, types, np.zeros(len(types), np.int32)))
    doc.recompute()
    assert (obj.HexCount, obj.PrismCount, obj.TetCount) == (2, 0, 0)
    assert obj.MinPrismSJ == 0.0 and obj.MeanTetSJ == 0.0


def test_save_reopen_keeps_mesh_and_quality(doc, tmp_path):
    mesh = sample()
    obj = make.make_hex_mesh(doc, mesh, "Sample")
    obj.Level = 3
    doc.recompute()
    before = {name: getattr(obj, name) for name in hex_mesh.QUALITY_PROPERTIES}
    doc2 = reopen(doc, str(tmp_path / "sample.FCStd"))
    try:
        obj2 = doc2.getObject("Sample")
        assert isinstance(obj2.Proxy, hex_mesh.HexMesh)
        assert obj2.Level == 3
        for name, value in before.items():
            assert getattr(obj2, name) == pytest.approx(value), name
        back = hex_mesh.get_mesh(obj2)
        np.testing.assert_allclose(back.V, mesh.V, rtol=0, atol=1e-12)
        np.testing.assert_array_equal(back.cells, mesh.cells)
        np.testing.assert_array_equal(back.types, mesh.types)
        np.testing.assert_array_equal(back.region, mesh.region)
        fem = obj2.FemMesh
        assert (fem.HexaCount, fem.PrismCount, fem.TetraCount) == (1, 2, 6)
        obj2.touch()
        doc2.recompute()
        assert "Invalid" not in obj2.State
        assert obj2.TetCount == 6
    finally:
        FreeCAD.closeDocument(doc2.Name)


def test_rockerarm_structure_survives_save_and_reopen(doc, tmp_path):
    path = fc_testdata.rockerarm_path()
    if path is None:
        pytest.skip("paper data missing: set HEXDOM_DATA to the folder holding "
                    "hexdom/rockerarm/rockerarm_polycube_withtet.k")
    mesh = core.read_mesh(path)
    report = core.quality_report(mesh)
    obj = make.make_hex_mesh(doc, mesh, "Rockerarm")
    doc.recompute()
    assert (obj.HexCount, obj.PrismCount, obj.TetCount) == (
        report["hex"]["count"], report["prism"]["count"], report["tet"]["count"])
    assert (obj.HexCount, obj.PrismCount, obj.TetCount) == (60, 11, 2)
    doc2 = reopen(doc, str(tmp_path / "rockerarm.FCStd"))
    try:
        obj2 = doc2.getObject("Rockerarm")
        fem = obj2.FemMesh
        assert (fem.HexaCount, fem.PrismCount, fem.TetraCount) == (60, 11, 2)
        assert fem.NodeCount == len(mesh.V)
        back = hex_mesh.get_mesh(obj2)
        np.testing.assert_allclose(back.V, mesh.V, rtol=0, atol=1e-9 * np.abs(mesh.V).max())
        np.testing.assert_array_equal(back.cells, mesh.cells)
        assert obj2.MinHexSJ == pytest.approx(report["hex"]["sj_min"])
        assert obj2.MeanHexSJ == pytest.approx(report["hex"]["sj_mean"])
        assert obj2.MinTetSJ == pytest.approx(report["tet"]["sj_min"])
        assert obj2.InvertedCount == 0
    finally:
        FreeCAD.closeDocument(doc2.Name)


def test_restore_adds_properties_missing_from_old_files(doc, tmp_path):
    obj = make.make_hex_mesh(doc, sample(), "Old")
    obj.removeProperty("MaxEdgeRatio")
    obj.removeProperty("Level")
    assert not hasattr(obj, "MaxEdgeRatio")
    doc2 = reopen(doc, str(tmp_path / "old.FCStd"))
    try:
        obj2 = doc2.getObject("Old")
        assert hasattr(obj2, "MaxEdgeRatio") and hasattr(obj2, "Level")
        obj2.touch()
        doc2.recompute()
        assert obj2.MaxEdgeRatio == pytest.approx(np.sqrt(3.0))
    finally:
        FreeCAD.closeDocument(doc2.Name)


def test_add_properties_is_idempotent(doc):
    obj = make.make_hex_mesh(doc, sample())
    names = sorted(obj.PropertiesList)
    obj.Proxy.add_properties(obj)
    obj.Proxy.add_properties(obj)
    assert sorted(obj.PropertiesList) == names


def test_generation_stage_plugs_in_through_generate(doc):
    class Generated(hex_mesh.HexMesh):
        def generate(self, obj):
            V, cells, types = fc_testdata.box_mesh(1.0, 1.0, 1.0, 1 << obj.Level, 1, 1)
            return core.Mesh(V, cells, types, np.zeros(len(types), np.int32))

    obj = doc.addObject("Fem::FemMeshObjectPython", "Generated")
    Generated(obj)
    obj.Level = 3
    doc.recompute()
    assert obj.HexCount == 8 and obj.FemMesh.HexaCount == 8
    obj.Level = 1
    doc.recompute()
    assert obj.HexCount == 2 and len(obj.Region) == 2


def test_document_saved_by_0_1_0_still_opens():
    """Fixture written by tests/freecad/data/make_fixture.py with HexDom 0.1.0: the Proxy module
    path HexDomWorkbench.objects.hex_mesh is frozen."""
    path = os.path.join(DATA, "hexdom_mesh_0.1.0.FCStd")
    doc = FreeCAD.openDocument(path)
    try:
        obj = doc.getObject("HexDomMesh")
        assert isinstance(obj.Proxy, hex_mesh.HexMesh)
        assert (obj.HexCount, obj.PrismCount, obj.TetCount) == (1, 2, 6)
        mesh = hex_mesh.get_mesh(obj)
        expected = sample()
        np.testing.assert_allclose(mesh.V, expected.V)
        np.testing.assert_array_equal(mesh.cells, expected.cells)
        np.testing.assert_array_equal(mesh.region, expected.region)
        obj.touch()
        doc.recompute()
        assert "Invalid" not in obj.State
    finally:
        FreeCAD.closeDocument(doc.Name)
