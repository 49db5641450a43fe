"""The macro API end to end: `import HexDomWorkbench as hexdom`, the bundled L-bracket meshed from
its patch and structure files into a HexDom Mesh, a CAD box meshed from its faces, FemMesh
counters, save and reopen of the whole pipeline."""

import os
import subprocess
import textwrap

import numpy as np
import pytest

import FreeCAD
import Part

import HexDomWorkbench as hexdom
from HexDomWorkbench import core
from HexDomWorkbench.objects import hex_mesh, polycube, segmentation, tessellation

import fc_testdata
from conftest import reopen

PATCHES = fc_testdata.example_path("lbracket_patches.k")
STRUCTURE = fc_testdata.example_path("lbracket_structure.k")


def lbracket(doc, **kw):
    kw.setdefault("level", 2)
    kw.setdefault("improve", True)
    return hexdom.make_document_objects(doc, patch_file=PATCHES, structure_file=STRUCTURE, **kw)


def test_package_stays_freecad_free_and_core_names_work():
    """Outside FreeCAD: importing the package, and the lazy API names, load no FreeCAD module;
    generate / improve work as before."""
    mod_dir = os.path.dirname(os.path.dirname(os.path.abspath(hexdom.__file__)))
    script = textwrap.dedent("""
        import sys
        sys.path.insert(0, {mod!r})
        import HexDomWorkbench as hexdom
        assert "FreeCAD" not in sys.modules
        s = hexdom.read_surface({patches!r})
        st = hexdom.read_structure({structure!r})
        seg = hexdom.segment if hexdom.has_segmentation() else None
        m = hexdom.improve(hexdom.generate(s, st, level=2), s)
        assert hexdom.generate is hexdom.api.generate and hexdom.improve is hexdom.api.improve
        assert "FreeCAD" not in sys.modules and "Part" not in sys.modules
        print(m.counts["hex"], m.counts["prism"])
    """).format(mod=mod_dir, patches=PATCHES, structure=STRUCTURE)
    env = dict(os.environ)
    env.pop("PYTHONPATH", None)
    out = subprocess.run(["/usr/bin/python3", "-c", script], capture_output=True, text=True,
                         env=env, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["192", "64"]


def test_lbracket_from_patch_and_structure_files(doc):
    objs = lbracket(doc)
    assert set(objs) == {"surface", "segmentation", "polycube", "mesh"}
    seg, poly, mesh = objs["segmentation"], objs["polycube"], objs["mesh"]
    assert seg.Method == "Patch file" and seg.PatchCount == 17
    assert (poly.HexBlocks, poly.PrismBlocks, poly.TetBlocks) == (3, 1, 0)
    assert mesh.Segmentation is seg and mesh.Polycube is poly
    assert mesh.Level == 2 and mesh.Improve
    assert (mesh.HexCount, mesh.PrismCount, mesh.TetCount) == (192, 64, 0)
    assert mesh.InvertedCount == 0
    fem = mesh.FemMesh
    assert (fem.HexaCount, fem.PrismCount, fem.TetraCount) == (192, 64, 0)
    assert fem.VolumeCount == 256
    # The same mesh the core makes directly.
    surface = core.read_surface(PATCHES)
    direct = core.improve(core.generate(surface, core.read_mesh(STRUCTURE), level=2), surface)
    assert fem.NodeCount == len(direct.V)
    got = hex_mesh.get_mesh(mesh)
    np.testing.assert_allclose(got.V, direct.V, rtol=0, atol=1e-9)
    np.testing.assert_array_equal(got.cells, direct.cells)
    np.testing.assert_array_equal(np.array(mesh.Region), direct.region)
    # The mesh fills the bracket: its volume is the surface's.
    _, volume, _ = fc_testdata.closed_surface_checks(surface.V, surface.F)
    assert mesh.MeshVolume == pytest.approx(volume, rel=0.01)
    assert mesh.MinHexSJ > 0.5 and mesh.MinPrismSJ > 0.5


def test_improve_flag_and_level(doc):
    objs = lbracket(doc, improve=False)
    mesh = objs["mesh"]
    raw = [mesh.MinHexSJ, mesh.MinPrismSJ]
    assert (mesh.HexCount, mesh.PrismCount, mesh.InvertedCount) == (192, 64, 0)
    mesh.Improve = True
    hexdom.recompute_document(doc, [mesh])
    improved = [mesh.MinHexSJ, mesh.MinPrismSJ]
    assert improved != raw and min(improved) >= min(raw) - 1e-9
    mesh.Level = 1
    hexdom.recompute_document(doc, [mesh])
    assert (mesh.HexCount, mesh.PrismCount, mesh.FemMesh.HexaCount) == (24, 8, 24)


def test_pipeline_survives_save_and_reopen(doc, tmp_path):
    objs = lbracket(doc)
    names = {k: o.Name for k, o in objs.items()}
    before = hex_mesh.get_mesh(objs["mesh"])
    doc2 = reopen(doc, str(tmp_path / "lbracket.FCStd"))
    try:
        got = {k: doc2.getObject(n) for k, n in names.items()}
        assert isinstance(got["surface"].Proxy, tessellation.Surface)
        assert isinstance(got["segmentation"].Proxy, segmentation.Segmentation)
        assert isinstance(got["polycube"].Proxy, polycube.Polycube)
        assert isinstance(got["mesh"].Proxy, hex_mesh.HexMesh)
        mesh = got["mesh"]
        assert mesh.Segmentation is got["segmentation"] and mesh.Polycube is got["polycube"]
        assert got["segmentation"].Surface is got["surface"]
        after = hex_mesh.get_mesh(mesh)
        np.testing.assert_array_equal(after.cells, before.cells)
        np.testing.assert_allclose(after.V, before.V, rtol=0, atol=1e-12)
        assert (mesh.FemMesh.HexaCount, mesh.FemMesh.PrismCount) == (192, 64)
        # Touching the first stage recomputes the whole chain, in order.
        got["surface"].touch()
        hexdom.recompute_document(doc2)
        for obj in got.values():
            assert obj.State == ["Up-to-date"] or "Invalid" not in obj.State
        assert (mesh.HexCount, mesh.PrismCount, mesh.InvertedCount) == (192, 64, 0)
    finally:
        FreeCAD.closeDocument(doc2.Name)


def test_cad_box_meshed_end_to_end(doc):
    """A Part box: tessellated with face ids, its six faces as patches, one hex block."""
    objs = hexdom.make_document_objects(
        doc, shape=Part.makeBox(20, 10, 5), size=2.0, segmentation="Surface patches",
        structure=core.Mesh(*fc_testdata.box_structure(20.0, 10.0, 5.0),
                            np.ones(1, np.int32)), level=2)
    mesh = objs["mesh"]
    assert objs["surface"].Source.TypeId == "Part::Feature"
    assert objs["segmentation"].PatchCount == 6
    assert (mesh.HexCount, mesh.PrismCount, mesh.TetCount, mesh.InvertedCount) == (64, 0, 0, 0)
    assert mesh.MeshVolume == pytest.approx(1000.0, rel=1e-6)
    assert mesh.MinHexSJ == pytest.approx(1.0, abs=1e-6)


def test_plain_api_from_shape_to_fem_mesh():
    shape = Part.makeBox(20, 10, 5)
    surface = hexdom.tessellate(shape, size=2.5)
    assert isinstance(surface, core.Surface)
    assert sorted(set(surface.patch.tolist())) == [1, 2, 3, 4, 5, 6]
    labels = hexdom.labels_from_normals(surface.V, surface.F, surface.patch)
    segmented = hexdom.SegmentedSurface(surface.V, surface.F, surface.patch, labels)
    structure = core.Mesh(*fc_testdata.box_structure(20.0, 10.0, 5.0), np.ones(1, np.int32))
    mesh = hexdom.improve(hexdom.generate(segmented, structure, level=1), segmented)
    fem = hexdom.to_fem_mesh(mesh)
    assert (fem.HexaCount, fem.PrismCount, fem.TetraCount, fem.NodeCount) == (8, 0, 0, 27)
    back = hexdom.from_fem_mesh(fem)
    np.testing.assert_array_equal(back.cells, mesh.cells)


def test_improve_object_on_an_imported_mesh(doc):
    surface = core.read_surface(PATCHES)
    raw = core.generate(surface, core.read_mesh(STRUCTURE), level=2)
    from HexDomWorkbench import make
    imported = make.make_hex_mesh(doc, raw, name="Imported")
    hexdom.recompute_document(doc, [imported])
    new = hexdom.improve_object(imported)
    assert new is not imported and new.BaseMesh is imported and new.Improve
    hexdom.recompute_document(doc, [new])
    assert (new.HexCount, new.PrismCount, new.InvertedCount) == (192, 64, 0)
    worst = min(imported.MinHexSJ, imported.MinPrismSJ)
    assert min(new.MinHexSJ, new.MinPrismSJ) >= worst - 1e-9
    assert hex_mesh.get_mesh(imported).V.shape == raw.V.shape, "the base mesh is untouched"
    # On a generated mesh it switches Improve on.
    objs = lbracket(doc, improve=False)
    assert hexdom.improve_object(objs["mesh"]) is objs["mesh"] and objs["mesh"].Improve


def test_errors_name_the_object(doc):
    objs = lbracket(doc)
    mesh = objs["mesh"]
    mesh.Polycube = None
    with pytest.raises(hexdom.RecomputeError, match="link both a Segmentation and a Polycube"):
        hexdom.recompute_document(doc, [mesh])
    cube = hexdom.make_document_objects(
        doc, structure=core.Mesh(*fc_testdata.box_structure(1.0, 1.0, 1.0),
                                 np.ones(1, np.int32)))["polycube"]
    mesh.Polycube = cube
    with pytest.raises(hexdom.RecomputeError) as info:
        hexdom.recompute_document(doc, [mesh])
    assert mesh.Label in str(info.value) and "structure" in str(info.value)


def test_pipeline_modules_and_icons_are_installed():
    import importlib
    from HexDomWorkbench import paths
    for name in ("api", "objects.tessellation", "objects.segmentation", "objects.polycube"):
        importlib.import_module("HexDomWorkbench." + name)
    for name in ("HexDom_Surface", "HexDom_Segmentation", "HexDom_Polycube", "HexDom_Tessellate",
                 "HexDom_Segment", "HexDom_ImportPatches", "HexDom_ImportStructure",
                 "HexDom_ExportStructure", "HexDom_GenerateMesh", "HexDom_ImproveQuality"):
        assert os.path.isfile(paths.icon(name)), name
    for name in ("tessellate", "segment", "generate", "improve", "to_fem_mesh",
                 "make_document_objects", "import_structure", "import_patches"):
        assert name in dir(hexdom) and callable(getattr(hexdom, name)), name


def test_pipeline_document_saved_by_0_1_0_still_opens():
    """Fixture written by tests/freecad/data/make_fixture.py with HexDom 0.1.0: the Proxy module
    paths HexDomWorkbench.objects.tessellation / segmentation / polycube / hex_mesh are frozen."""
    path = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "data",
                        "hexdom_pipeline_0.1.0.FCStd")
    doc = FreeCAD.openDocument(path)
    try:
        surf, seg = doc.getObject("HexDomSurface"), doc.getObject("HexDomSegmentation")
        poly, mesh = doc.getObject("HexDomPolycube"), doc.getObject("HexDomMesh")
        assert isinstance(surf.Proxy, tessellation.Surface)
        assert isinstance(seg.Proxy, segmentation.Segmentation)
        assert isinstance(poly.Proxy, polycube.Polycube)
        assert isinstance(mesh.Proxy, hex_mesh.HexMesh)
        assert surf.TriangleCount == 2048 and seg.PatchCount == 17
        assert list(seg.EditedTriangles) == [0] and len(seg.Labels) == 2048
        assert (poly.HexBlocks, poly.PrismBlocks) == (3, 1)
        assert mesh.Segmentation is seg and mesh.Polycube is poly and mesh.Level == 1
        assert (mesh.FemMesh.HexaCount, mesh.FemMesh.PrismCount) == (24, 8)
        mesh.Level = 2
        hexdom.recompute_document(doc, [mesh])
        assert (mesh.HexCount, mesh.PrismCount, mesh.InvertedCount) == (192, 64, 0)
    finally:
        FreeCAD.closeDocument(doc.Name)
