"""View provider of HexDom Polycube: the block wireframe over semi-transparent boundary faces,
coloured by block type (hex blue, prism orange, tet magenta, as in the HexDom Mesh view).
Double-click (or HexDom_BuildPolycube) opens the Build Polycube task panel."""

import numpy as np

from . import coin_mesh
from .view_base import VPBaseHexDomObject, edit_on_double_click, open_task_panel

HEX, WEDGE, TET = 12, 13, 10
# Faces of each block type in VTK node order, outward.
BLOCK_FACES = {
    HEX: [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)],
    WEDGE: [(0, 1, 2), (3, 5, 4), (0, 3, 4, 1), (1, 4, 5, 2), (2, 5, 3, 0)],
    TET: [(0, 2, 1), (0, 1, 3), (1, 2, 3), (2, 0, 3)],
}
BLOCK_COLORS = {HEX: (0.25, 0.52, 0.90), WEDGE: (1.00, 0.60, 0.10), TET: (0.80, 0.20, 0.80)}


def block_faces(blocks, types):
    """(boundary faces as index lists, block type of each, all block edges #E x 2)."""
    count, owner = {}, {}
    edges = set()
    for cell, t in zip(blocks, types):
        for face in BLOCK_FACES.get(t, ()):
            ids = [int(cell[i]) for i in face]
            key = tuple(sorted(ids))
            count[key] = count.get(key, 0) + 1
            owner.setdefault(key, (ids, t))
            for a, b in zip(ids, ids[1:] + ids[:1]):
                edges.add((min(a, b), max(a, b)))
    boundary = [owner[k] for k, c in count.items() if c == 1]
    faces = [ids for ids, _ in boundary]
    face_types = [t for _, t in boundary]
    return faces, face_types, np.array(sorted(edges), np.int64).reshape(-1, 2)


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
            n = {HEX: 8, WEDGE: 6, TET: 4}.get(t, 0)
            if n == 0 or cell[:n].min() < 0 or cell[:n].max() >= len(V):
                return False
        faces, face_types, edges = block_faces(blocks.tolist(), types)
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
