"""Task panels: task_<object>.py with _TaskPanel(obj), editing one object's properties and
recomputing (GUI only). What a panel does lives in HexDomWorkbench.logic, which imports neither
Qt nor FreeCAD, so that scripts and tests drive it as clicks would: logic.patch_editing.PatchEditor
behind task_segmentation (Edit Patches), logic.polycube_building.PolycubeBuilder behind
task_polycube (Build Polycube). view_overlay holds the Coin drawing and picking both panels share.
Panels import the objects, the logic, the drawing helpers and guiutils; never the commands, api or
make (a panel that needs a new object is handed the function that makes it)."""
