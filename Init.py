# HexDom for FreeCAD: application start-up (runs in every FreeCAD, with or without GUI).
# Registers file types only; nothing here imports the compiled core.
import FreeCAD

FreeCAD.addImportType("HexDom volume mesh (*.k *.vtk *.vtu)", "HexDomWorkbench.fileio")
FreeCAD.addExportType("HexDom volume mesh (*.k *.vtk *.vtu)", "HexDomWorkbench.fileio")
