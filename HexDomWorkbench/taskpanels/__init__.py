"""Task panels: task_<object>.py with _TaskPanel(obj), editing one object's properties and
recomputing (GUI only). What a panel does lives in a module of its own that imports neither Qt
nor FreeCAD, so that scripts and tests drive it as clicks would: patch_editing.PatchEditor
behind task_segmentation (Edit Patches), polycube_building.PolycubeBuilder behind task_polycube
(Build Polycube). view_overlay holds the Coin drawing and picking both panels share."""
