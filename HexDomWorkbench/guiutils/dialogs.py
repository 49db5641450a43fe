"""Messages and remembered settings shared by the commands and the task panels (GUI only): the
main window, an error in the report view and a message box, the workbench's parameters."""

import FreeCAD
import FreeCADGui

PARAMS = "User parameter:BaseApp/Preferences/Mod/HexDom"


def main_window():
    return FreeCADGui.getMainWindow()


def show_error(title, error):
    """Reports ``error`` in the report view and in a message box."""
    from PySide import QtGui
    text = str(error) or type(error).__name__
    FreeCAD.Console.PrintError("HexDom: {}: {}\n".format(title, text))
    QtGui.QMessageBox.critical(main_window(), "HexDom: " + title, text)


def get_param(name, default=""):
    return FreeCAD.ParamGet(PARAMS).GetString(name, default)


def set_param(name, value):
    FreeCAD.ParamGet(PARAMS).SetString(name, value)
