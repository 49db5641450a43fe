"""A Coin sub-graph that a task panel shows in the active 3D view while it is open, with the
mouse handling the panels share (GUI only).

Picking is done in numpy from the camera's projection matrix rather than with Coin pick actions:
``project`` maps points to view pixels (origin at the lower left, as Coin's events and
View3DInventor.getPointOnScreen), ``ray`` gives the line of sight through a pixel, and the panels
intersect it with their own triangles and vertices. The same code serves mouse clicks and the
tests that call the panels' public methods with pixel positions.
"""

import numpy as np
from pivy import coin

import FreeCAD
import FreeCADGui

CLICK_TOLERANCE = 4  # pixels a press may move and still count as a click
LASSO_STEP = 3  # pixels the mouse moves before the lasso takes another point


def active_view():
    gui_doc = FreeCADGui.ActiveDocument
    view = getattr(gui_doc, "ActiveView", None) if gui_doc is not None else None
    if view is None or not hasattr(view, "getSceneGraph"):
        return None
    return view


class ViewOverlay:
    """Owns ``root`` (an SoSeparator added to the view's scene graph) and, once ``install_mouse``
    ran, turns mouse presses into ``on_click(x, y, ctrl, shift)``, in box mode drags into
    ``on_box(x0, y0, x1, y1)`` and in lasso mode drags into ``on_lasso(points)`` (the polygon the
    mouse drew, #P x 2; pixels, origin lower left)."""

    def __init__(self, view=None):
        self.view = view or active_view()
        self.root = coin.SoSeparator()
        self.root.setName("HexDomTaskOverlay")
        self.on_click = None
        self.on_box = None
        self.on_lasso = None
        self.box_mode = False
        self.lasso_mode = False
        self._press = None
        self._lasso = []
        self._redirected = None
        self._callbacks = []
        self._band = _RubberBand()
        self.root.addChild(self._band.root)
        if self.view is not None:
            self.view.getSceneGraph().addChild(self.root)

    # --------------------------------------------------------------------------------------------
    # Life cycle

    def install_mouse(self):
        if self.view is None or self._callbacks:
            return
        for kind, handler in ((coin.SoMouseButtonEvent.getClassTypeId(), self._mouse_button),
                              (coin.SoLocation2Event.getClassTypeId(), self._mouse_move)):
            self._callbacks.append((kind, self.view.addEventCallbackPivy(kind, handler)))

    def remove(self):
        """Takes the overlay out of the view and stops listening to the mouse."""
        if self.view is None:
            return
        self._grab_mouse(False)
        for kind, cb in self._callbacks:
            try:
                self.view.removeEventCallbackPivy(kind, cb)
            except (RuntimeError, AttributeError):
                pass
        self._callbacks = []
        try:
            self.view.getSceneGraph().removeChild(self.root)
        except (RuntimeError, AttributeError):
            pass
        self.view = None

    # --------------------------------------------------------------------------------------------
    # Camera

    def size(self):
        """(width, height) of the view in pixels."""
        region = self.view.getViewer().getSoRenderManager().getViewportRegion()
        w, h = region.getViewportSizePixels().getValue()
        return int(w), int(h)

    def _matrix(self):
        region = self.view.getViewer().getSoRenderManager().getViewportRegion()
        camera = self.view.getCameraNode()
        volume = camera.getViewVolume(region.getViewportAspectRatio())
        return np.array(volume.getMatrix().getValue(), float)

    def project(self, points):
        """(#P x 2 pixel positions, origin lower left; #P depths in -1..1, smaller is nearer)."""
        points = np.asarray(points, float).reshape(-1, 3)
        clip = np.c_[points, np.ones(len(points))] @ self._matrix()
        w = np.where(np.abs(clip[:, 3]) > 1e-300, clip[:, 3], 1e-300)
        ndc = clip[:, :3] / w[:, None]
        width, height = self.size()
        xy = np.c_[(ndc[:, 0] + 1.0) * 0.5 * width, (ndc[:, 1] + 1.0) * 0.5 * height]
        return xy, ndc[:, 2]

    def ray(self, x, y):
        """(origin, unit direction) of the line of sight through pixel (x, y)."""
        width, height = self.size()
        nx, ny = 2.0 * x / width - 1.0, 2.0 * y / height - 1.0
        inverse = np.linalg.inv(self._matrix())
        ends = np.array([[nx, ny, -1.0, 1.0], [nx, ny, 1.0, 1.0]]) @ inverse
        ends = ends[:, :3] / ends[:, 3:]
        d = ends[1] - ends[0]
        return ends[0], d / np.linalg.norm(d)

    def view_direction(self):
        return np.array(tuple(self.view.getViewDirection()), float)

    def zoom_to(self, lo, hi, margin=1.3):
        """Fits the camera to the box [lo, hi] keeping its orientation."""
        lo, hi = np.asarray(lo, float), np.asarray(hi, float)
        centre, half = 0.5 * (lo + hi), 0.5 * (hi - lo) * margin
        half = np.maximum(half, 1e-6 * max(float(np.abs(hi - lo).max()), 1e-9))
        a, b = centre - half, centre + half
        region = self.view.getViewer().getSoRenderManager().getViewportRegion()
        camera = self.view.getCameraNode()
        camera.viewBoundingBox(coin.SbBox3f(*(list(map(float, a)) + list(map(float, b)))),
                               region.getViewportAspectRatio(), 1.0)

    # --------------------------------------------------------------------------------------------
    # Mouse

    def set_box_mode(self, on):
        self.box_mode = bool(on)
        if on:
            self.lasso_mode = False
        self._press = None
        self._band.hide()
        self._grab_mouse(self.box_mode or self.lasso_mode)

    def set_lasso_mode(self, on):
        self.lasso_mode = bool(on)
        if on:
            self.box_mode = False
        self._press = None
        self._lasso = []
        self._band.hide()
        self._grab_mouse(self.box_mode or self.lasso_mode)

    def _grab_mouse(self, on):
        """While a box or lasso is drawn, the view's navigation style must not take the drag
        for a rotation (it would swallow the mouse moves, depending on timing): the viewer
        sends every event to the scene graph, where the overlay's callbacks get them."""
        viewer = self.view.getViewer() if self.view is not None else None
        if viewer is None or not hasattr(viewer, "setRedirectToSceneGraph"):
            return
        if on and self._redirected is None:
            self._redirected = bool(viewer.isRedirectedToSceneGraph())
            viewer.setRedirectToSceneGraph(True)
        elif not on and self._redirected is not None:
            viewer.setRedirectToSceneGraph(self._redirected)
            self._redirected = None

    def _mouse_button(self, event_cb):
        event = event_cb.getEvent()
        if event.getButton() != coin.SoMouseButtonEvent.BUTTON1:
            return
        x, y = event.getPosition().getValue()
        if event.getState() == coin.SoButtonEvent.DOWN:
            self._press = (x, y)
            self._lasso = [(x, y)]
            if self.box_mode or self.lasso_mode:
                event_cb.setHandled()
            return
        if event.getState() != coin.SoButtonEvent.UP or self._press is None:
            return
        x0, y0 = self._press
        self._press = None
        try:
            if self.lasso_mode:
                event_cb.setHandled()
                self._band.hide()
                self.lasso_mode = False
                self._grab_mouse(False)
                points = self._lasso + [(x, y)]
                self._lasso = []
                if self.on_lasso is not None and len(points) >= 3:
                    self.on_lasso(np.array(points, float))
            elif self.box_mode:
                event_cb.setHandled()
                self._band.hide()
                self.box_mode = False
                self._grab_mouse(False)
                if self.on_box is not None:
                    self.on_box(min(x0, x), min(y0, y), max(x0, x), max(y0, y))
            elif abs(x - x0) <= CLICK_TOLERANCE and abs(y - y0) <= CLICK_TOLERANCE:
                if self.on_click is not None:
                    self.on_click(x, y, event.wasCtrlDown(), event.wasShiftDown())
        except Exception as e:  # an exception must not escape into Coin's event loop
            FreeCAD.Console.PrintError("HexDom: {}\n".format(e))

    def _mouse_move(self, event_cb):
        if not (self.box_mode or self.lasso_mode) or self._press is None:
            return
        event_cb.setHandled()
        x, y = event_cb.getEvent().getPosition().getValue()
        if self.box_mode:
            self._band.show(self._press, (x, y), self.size())
            return
        last = self._lasso[-1]
        if abs(x - last[0]) + abs(y - last[1]) >= LASSO_STEP:
            self._lasso.append((x, y))
            self._band.show_polygon(self._lasso, self.size())


class _RubberBand:
    """A dashed rectangle drawn over the view (its own camera maps -1..1 to the viewport)."""

    def __init__(self):
        self.root = coin.SoAnnotation()
        self.switch = coin.SoSwitch()
        self.switch.whichChild = coin.SO_SWITCH_NONE
        sep = coin.SoSeparator()
        camera = coin.SoOrthographicCamera()
        camera.viewportMapping = coin.SoCamera.LEAVE_ALONE
        camera.position = (0.0, 0.0, 1.0)
        camera.height = 2.0
        camera.nearDistance = 0.5
        camera.farDistance = 1.5
        light = coin.SoLightModel()
        light.model = coin.SoLightModel.BASE_COLOR
        color = coin.SoBaseColor()
        color.rgb = (0.1, 0.1, 0.1)
        style = coin.SoDrawStyle()
        style.lineWidth = 1.5
        style.linePattern = 0xF0F0
        self.coords = coin.SoCoordinate3()
        self.lines = coin.SoLineSet()
        for node in (camera, light, color, style, self.coords, self.lines):
            sep.addChild(node)
        self.switch.addChild(sep)
        self.root.addChild(self.switch)

    def show(self, a, b, size):
        """The rectangle with corners ``a`` and ``b`` (pixels)."""
        self.show_polygon([(a[0], a[1]), (b[0], a[1]), (b[0], b[1]), (a[0], b[1])], size)

    def show_polygon(self, points, size):
        """The closed polygon through ``points`` (pixels)."""
        w, h = size
        pts = [(2.0 * x / w - 1.0, 2.0 * y / h - 1.0, 0.0) for x, y in points]
        pts.append(pts[0])
        self.lines.numVertices.setValue(len(pts))
        self.coords.point.setNum(0)
        self.coords.point.setValues(0, len(pts), pts)
        self.switch.whichChild = 0

    def hide(self):
        self.switch.whichChild = coin.SO_SWITCH_NONE


def pick_triangle(origin, direction, V, F):
    """(triangle, point) where the ray first hits the triangles F of V, or (None, None)."""
    V = np.asarray(V, float)
    F = np.asarray(F, np.int64).reshape(-1, 3)
    if len(F) == 0:
        return None, None
    a = V[F[:, 0]]
    e1, e2 = V[F[:, 1]] - a, V[F[:, 2]] - a
    p = np.cross(direction, e2)
    det = np.einsum("ij,ij->i", e1, p)
    ok = np.abs(det) > 1e-300
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = origin - a
    u = np.einsum("ij,ij->i", s, p) * inv
    q = np.cross(s, e1)
    v = (q @ direction) * inv
    t = np.einsum("ij,ij->i", e2, q) * inv
    eps = 1e-9
    hit = ok & (u >= -eps) & (v >= -eps) & (u + v <= 1 + eps) & (t > 0)
    if not np.any(hit):
        return None, None
    candidates = np.flatnonzero(hit)
    best = int(candidates[np.argmin(t[candidates])])
    return best, origin + t[best] * direction


def front_facing(xy, F):
    """Triangles whose projected corners (``xy``: pixel positions of the points) turn
    counter-clockwise, i.e. that face the camera (orthographic or perspective)."""
    F = np.asarray(F, np.int64).reshape(-1, 3)
    a, b, c = xy[F[:, 0]], xy[F[:, 1]], xy[F[:, 2]]
    return ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1])
            - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])) > 0


def visible_points(xy, depth, F, facing, queries_xy, queries_depth, cell=16.0):
    """Which query points (pixel position, depth) no facing triangle hides: a software depth test
    against the triangles (``xy``, ``depth`` per point; ``facing`` the triangles that can hide
    anything, those facing the camera on a closed surface), binned on a grid of ``cell`` pixels."""
    F = np.asarray(F, np.int64).reshape(-1, 3)[facing]
    q = np.asarray(queries_xy, float).reshape(-1, 2)
    qd = np.asarray(queries_depth, float).reshape(-1)
    if len(F) == 0 or len(q) == 0:
        return np.ones(len(q), bool)
    txy = xy[F]  # (T, 3, 2)
    td = depth[F]  # (T, 3)
    lo = np.floor(txy.min(axis=1) / cell).astype(np.int64)
    hi = np.floor(txy.max(axis=1) / cell).astype(np.int64)
    span = (hi - lo + 1)
    count = span[:, 0] * span[:, 1]
    keep = count < 4096  # a triangle covering much of the view cannot be binned cheaply
    tri = np.repeat(np.flatnonzero(keep), count[keep])
    first = np.repeat(np.cumsum(count[keep]) - count[keep], count[keep])
    k = np.arange(len(tri)) - first
    cx = lo[tri, 0] + k % span[tri, 0]
    cy = lo[tri, 1] + k // span[tri, 0]
    offset = np.array([min(lo[:, 0].min(), np.floor(q[:, 0].min() / cell)),
                       min(lo[:, 1].min(), np.floor(q[:, 1].min() / cell))], np.int64)
    width = int(max(hi[:, 0].max(), np.floor(q[:, 0].max() / cell)) - offset[0] + 2)
    key = (cx - offset[0]) + (cy - offset[1]) * width
    order = np.argsort(key, kind="stable")
    key, tri = key[order], tri[order]
    qcell = np.floor(q / cell).astype(np.int64)
    qkey = (qcell[:, 0] - offset[0]) + (qcell[:, 1] - offset[1]) * width
    start = np.searchsorted(key, qkey, side="left")
    stop = np.searchsorted(key, qkey, side="right")
    n = stop - start
    pq = np.repeat(np.arange(len(q)), n)
    pt = tri[np.repeat(start, n) + (np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n))]
    # Also test the unbinned (huge) triangles against every query.
    big = np.flatnonzero(~keep)
    if len(big):
        pq = np.concatenate([pq, np.repeat(np.arange(len(q)), len(big))])
        pt = np.concatenate([pt, np.tile(big, len(q))])
    a, b, c = txy[pt, 0], txy[pt, 1], txy[pt, 2]
    p = q[pq]
    v0, v1, v2 = b - a, c - a, p - a
    den = v0[:, 0] * v1[:, 1] - v1[:, 0] * v0[:, 1]
    safe = np.where(np.abs(den) > 1e-12, den, 1.0)
    s = (v2[:, 0] * v1[:, 1] - v1[:, 0] * v2[:, 1]) / safe
    t = (v0[:, 0] * v2[:, 1] - v2[:, 0] * v0[:, 1]) / safe
    inside = (np.abs(den) > 1e-12) & (s >= 0) & (t >= 0) & (s + t <= 1)
    d = td[pt, 0] + s * (td[pt, 1] - td[pt, 0]) + t * (td[pt, 2] - td[pt, 0])
    nearest = np.full(len(q), np.inf)
    np.minimum.at(nearest, pq[inside], d[inside])
    extent = float(depth.max() - depth.min()) if len(depth) else 1.0
    return qd <= nearest + 1e-4 * max(extent, 1e-12)


def set_points(field, points):
    points = np.asarray(points, float).reshape(-1, 3)
    field.setNum(0)
    if len(points):
        field.setValues(0, len(points), points.tolist())


def set_ints(field, values):
    values = [int(v) for v in np.asarray(values, np.int64).reshape(-1).tolist()]
    field.setNum(0)
    if values:
        field.setValues(0, len(values), values)


def marker_node(color, marker="CIRCLE_FILLED", size=9):
    """(separator, coordinates, marker set, colour) drawing points as markers of one colour
    (FreeCAD's marker names and sizes: "CIRCLE_FILLED", "CIRCLE_LINE", "SQUARE_FILLED", ...)."""
    sep = coin.SoSeparator()
    light = coin.SoLightModel()
    light.model = coin.SoLightModel.BASE_COLOR
    base = coin.SoBaseColor()
    base.rgb = tuple(color)
    coords = coin.SoCoordinate3()
    coords.point.setNum(0)  # Coin's default is one point at the origin
    markers = coin.SoMarkerSet()
    markers.markerIndex = FreeCADGui.getMarkerIndex(marker, int(size))
    for node in (light, base, coords, markers):
        sep.addChild(node)
    return sep, coords, markers, base


def line_node(color, width=2.0):
    """(separator, coordinates, indexed line set) drawing lines of one colour."""
    sep = coin.SoSeparator()
    light = coin.SoLightModel()
    light.model = coin.SoLightModel.BASE_COLOR
    base = coin.SoBaseColor()
    base.rgb = tuple(color)
    style = coin.SoDrawStyle()
    style.lineWidth = float(width)
    coords = coin.SoCoordinate3()
    coords.point.setNum(0)
    lines = coin.SoIndexedLineSet()
    for node in (light, base, style, coords, lines):
        sep.addChild(node)
    return sep, coords, lines, base


def face_node(color, transparency=0.0, offset=None):
    """(separator, coordinates, indexed face set, material) drawing faces of one colour."""
    sep = coin.SoSeparator()
    hints = coin.SoShapeHints()
    hints.vertexOrdering = coin.SoShapeHints.COUNTERCLOCKWISE
    hints.shapeType = coin.SoShapeHints.UNKNOWN_SHAPE_TYPE
    material = coin.SoMaterial()
    material.diffuseColor = tuple(color)
    material.emissiveColor = tuple(0.35 * c for c in color)
    material.transparency = float(transparency)
    coords = coin.SoCoordinate3()
    coords.point.setNum(0)
    faces = coin.SoIndexedFaceSet()
    nodes = [hints, material]
    if offset is not None:
        po = coin.SoPolygonOffset()
        po.factor = float(offset)
        po.units = float(offset)
        nodes.append(po)
    for node in nodes + [coords, faces]:
        sep.addChild(node)
    return sep, coords, faces, material


def polygon_index(polygons):
    out = []
    for poly in polygons:
        out.extend(int(i) for i in poly)
        out.append(-1)
    return out


def edge_index(edges):
    edges = np.asarray(edges, np.int64).reshape(-1, 2)
    return np.c_[edges, -np.ones(len(edges), np.int64)].reshape(-1)
