"""Coin3D scene pieces shared by the HexDom view providers (GUI only): polygons coloured per face
through an indexed material, plus line sets, behind one coordinate node.

Colour tables live here too, so that every view uses the same meaning for a colour: labels
+X red, -X cyan, +Y green, -Y magenta, +Z blue, -Z yellow (each axis colour against its
complement), patches of one label in shades of that colour, block types as in the HexDom Mesh
view (hex blue, prism orange, tet magenta).
"""

import colorsys

import numpy as np
from pivy import coin

LABEL_COLORS = [  # labels 1..6
    (0.90, 0.15, 0.15),  # +X red
    (0.10, 0.80, 0.85),  # -X cyan
    (0.15, 0.72, 0.15),  # +Y green
    (0.85, 0.22, 0.85),  # -Y magenta
    (0.18, 0.35, 0.95),  # +Z blue
    (0.95, 0.85, 0.10),  # -Z yellow
]
OTHER_COLOR = (0.6, 0.6, 0.6)
LINE_COLOR = (0.08, 0.08, 0.08)

# Shades of one label colour for its successive patches: (value scale, mix with white).
_SHADES = [(1.0, 0.0), (0.72, 0.0), (1.0, 0.30), (0.55, 0.0), (0.85, 0.15)]


def shade(rgb, k):
    """k-th shade of ``rgb`` (k = 0 is the colour itself)."""
    scale, white = _SHADES[k % len(_SHADES)]
    return tuple(min(1.0, (c * scale) * (1.0 - white) + white) for c in rgb)


def label_color(label):
    """Colour of label 1..6 (+X -X +Y -Y +Z -Z); grey for anything else."""
    return LABEL_COLORS[label - 1] if 1 <= label <= len(LABEL_COLORS) else OTHER_COLOR


def distinct_color(i):
    """Well-spread colours for ids (golden-ratio hues)."""
    h = (0.13 + 0.618033988749895 * i) % 1.0
    return colorsys.hsv_to_rgb(h, 0.55 + 0.25 * ((i // 7) % 2), 0.92)


def palette_by_patch_label(patches, labels):
    """(material index per triangle, colours): one colour per patch, a shade of its label's."""
    patches = np.asarray(patches)
    labels = np.asarray(labels)
    ids, first, inverse = np.unique(patches, return_index=True, return_inverse=True)
    patch_label = labels[first]
    seen = {}
    colors = []
    for p_label in patch_label.tolist():
        k = seen.get(p_label, 0)
        seen[p_label] = k + 1
        colors.append(shade(label_color(p_label), k))
    return inverse.astype(np.int64), colors


def palette_by_id(ids):
    """(material index per triangle, colours): one distinct colour per id value."""
    values, inverse = np.unique(np.asarray(ids), return_inverse=True)
    return inverse.astype(np.int64), [distinct_color(int(v)) for v in values.tolist()]


def _set_points(field, points):
    points = np.asarray(points, float).reshape(-1, 3)
    field.setNum(0)
    if len(points):
        field.setValues(0, len(points), points.tolist())


def _set_ints(field, values):
    values = np.asarray(values, np.int64).reshape(-1)
    field.setNum(0)
    if len(values):
        field.setValues(0, len(values), [int(v) for v in values.tolist()])


def _set_colors(field, colors):
    field.setNum(0)
    if len(colors):
        field.setValues(0, len(colors), [list(c) for c in colors])


def polygons_index(polygons):
    """Coin coordIndex for a list of polygons (each a list of point indices)."""
    out = []
    for poly in polygons:
        out.extend(int(i) for i in poly)
        out.append(-1)
    return out


def lines_index(edges):
    edges = np.asarray(edges, np.int64).reshape(-1, 2)
    return np.c_[edges, -np.ones(len(edges), np.int64)].reshape(-1)


class ColoredPolygons:
    """Faces coloured per face (material index per face), feature lines (thick) and all edges
    (thin), sharing one SoCoordinate3. ``groups`` maps display-mode names to their root nodes."""

    def __init__(self, modes=("Shaded", "Flat Lines", "Wireframe")):
        self.coords = coin.SoCoordinate3()
        self.material = coin.SoMaterial()
        self.faces = coin.SoIndexedFaceSet()
        self.features = coin.SoIndexedLineSet()
        self.edges = coin.SoIndexedLineSet()
        self.feature_style = coin.SoDrawStyle()
        self.feature_style.lineWidth = 2.0
        self.edge_style = coin.SoDrawStyle()
        self.edge_style.lineWidth = 1.0
        self.feature_color = coin.SoBaseColor()
        self.feature_color.rgb.setValue(*LINE_COLOR)
        self.edge_color = coin.SoBaseColor()
        self.edge_color.rgb.setValue(0.25, 0.25, 0.25)
        self.groups = {}
        for mode in modes:
            group = coin.SoSeparator()
            group.addChild(self.coords)
            if mode in ("Shaded", "Flat Lines", "Transparent"):
                group.addChild(self._face_node())
                group.addChild(self._line_node(self.feature_style, self.feature_color,
                                               self.features))
            if mode in ("Flat Lines", "Wireframe"):
                group.addChild(self._line_node(self.edge_style, self.edge_color, self.edges))
            if mode == "Wireframe":
                group.addChild(self._line_node(self.feature_style, self.feature_color,
                                               self.features))
            self.groups[mode] = group

    def _face_node(self):
        sep = coin.SoSeparator()
        hints = coin.SoShapeHints()
        hints.vertexOrdering = coin.SoShapeHints.COUNTERCLOCKWISE
        hints.shapeType = coin.SoShapeHints.UNKNOWN_SHAPE_TYPE
        hints.creaseAngle = 0.0
        binding = coin.SoMaterialBinding()
        binding.value = coin.SoMaterialBinding.PER_FACE_INDEXED
        offset = coin.SoPolygonOffset()
        offset.factor = 1.0
        offset.units = 1.0
        for node in (hints, binding, self.material, offset, self.faces):
            sep.addChild(node)
        return sep

    @staticmethod
    def _line_node(style, color, lines):
        sep = coin.SoSeparator()
        light = coin.SoLightModel()
        light.model = coin.SoLightModel.BASE_COLOR
        for node in (light, style, color, lines):
            sep.addChild(node)
        return sep

    def clear(self):
        self.set(np.zeros((0, 3)), [], [], [], np.zeros((0, 2)), np.zeros((0, 2)))

    def set(self, points, polygons, face_material, colors, features, edges, transparency=0.0):
        """points #P x 3; polygons: list of index lists; face_material: colour index per
        polygon; colors: RGB list; features / edges: #E x 2 point-index pairs."""
        # Empty the index fields first, so that Coin never sees indices beyond the points.
        for field in (self.faces.coordIndex, self.faces.materialIndex,
                      self.features.coordIndex, self.edges.coordIndex):
            field.setNum(0)
        _set_points(self.coords.point, points)
        _set_colors(self.material.diffuseColor, colors)
        self.material.transparency.setNum(0)
        self.material.transparency.setValues(0, max(len(colors), 1),
                                             [float(transparency)] * max(len(colors), 1))
        if isinstance(polygons, np.ndarray) and polygons.ndim == 2:
            index = np.c_[polygons, -np.ones(len(polygons), np.int64)].reshape(-1)
        else:
            index = polygons_index(polygons)
        _set_ints(self.faces.coordIndex, index)
        _set_ints(self.faces.materialIndex, face_material)
        _set_ints(self.features.coordIndex, lines_index(features))
        _set_ints(self.edges.coordIndex, lines_index(edges))

    def set_line_width(self, width):
        self.feature_style.lineWidth = float(width)


class VPCoinBase:
    """Mixin for view providers drawing a ColoredPolygons scene: display modes, rebuild on data
    changes (``DATA_PROPERTIES``) and view changes (``VIEW_PROPERTIES``). Subclasses implement
    ``build(obj, vobj, scene)``; errors while drawing clear the scene and go to the report view."""

    MODES = ("Shaded", "Flat Lines", "Wireframe")
    DEFAULT_MODE = "Shaded"
    DATA_PROPERTIES = ()
    VIEW_PROPERTIES = ()

    def attach(self, vobj):
        super().attach(vobj)
        self.scene = ColoredPolygons(self.MODES)
        for mode in self.MODES:
            vobj.addDisplayMode(self.scene.groups[mode], mode)
        self.refresh()

    def getDisplayModes(self, vobj):
        return list(self.MODES)

    def getDefaultDisplayMode(self):
        return self.DEFAULT_MODE

    def setDisplayMode(self, mode):
        return mode

    def updateData(self, obj, prop):
        if prop in self.DATA_PROPERTIES:
            self.refresh()

    def onChanged(self, vobj, prop):
        if prop in self.VIEW_PROPERTIES:
            self.refresh()

    def refresh(self):
        scene = getattr(self, "scene", None)
        obj = getattr(self, "Object", None)
        if scene is None or obj is None:
            return
        try:
            if not self.build(obj, self.ViewObject, scene):
                scene.clear()
        except (ValueError, IndexError, TypeError, AttributeError) as e:
            import FreeCAD
            scene.clear()
            FreeCAD.Console.PrintError("HexDom: cannot draw {}: {}\n".format(obj.Label, e))

    def build(self, obj, vobj, scene):
        """Fills ``scene``; returns False when there is nothing (consistent) to draw."""
        raise NotImplementedError


def triangle_arrays(surface_obj):
    """(V, F) of a HexDom Surface's properties, or None while they are inconsistent."""
    V = np.array([tuple(p) for p in surface_obj.Points], float).reshape(-1, 3)
    flat = list(surface_obj.Triangles)
    if len(flat) % 3:
        return None
    F = np.array(flat, np.int64).reshape(-1, 3)
    if len(F) and (F.min() < 0 or F.max() >= len(V)):
        return None
    return V, F
