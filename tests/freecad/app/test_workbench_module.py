"""The installed workbench package imports inside FreeCAD and registers its file types."""

import os

import FreeCAD


def test_package_is_the_installed_copy_with_its_own_core():
    import HexDomWorkbench
    from HexDomWorkbench import core
    mod_dir = os.path.join(FreeCAD.getUserAppDataDir(), "Mod", "HexDom")
    assert os.path.realpath(HexDomWorkbench.__file__).startswith(os.path.realpath(mod_dir))
    assert core._hexdom.__name__ == "HexDomWorkbench._hexdom"
    assert not os.path.islink(os.path.join(mod_dir, "HexDomWorkbench"))


def test_all_app_modules_import():
    import importlib
    for name in ("make", "fileio", "report", "paths", "objects.hex_mesh", "objects.base_object",
                 "convert.femmesh", "convert.fem_setup", "api", "document",
                 "part_meshing", "shape_tessellation", "progress", "version", "logic.labels",
                 "logic.triangles", "logic.cells", "logic.stages", "logic.patch_editing",
                 "logic.polycube_building"):
        importlib.import_module("HexDomWorkbench." + name)


def test_start_up_does_not_load_the_compiled_core():
    assert os.environ.get("HEXDOM_FC_CORE_AT_STARTUP") == "0"


def test_file_types_are_registered():
    for ext in ("k", "vtk", "vtu"):
        assert "HexDomWorkbench.fileio" in FreeCAD.getImportType(ext), ext
        assert "HexDomWorkbench.fileio" in FreeCAD.getExportType(ext), ext


def test_resources_are_installed():
    from HexDomWorkbench import paths
    for name in ("HexDomWorkbench", "HexDom_Mesh", "HexDom_ImportMesh", "HexDom_QualityReport",
                 "HexDom_ExportMesh", "HexDom_AddToAnalysis"):
        assert os.path.isfile(paths.icon(name)), name
    root = os.path.dirname(paths.RESOURCES)
    for name in ("Init.py", "InitGui.py", "package.xml"):
        assert os.path.isfile(os.path.join(root, name)), name


def test_package_xml_names_the_workbench():
    import xml.etree.ElementTree as ET
    from HexDomWorkbench import paths
    root = ET.parse(os.path.join(os.path.dirname(paths.RESOURCES), "package.xml")).getroot()
    ns = {"p": "https://wiki.freecad.org/Package_Metadata"}
    assert root.find("p:name", ns).text == "HexDom"
    wb = root.find("p:content/p:workbench", ns)
    assert wb.find("p:classname", ns).text == "HexDomWorkbench"
    assert wb.find("p:subdirectory", ns).text == "./"
    import HexDomWorkbench
    assert root.find("p:version", ns).text == HexDomWorkbench.__version__
