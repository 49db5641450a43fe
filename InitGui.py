# HexDom for FreeCAD: GUI start-up. Commands are imported only when the workbench is activated.
import FreeCADGui


class HexDomWorkbench(FreeCADGui.Workbench):
    """Hex-dominant volume meshes by polycubes, for FEM."""

    MenuText = "HexDom"
    ToolTip = "Hex-dominant volume meshing by polycubes, for FEM analyses"

    def __init__(self):
        # Locate the icon without importing the package (which loads the compiled core).
        import importlib.util
        import os
        spec = importlib.util.find_spec("HexDomWorkbench")
        if spec is not None and spec.submodule_search_locations:
            root = os.path.dirname(list(spec.submodule_search_locations)[0])
            self.__class__.Icon = os.path.join(root, "Resources", "icons", "HexDomWorkbench.svg")

    def Initialize(self):
        from HexDomWorkbench.commands import commands
        self.appendToolbar("HexDom pipeline", commands.PIPELINE_TOOLBAR)
        self.appendToolbar("HexDom", commands.TOOLBAR)
        self.appendMenu("&HexDom", commands.MENU)

    def Activated(self):
        pass

    def Deactivated(self):
        pass

    def GetClassName(self):
        return "Gui::PythonWorkbench"


FreeCADGui.addWorkbench(HexDomWorkbench())
