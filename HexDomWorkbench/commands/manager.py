"""Base class of HexDom commands and the helpers they share.

A command's name is "HexDom_" + its class name without the leading underscore, its icon
Resources/icons/<name>.svg. ``is_active`` picks IsActive from a small vocabulary. Actions that
change a document run as console lines through FreeCADGui.doCommand inside a transaction, so a
macro recording replays them; errors from core (and conversions) become a message box plus a
FreeCAD.Console error, never an exception out of the GUI.
"""

import FreeCAD
import FreeCADGui

from .. import core, paths
from ..document import RecomputeError
from ..guiutils.dialogs import PARAMS, get_param, main_window, set_param, show_error  # noqa: F401
from ..objects import hex_mesh
from ..progress import Progress

# Exceptions a command reports to the user instead of raising.
USER_ERRORS = (core.Error, ValueError, OSError)


class CommandManager:
    """Base of HexDom commands.

    Class attributes: ``menutext``, ``tooltip``, and ``is_active``, one of "always",
    "with_document", "with_fem_mesh" (one FEM mesh selected), "with_hex_mesh" (one HexDom Mesh
    selected), "with_analysis_and_hex_mesh" (an active FEM analysis and one HexDom Mesh selected),
    "with_part" (Part objects with faces selected), "with_surface" (one HexDom Surface),
    "with_polycube" (one HexDom Polycube).
    """

    menutext = ""
    tooltip = ""
    is_active = "with_document"

    def __init__(self):
        self.command_name = "HexDom_" + type(self).__name__.lstrip("_")

    def GetResources(self):
        return {
            "Pixmap": paths.icon(self.command_name),
            "MenuText": self.menutext,
            "ToolTip": self.tooltip,
        }

    def IsActive(self):
        check = self.is_active
        if check == "always":
            return True
        if FreeCAD.ActiveDocument is None:
            return False
        if check == "with_document":
            return True
        if check == "with_fem_mesh":
            return selected_mesh(hexdom_only=False) is not None
        if check == "with_hex_mesh":
            return selected_mesh(hexdom_only=True) is not None
        if check == "with_analysis_and_hex_mesh":
            return active_analysis() is not None and selected_mesh(hexdom_only=True) is not None
        if check == "with_part":
            return bool(selected_parts())
        if check == "with_surface":
            return selected_of_type("HexDom::Surface") is not None
        if check == "with_polycube":
            return selected_of_type("HexDom::Polycube") is not None
        raise ValueError("unknown is_active value '{}'".format(check))

    def Activated(self):
        raise NotImplementedError


def selected_mesh(hexdom_only=True):
    """The one selected FEM mesh object (HexDom Mesh if ``hexdom_only``), else None."""
    sel = FreeCADGui.Selection.getSelection()
    if len(sel) != 1:
        return None
    obj = sel[0]
    if hexdom_only:
        return obj if hex_mesh.is_hex_mesh(obj) else None
    return obj if obj.isDerivedFrom("Fem::FemMeshObject") else None


def selected_of_type(type_name):
    """The one selected HexDom object of Proxy Type ``type_name``, else None."""
    sel = FreeCADGui.Selection.getSelection()
    if len(sel) != 1:
        return None
    return sel[0] if getattr(getattr(sel[0], "Proxy", None), "Type", None) == type_name else None


def selected_parts():
    """Selected objects with a shape that has faces (Part solids and the like) or with triangles
    (FreeCAD mesh objects: an STL or OBJ opened in FreeCAD), not HexDom's."""
    from ..objects.tessellation import is_mesh_feature
    parts = []
    for obj in FreeCADGui.Selection.getSelection():
        shape = getattr(obj, "Shape", None)
        if hasattr(getattr(obj, "Proxy", None), "Type") and \
                str(getattr(obj.Proxy, "Type", "")).startswith("HexDom::"):
            continue
        if shape is not None and hasattr(shape, "Faces") and not shape.isNull() and shape.Faces:
            parts.append(obj)
        elif is_mesh_feature(obj) and obj.Mesh.CountFacets:
            parts.append(obj)
    return parts


def active_analysis():
    import FemGui
    return FemGui.getActiveAnalysis()


def run_in_transaction(doc, title, modules, lines):
    """Runs console ``lines`` (after importing ``modules``) as one undoable transaction.

    Returns True on success; on a USER_ERRORS exception aborts the transaction, reports the
    error and returns False.
    """
    doc.openTransaction(title)
    try:
        for module in modules:
            FreeCADGui.addModule(module)
        for line in lines:
            FreeCADGui.doCommand(line)
    except USER_ERRORS as e:
        doc.abortTransaction()
        show_error(title, e)
        return False
    doc.commitTransaction()
    return True


def run_and_recompute(doc, title, modules, steps):
    """Runs console lines as one transaction, each step a ``(text, line)`` advancing the progress
    bar, then recomputes the document (also echoed as a console line).

    Returns the objects the transaction added. If a line raises one of USER_ERRORS, or an object
    fails to recompute, the transaction is aborted (nothing is added) and the error shown in a
    message box (a warning in the report view after Cancel); returns None then. Long core calls
    inside the recompute share this Progress: one dialog with a Cancel button.
    """
    before = set(o.Name for o in doc.Objects)
    invalid_before = set(o.Name for o in doc.Objects if "Invalid" in o.State)
    doc.openTransaction(title)
    cancelled = False
    try:
        with Progress(title, len(steps) + 1) as bar:
            for module in modules:
                FreeCADGui.addModule(module)
            for text, line in steps:
                FreeCADGui.doCommand(line)
                bar.step(text)
            FreeCADGui.doCommand("App.ActiveDocument.recompute()")
            bar.step("recomputed")
            cancelled = bar.is_cancelled()
        failed = [o for o in doc.Objects
                  if ("Invalid" in o.State or "Error" in o.State) and o.Name not in invalid_before]
        if failed:
            message = failed[0].getStatusString() or "recompute failed"
            raise RecomputeError("{}: {}".format(failed[0].Label, message))
    except USER_ERRORS as e:
        doc.abortTransaction()
        doc.recompute()
        if cancelled:  # the user asked for it: no message box
            FreeCAD.Console.PrintWarning("HexDom: {}: cancelled; the document is as it was\n"
                                         .format(title))
        else:
            show_error(title, e)
        return None
    doc.commitTransaction()
    return [o for o in doc.Objects if o.Name not in before]
