"""HexDom commands, one small class each, registered at the end."""

import os

import FreeCAD
import FreeCADGui

from .. import core, fileio
from ..objects import hex_mesh
from . import manager
from .manager import CommandManager

_EXPORT_FILTERS = [
    ("VTK legacy (*.vtk)", ".vtk"),
    ("VTK XML (*.vtu)", ".vtu"),
    ("LS-DYNA keyword (*.k)", ".k"),
    ("Abaqus / CalculiX input (*.inp)", ".inp"),
]


class _ImportMesh(CommandManager):
    menutext = "Import mesh..."
    tooltip = "Reads a hex-dominant volume mesh (.k, .vtk, .vtu) into a HexDom Mesh object"
    is_active = "always"

    def Activated(self):
        from PySide import QtGui
        path, _ = QtGui.QFileDialog.getOpenFileName(
            manager.main_window(), "Import HexDom mesh", manager.get_param("LastDir"),
            "HexDom meshes (*.k *.vtk *.vtu);;All files (*)")
        if path:
            self.import_file(path)

    def import_file(self, path):
        """Imports ``path`` (as the file dialog would); returns the new object or None."""
        manager.set_param("LastDir", os.path.dirname(path))
        if FreeCAD.ActiveDocument is None:
            FreeCADGui.doCommand("App.newDocument()")
        doc = FreeCAD.ActiveDocument
        before = set(o.Name for o in doc.Objects)
        ok = manager.run_in_transaction(
            doc, "Import mesh", ["HexDomWorkbench.fileio"],
            ["HexDomWorkbench.fileio.import_mesh({!r}, App.ActiveDocument)".format(path)])
        if not ok:
            return None
        new = [o for o in doc.Objects if o.Name not in before and hex_mesh.is_hex_mesh(o)]
        if FreeCADGui.ActiveDocument is not None:
            FreeCADGui.SendMsgToActiveView("ViewFit")
        return new[0] if new else None


class _QualityReport(CommandManager):
    menutext = "Quality report"
    tooltip = ("Scaled Jacobian and edge ratio of the selected mesh, per cell type, with "
               "histograms")
    is_active = "with_fem_mesh"

    def Activated(self):
        obj = manager.selected_mesh(hexdom_only=False)
        if obj is None:
            return
        try:
            mesh = hex_mesh.get_mesh(obj)
            report = core.quality_report(mesh)
        except manager.USER_ERRORS as e:
            manager.show_error("Quality report", e)
            return
        from ..report import format_quality_report
        text = format_quality_report(report, "Quality of {}".format(obj.Label))
        FreeCAD.Console.PrintMessage(text)
        from ..guiutils import quality_dialog
        self.dialog = quality_dialog.show_quality_dialog(obj.Label, report, text)


class _ExportMesh(CommandManager):
    menutext = "Export mesh..."
    tooltip = "Writes the selected mesh as .vtk, .vtu, .k or .inp"
    is_active = "with_fem_mesh"

    def Activated(self):
        from PySide import QtGui
        obj = manager.selected_mesh(hexdom_only=False)
        if obj is None:
            return
        start = os.path.join(manager.get_param("LastDir"), obj.Label + ".vtk")
        path, chosen = QtGui.QFileDialog.getSaveFileName(
            manager.main_window(), "Export mesh", start, ";;".join(f for f, _ in _EXPORT_FILTERS))
        if path:
            ext = dict(_EXPORT_FILTERS).get(chosen, ".vtk")
            if os.path.splitext(path)[1].lower() not in fileio.WRITE_EXTENSIONS:
                path += ext
            self.export_file(obj, path)

    def export_file(self, obj, path):
        """Writes ``obj`` to ``path`` (as the file dialog would); returns True on success."""
        manager.set_param("LastDir", os.path.dirname(path))
        try:
            FreeCADGui.addModule("HexDomWorkbench.fileio")
            FreeCADGui.doCommand("HexDomWorkbench.fileio.export_mesh("
                                 "App.ActiveDocument.getObject({!r}), {!r})".format(obj.Name, path))
        except manager.USER_ERRORS as e:
            manager.show_error("Export mesh", e)
            return False
        return True


class _AddToAnalysis(CommandManager):
    menutext = "Add mesh to analysis"
    tooltip = "Adds the selected HexDom Mesh to the active FEM analysis"
    is_active = "with_analysis_and_hex_mesh"

    def Activated(self):
        analysis = manager.active_analysis()
        obj = manager.selected_mesh(hexdom_only=True)
        if analysis is None or obj is None:
            return
        manager.run_in_transaction(
            obj.Document, "Add mesh to analysis", ["HexDomWorkbench.convert.fem_setup"],
            ["HexDomWorkbench.convert.fem_setup.add_to_analysis("
             "App.ActiveDocument.getObject({!r}), App.ActiveDocument.getObject({!r}))".format(
                 analysis.Name, obj.Name)])


COMMANDS = [_ImportMesh(), _QualityReport(), _ExportMesh(), _AddToAnalysis()]
TOOLBAR = [c.command_name for c in COMMANDS]
MENU = list(TOOLBAR)

for _command in COMMANDS:
    FreeCADGui.addCommand(_command.command_name, _command)
