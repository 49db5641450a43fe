"""View provider of HexDom Polycube: the block wireframe over semi-transparent boundary faces,
coloured by block type (hex blue, prism orange, tet magenta, as in the HexDom Mesh view).
Double-click (or HexDom_BuildPolycube) opens the Build Polycube task panel."""

import numpy as np

from ..logic.cells import HEX, NODE_COUNT, TET, WEDGE, structure_boundary
from . import coin_mesh
from .view_base import VPBaseHexDomObject, edit_on_double_click, open_task_panel

BLOCK_COLORS = {HEX: (0.25, 0.52, 0.90), WEDGE: (1.00, 0.60, 0.10), TET: (0.80, 0.20, 0.80)}


class VPPolycube(coin_mesh.VPCoinBase, VPBaseHexDomObject):
    """View provider of HexDom Polycube objects."""

    MODES = ("Transparent", "Shaded", "Wireframe")
    DEFAULT_MODE = "Transparent"
    DATA_PROPERTIES = ("Points", "Blocks", "BlockTypes")
    VIEW_PROPERTIES = ("FaceTransparency", "LineWidth", "DisplayMode")

    def add_properties(self, vobj):
        if not hasattr(vobj, "FaceTransparency"):
            vobj.addProperty("App::PropertyPercent", "FaceTransparency", "HexDom",
                             "Transparency of the block faces in the Transparent display mode")
            vobj.FaceTransparency = 60
        if not hasattr(vobj, "LineWidth"):
            vobj.addProperty("App::PropertyFloat", "LineWidth", "HexDom",
                             "Width of the block edges")
            vobj.LineWidth = 2.0

    def build(self, obj, vobj, scene):
        V = np.array([tuple(p) for p in obj.Points], float).reshape(-1, 3)
        flat = list(obj.Blocks)
        types = list(obj.BlockTypes)
        if len(flat) != 8 * len(types):
            return False
        blocks = np.array(flat, np.int64).reshape(-1, 8)
        for cell, t in zip(blocks, types):
            n = NODE_COUNT.get(t, 0)
            if n == 0 or cell[:n].min() < 0 or cell[:n].max() >= len(V):
                return False
        faces, face_types, edges = structure_boundary(blocks.tolist(), types)
        kinds = sorted(set(face_types))
        material = [kinds.index(t) for t in face_types]
        colors = [BLOCK_COLORS[t] for t in kinds]
        transparent = getattr(vobj, "DisplayMode", "Transparent") == "Transparent"
        alpha = getattr(vobj, "FaceTransparency", 60) / 100.0 if transparent else 0.0
        scene.set(V, faces, material, colors, edges, edges, transparency=alpha)
        scene.set_line_width(getattr(vobj, "LineWidth", 2.0))
        return True

    def setEdit(self, vobj, mode=0):
        if mode != 0:
            return None
        from ..taskpanels import task_polycube
        segmentation = getattr(self, "edit_segmentation", None)
        self.edit_segmentation = None
        return open_task_panel(
            lambda: task_polycube._TaskPanel(vobj.Object, segmentation=segmentation),
            "Build polycube")

    def unsetEdit(self, vobj, mode=0):
        import FreeCADGui
        FreeCADGui.Control.closeDialog()
        return True

    def doubleClicked(self, vobj):
        return edit_on_double_click(vobj)
