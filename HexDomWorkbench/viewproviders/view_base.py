"""Boilerplate shared by HexDom view providers."""

import FreeCAD

from .. import paths


class VPBaseHexDomObject:
    """Base view provider: icon named after the object's Type ("HexDom::Mesh" ->
    Resources/icons/HexDom_Mesh.svg), view properties added idempotently."""

    def __init__(self, vobj):
        vobj.Proxy = self
        self.add_properties(vobj)

    def add_properties(self, vobj):
        """Adds missing view properties; also called from attach, so restored documents get
        properties added after they were saved."""

    def attach(self, vobj):
        self.Object = vobj.Object
        self.ViewObject = vobj
        self.add_properties(vobj)

    def getIcon(self):
        obj = getattr(self, "Object", None)
        type_name = getattr(getattr(obj, "Proxy", None), "Type", "")
        if not type_name.startswith("HexDom::"):
            FreeCAD.Console.PrintLog("HexDom: no icon for {}\n".format(type_name))
            return ""
        return paths.icon(type_name.replace("::", "_"))

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    def dumps(self):
        return None

    def loads(self, state):
        return None


def open_task_panel(make_panel, title):
    """Shows the task panel ``make_panel()`` builds; False (and a message) when another task
    dialog is open or the panel cannot be built."""
    import FreeCAD
    import FreeCADGui
    from PySide import QtGui

    from .. import core
    if FreeCADGui.Control.activeDialog():
        FreeCAD.Console.PrintWarning("HexDom: close the open task dialog first\n")
        return False
    try:
        panel = make_panel()
    except (core.Error, ValueError) as e:
        FreeCAD.Console.PrintError("HexDom: {}: {}\n".format(title, e))
        QtGui.QMessageBox.critical(FreeCADGui.getMainWindow(), "HexDom: " + title, str(e))
        return False
    FreeCADGui.Control.showDialog(panel)
    return True


def edit_on_double_click(vobj):
    """Opens the object's task panel (setEdit), unless another task dialog is open."""
    import FreeCAD
    import FreeCADGui
    if FreeCADGui.Control.activeDialog():
        FreeCAD.Console.PrintWarning("HexDom: close the open task dialog first\n")
        return True
    FreeCADGui.getDocument(vobj.Object.Document.Name).setEdit(vobj.Object.Name, 0)
    return True
