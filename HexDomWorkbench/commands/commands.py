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
    ("Gmsh mesh (*.msh)", ".msh"),
]


class _ImportMesh(CommandManager):
    menutext = "Import mesh..."
    tooltip = "Reads a hex-dominant volume mesh (.k, .vtk, .vtu, .inp, .msh) into a HexDom Mesh object"
    is_active = "always"

    def Activated(self):
        from PySide import QtGui
        path, _ = QtGui.QFileDialog.getOpenFileName(
            manager.main_window(), "Import HexDom mesh", manager.get_param("LastDir"),
            "HexDom meshes (*.k *.vtk *.vtu *.inp *.msh);;All files (*)")
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


class _MeshRegion(CommandManager):
    menutext = "Mesh region"
    tooltip = ("Adds a FreeCAD FEM mesh region to the selected HexDom Mesh: cells of its "
               "CharacteristicLength on the faces it references (`hexdom mesh --face-size`); pick "
               "the faces and the length in its task panel, then recompute the Mesh")
    is_active = "with_hex_mesh"

    def Activated(self):
        obj = manager.selected_mesh(hexdom_only=True)
        if obj is None:
            return
        size = float(getattr(getattr(obj, "Size", None), "Value", 0.0) or 0.0)
        length = round(size / 3.0, 6) if size > 0 else 1.0
        before = set(o.Name for o in obj.Document.Objects)
        if not manager.run_in_transaction(
                obj.Document, "Mesh region", ["ObjectsFem"],
                ["ObjectsFem.makeMeshRegion({}.Document, {}, {!r}, 'MeshRegion')".format(
                    _doc_expr(obj), _doc_expr(obj), length)]):
            return
        added = [o for o in obj.Document.Objects if o.Name not in before]
        if added and FreeCADGui.ActiveDocument is not None:
            FreeCADGui.ActiveDocument.setEdit(added[0].Name)


def _doc_expr(obj):
    return "App.getDocument({!r}).getObject({!r})".format(obj.Document.Name, obj.Name)


def _ensure_document():
    if FreeCAD.ActiveDocument is None:
        FreeCADGui.doCommand("App.newDocument()")
    return FreeCAD.ActiveDocument


def _open_file(title, filters):
    from PySide import QtGui
    path, _ = QtGui.QFileDialog.getOpenFileName(manager.main_window(), title,
                                                manager.get_param("LastDir"), filters)
    if path:
        manager.set_param("LastDir", os.path.dirname(path))
    return path


def _fit():
    if FreeCADGui.ActiveDocument is not None:
        FreeCADGui.SendMsgToActiveView("ViewFit")


class _Tessellate(CommandManager):
    menutext = "Tessellate part"
    tooltip = ("Triangulates the selected Part solid into a HexDom Surface that keeps the CAD "
               "face of each triangle (edit Size, Deflection, Angle, then recompute)")
    is_active = "with_part"

    def Activated(self):
        parts = manager.selected_parts()
        if parts:
            self.tessellate(parts)

    def tessellate(self, parts):
        doc = parts[0].Document
        steps = [("tessellating " + p.Label,
                  "HexDomWorkbench.make.make_surface(App.ActiveDocument, {})".format(_doc_expr(p)))
                 for p in parts]
        new = manager.run_and_recompute(doc, "Tessellate", ["HexDomWorkbench.make"], steps)
        _fit()
        return new


class _Segment(CommandManager):
    menutext = "Segment surface"
    tooltip = ("Labels the triangles of the selected HexDom Surface with polycube directions "
               "(+X -X +Y -Y +Z -Z) and groups them into patches: a HexDom Segmentation")
    is_active = "with_surface"

    def Activated(self):
        surface = manager.selected_of_type("HexDom::Surface")
        if surface is not None:
            self.segment(surface)

    def segment(self, surface):
        from .. import api
        if not api.has_segmentation():
            manager.show_error("Segment", "segmentation not available in this build")
            return None
        line = ("HexDomWorkbench.make.make_segmentation(App.ActiveDocument, {}, "
                "method='Automatic')".format(_doc_expr(surface)))
        return manager.run_and_recompute(surface.Document, "Segment", ["HexDomWorkbench.make"],
                                         [("segmenting", line)])


class _ImportKFile(CommandManager):
    """Reads a .k file through ``HexDomWorkbench.api.<api_function>(path, doc)`` in one transaction."""
    is_active = "always"
    dialog_title = transaction = api_function = ""

    def Activated(self):
        path = _open_file(self.dialog_title, "LS-DYNA keyword (*.k);;All files (*)")
        if path:
            self.import_file(path)

    def import_file(self, path):
        doc = _ensure_document()
        new = manager.run_and_recompute(
            doc, self.transaction, ["HexDomWorkbench.api"],
            [("reading " + os.path.basename(path),
              "HexDomWorkbench.api.{}({!r}, App.ActiveDocument)".format(self.api_function, path))])
        _fit()
        return new


class _ImportPatches(_ImportKFile):
    menutext = "Import patches..."
    tooltip = ("Reads a segmented surface (.k shells, part id = patch id, as the paper's patch "
               "files) into a HexDom Surface and a HexDom Segmentation")
    dialog_title, transaction, api_function = ("Import HexDom patches", "Import patches",
                                               "import_patches")


class _ImportStructure(_ImportKFile):
    menutext = "Import polycube structure..."
    tooltip = ("Reads a polycube structure (.k, hex / prism / tet blocks as *ELEMENT_SOLID) into "
               "a HexDom Polycube")
    dialog_title, transaction, api_function = ("Import polycube structure", "Import structure",
                                               "import_structure")


class _ExportStructure(CommandManager):
    menutext = "Export polycube structure..."
    tooltip = "Writes the selected HexDom Polycube as a .k structure file (or .vtk, .vtu)"
    is_active = "with_polycube"

    def Activated(self):
        from PySide import QtGui
        obj = manager.selected_of_type("HexDom::Polycube")
        if obj is None:
            return
        start = os.path.join(manager.get_param("LastDir"), obj.Label + ".k")
        path, _ = QtGui.QFileDialog.getSaveFileName(
            manager.main_window(), "Export polycube structure", start,
            "LS-DYNA keyword (*.k);;VTK legacy (*.vtk);;VTK XML (*.vtu)")
        if path:
            if os.path.splitext(path)[1].lower() not in (".k", ".vtk", ".vtu"):
                path += ".k"
            self.export_file(obj, path)

    def export_file(self, obj, path):
        manager.set_param("LastDir", os.path.dirname(path))
        try:
            FreeCADGui.addModule("HexDomWorkbench.api")
            FreeCADGui.doCommand("HexDomWorkbench.api.export_structure({}, {!r})".format(
                _doc_expr(obj), path))
        except manager.USER_ERRORS as e:
            manager.show_error("Export structure", e)
            return False
        return True


class _GenerateMesh(CommandManager):
    menutext = "Generate hex-dominant mesh"
    tooltip = ("Generates a HexDom Mesh from the selected Segmentation and Polycube (level 2, "
               "improved); with nothing selected, asks for a patch file and a structure file")
    is_active = "always"

    def Activated(self):
        sel = FreeCADGui.Selection.getSelection()
        seg = [o for o in sel if getattr(getattr(o, "Proxy", None), "Type", "")
               == "HexDom::Segmentation"]
        poly = [o for o in sel if getattr(getattr(o, "Proxy", None), "Type", "")
                == "HexDom::Polycube"]
        if len(seg) == 1 and len(poly) == 1:
            self.generate(seg[0], poly[0])
            return
        if sel:
            manager.show_error("Generate mesh", "select one HexDom Segmentation and one HexDom "
                               "Polycube, or nothing to mesh from files")
            return
        patches = _open_file("Patch file (segmented surface)",
                             "LS-DYNA keyword (*.k);;All files (*)")
        if not patches:
            return
        structure = _open_file("Polycube structure file", "LS-DYNA keyword (*.k);;All files (*)")
        if structure:
            self.generate_from_files(patches, structure)

    def generate(self, segmentation, polycube, level=2, improve=True):
        line = ("HexDomWorkbench.make.make_hex_mesh(App.ActiveDocument, segmentation={}, "
                "polycube={}, level={}, improve={})".format(
                    _doc_expr(segmentation), _doc_expr(polycube), int(level), bool(improve)))
        new = manager.run_and_recompute(segmentation.Document, "Generate mesh",
                                        ["HexDomWorkbench.make"], [("meshing", line)])
        _fit()
        return new

    def generate_from_files(self, patch_file, structure_file, level=2, improve=True):
        doc = _ensure_document()
        line = ("HexDomWorkbench.api.make_document_objects(App.ActiveDocument, patch_file={!r}, "
                "structure_file={!r}, level={}, improve={}, recompute=False)".format(
                    patch_file, structure_file, int(level), bool(improve)))
        new = manager.run_and_recompute(doc, "Generate mesh", ["HexDomWorkbench.api"],
                                        [("reading and meshing", line)])
        _fit()
        return new


class _ImproveQuality(CommandManager):
    menutext = "Improve mesh quality"
    tooltip = ("Pillowing, smoothing and Jacobian optimisation of the selected mesh: a generated "
               "HexDom Mesh gets Improve = true, another FEM mesh an improved copy")
    is_active = "with_fem_mesh"

    def Activated(self):
        obj = manager.selected_mesh(hexdom_only=False)
        if obj is not None:
            self.improve(obj)

    def improve(self, obj):
        new = manager.run_and_recompute(
            obj.Document, "Improve quality", ["HexDomWorkbench.api"],
            [("improving", "HexDomWorkbench.api.improve_object({})".format(_doc_expr(obj)))])
        return new


class _MeshPart(CommandManager):
    menutext = "Mesh part"
    tooltip = ("Meshes the selected Part solid (or mesh object: an STL or OBJ opened in FreeCAD, "
               "each closed shell a solid) with no manual step, as `hexdom mesh` does: the "
               "HexDom Mesh runs its pipeline once (element size = bounding-box diagonal / 30, "
               "the polycube or, where it fails or misses a target, the overlay grid) and fills "
               "a Surface, a Segmentation and a Polycube with the stages it made, all kept and "
               "editable. Change the Mesh's Size, MaxSize, MinSize, CellsAcross, Level or Method "
               "and recompute to mesh again; "
               "edit a stage and the mesh is rebuilt from the stages")
    is_active = "with_part"

    def Activated(self):
        parts = manager.selected_parts()
        if len(parts) != 1:
            manager.show_error("Mesh part", "select one Part solid or mesh object")
            return
        self.mesh_part(parts[0])

    def mesh_part(self, part, size=0.0, level=1):
        """Creates the four objects for ``part`` and recomputes them in order, with progress and
        Cancel. Returns the dict of objects (api.mesh_part's), or None if none were made. A
        stage that fails, or Cancel, keeps the objects: the finished ones stay valid and the
        message names the stage."""
        from .. import api
        doc = part.Document
        before = set(o.Name for o in doc.Objects)
        doc.openTransaction("Mesh part")
        cancelled = False
        try:
            with api.Progress("Meshing " + part.Label, 2) as bar:
                FreeCADGui.addModule("HexDomWorkbench.api")
                FreeCADGui.doCommand(
                    "_objs = HexDomWorkbench.api.make_mesh_part(App.ActiveDocument, {}, "
                    "size={!r}, level={})".format(_doc_expr(part), float(size), int(level)))
                bar.step("objects created")
                # The Mesh runs `hexdom mesh`'s pipeline once and fills the three others.
                FreeCADGui.doCommand("App.ActiveDocument.recompute()")
                bar.step("recomputed")
                cancelled = bar.is_cancelled()
        except manager.USER_ERRORS as e:  # bad input: nothing made
            doc.abortTransaction()
            manager.show_error("Mesh part", e)
            return None
        doc.commitTransaction()
        objs = {}
        for o in doc.Objects:
            if o.Name in before:
                continue
            for key, type_name in (("surface", "HexDom::Surface"),
                                   ("segmentation", "HexDom::Segmentation"),
                                   ("polycube", "HexDom::Polycube"), ("mesh", "HexDom::Mesh")):
                if getattr(getattr(o, "Proxy", None), "Type", None) == type_name:
                    objs[key] = o
        _fit()
        try:
            api.check_mesh_part(objs)
        except api.MeshPartError as e:
            if cancelled:
                FreeCAD.Console.PrintWarning("HexDom: Mesh part: cancelled ({}); the objects "
                                             "are kept, recompute to resume\n".format(e))
            else:
                manager.show_error("Mesh part", e)
            return objs
        mesh = objs["mesh"]
        FreeCAD.Console.PrintMessage(
            "HexDom: {}: {} hex, {} prism, {} tet; worst hex SJ {:.3f}, mean {:.3f}; "
            "volume {:.6g}; made by the {} path{}\n".format(
                mesh.Label, mesh.HexCount, mesh.PrismCount, mesh.TetCount, mesh.MinHexSJ,
                mesh.MeanHexSJ, mesh.MeshVolume, getattr(mesh, "MeshingPath", "") or "polycube",
                " ({})".format(mesh.PolycubeNote) if getattr(mesh, "PolycubeNote", "") else ""))
        return objs


def _of_type(objs, type_name):
    return [o for o in objs if getattr(getattr(o, "Proxy", None), "Type", None) == type_name]


class _EditPatches(CommandManager):
    menutext = "Edit patches..."
    tooltip = ("Opens the Edit Patches panel on the selected HexDom Segmentation: pick facets, "
               "assign them to a patch, a new patch or an orientation, merge and split patches, "
               "with the polycube problems listed live")

    def IsActive(self):
        return (FreeCAD.ActiveDocument is not None and not FreeCADGui.Control.activeDialog()
                and manager.selected_of_type("HexDom::Segmentation") is not None)

    def Activated(self):
        seg = manager.selected_of_type("HexDom::Segmentation")
        if seg is not None:
            self.edit(seg)

    def edit(self, segmentation):
        """Opens the panel on ``segmentation`` (as a double-click does); True when it opened."""
        FreeCADGui.doCommand("Gui.getDocument({!r}).setEdit({!r}, 0)".format(
            segmentation.Document.Name, segmentation.Name))
        return FreeCADGui.Control.activeDialog()


class _BuildPolycube(CommandManager):
    menutext = "Build polycube..."
    tooltip = ("Opens the Build Polycube panel: blocks (hex, prism, tet) over the corners of the "
               "selected HexDom Segmentation's patches, or edits the selected HexDom Polycube")

    def IsActive(self):
        if FreeCAD.ActiveDocument is None or FreeCADGui.Control.activeDialog():
            return False
        sel = FreeCADGui.Selection.getSelection()
        segs = _of_type(sel, "HexDom::Segmentation")
        polys = _of_type(sel, "HexDom::Polycube")
        return len(segs) <= 1 and len(polys) <= 1 and len(segs) + len(polys) == len(sel) > 0

    def Activated(self):
        sel = FreeCADGui.Selection.getSelection()
        segs = _of_type(sel, "HexDom::Segmentation")
        polys = _of_type(sel, "HexDom::Polycube")
        self.build(segs[0] if segs else None, polys[0] if polys else None)

    def build(self, segmentation=None, polycube=None):
        """Opens the panel: on ``polycube`` (against ``segmentation``, else the one found), or
        for a new Polycube over ``segmentation``. True when it opened."""
        from ..viewproviders.view_base import open_task_panel
        if polycube is not None:
            polycube.ViewObject.Proxy.edit_segmentation = segmentation
            FreeCADGui.doCommand("Gui.getDocument({!r}).setEdit({!r}, 0)".format(
                polycube.Document.Name, polycube.Name))
            return FreeCADGui.Control.activeDialog()
        if segmentation is None:
            return False
        from .. import make
        from ..taskpanels import task_polycube
        return open_task_panel(
            lambda: task_polycube._TaskPanel(
                None, segmentation=segmentation,
                new_polycube=lambda doc, structure: make.make_polycube(doc, structure=structure)),
            "Build polycube")


COMMANDS = [_ImportMesh(), _QualityReport(), _ExportMesh(), _AddToAnalysis()]
PIPELINE_COMMANDS = [_MeshPart(), _MeshRegion(), _Tessellate(), _Segment(), _ImportPatches(), _EditPatches(),
                     _ImportStructure(), _BuildPolycube(), _GenerateMesh(), _ImproveQuality(),
                     _ExportStructure()]
TOOLBAR = [c.command_name for c in COMMANDS]
PIPELINE_TOOLBAR = [c.command_name for c in PIPELINE_COMMANDS]
MENU = PIPELINE_TOOLBAR + ["Separator"] + TOOLBAR

for _command in COMMANDS + PIPELINE_COMMANDS:
    FreeCADGui.addCommand(_command.command_name, _command)

