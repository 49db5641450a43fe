"""View provider of HexDom Segmentation: the surface coloured by polycube label (+X red, -X cyan,
+Y green, -Y magenta, +Z blue, -Z yellow; patches of one label in shades of its colour) or by
patch, with the patch boundaries drawn as lines. Double-click (or HexDom_EditPatches) opens the
Edit Patches task panel."""

import numpy as np

from ..logic.triangles import all_edges, boundary_edges
from . import coin_mesh
from .view_base import VPBaseHexDomObject, edit_on_double_click, open_task_panel

COLOR_BY = ["Label", "Patch", "Plain"]


class VPSegmentation(coin_mesh.VPCoinBase, VPBaseHexDomObject):
    """View provider of HexDom Segmentation objects."""

    DATA_PROPERTIES = ("Labels", "Patches", "Surface")
    VIEW_PROPERTIES = ("ColorBy",)

    def add_properties(self, vobj):
        if not hasattr(vobj, "ColorBy"):
            vobj.addProperty("App::PropertyEnumeration", "ColorBy", "HexDom",
                             "Colour by label (+X red, -X cyan, +Y green, -Y magenta, +Z blue, "
                             "-Z yellow; shades per patch), by patch, or plain")
            vobj.ColorBy = COLOR_BY
            vobj.ColorBy = "Label"

    def build(self, obj, vobj, scene):
        surface = getattr(obj, "Surface", None)
        if surface is None or not hasattr(surface, "Triangles"):
            return False
        arrays = coin_mesh.triangle_arrays(surface)
        labels = np.array(obj.Labels, np.int64)
        patches = np.array(obj.Patches, np.int64)
        if arrays is None or len(labels) != len(arrays[1]) or len(patches) != len(labels):
            return False
        V, F = arrays
        color_by = getattr(vobj, "ColorBy", "Label")
        if color_by == "Label":
            material, colors = coin_mesh.palette_by_patch_label(patches, labels)
        elif color_by == "Patch":
            material, colors = coin_mesh.palette_by_id(patches)
        else:
            material, colors = np.zeros(len(F), np.int64), [(0.75, 0.75, 0.78)]
        scene.set(V, F, material, colors, boundary_edges(F, patches),
                  all_edges(F))
        return True

    def claimChildren(self):
        surface = getattr(getattr(self, "Object", None), "Surface", None)
        return [surface] if surface is not None else []

    def setEdit(self, vobj, mode=0):
        if mode != 0:
            return None
        from ..taskpanels import task_segmentation
        return open_task_panel(lambda: task_segmentation._TaskPanel(vobj.Object), "Edit patches")

    def unsetEdit(self, vobj, mode=0):
        import FreeCADGui
        FreeCADGui.Control.closeDialog()
        return True

    def doubleClicked(self, vobj):
        return edit_on_double_click(vobj)
