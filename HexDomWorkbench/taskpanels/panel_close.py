"""What the two editing panels (Edit Patches, Build Polycube) share when they close (GUI only)."""

import FreeCADGui


def close_panel(panel, active, document_name):
    """Closes an editing panel once: takes it off ``active`` (its module's list of open panels),
    gives FreeCAD's Undo / Redo back, removes the overlay, shows again the objects it hid, and
    leaves edit mode (or closes the task dialog) of the document named ``document_name``."""
    if panel._closed:
        return
    panel._closed = True
    if panel in active:
        active.remove(panel)
    panel.undo_redirect.remove()
    if panel.overlay is not None:
        panel.overlay.remove()
        panel.overlay = None
    for vobj in panel._hidden:
        try:
            vobj.Visibility = True
        except (RuntimeError, ReferenceError):
            pass
    panel._hidden = []
    gui_doc = FreeCADGui.getDocument(document_name)
    if gui_doc is not None and gui_doc.getInEdit() is not None:
        gui_doc.resetEdit()
    else:
        FreeCADGui.Control.closeDialog()
