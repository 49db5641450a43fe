"""Edit Patches: the task panel of a HexDom Segmentation (GUI only).

The surface is drawn with each patch coloured (its label's colour, a shade per patch); a click in
the 3D view picks facets, whole patches, whole CAD faces or the vertices of a split path, a drag
in box mode picks the visible facets facing the camera inside the rectangle, a drag in lasso mode
those inside the polygon the mouse draws (hidden ones too when asked), and "Add selected CAD
faces" takes the faces selected on the source Part. The selection then joins a patch, becomes
a new patch, or takes one of the six orientations; patches merge and split. The problems
core.check_patches finds are listed live; clicking one selects its facets, marks its vertex and
zooms to it. Undo and redo work inside the panel, and while it is open FreeCAD's Edit > Undo /
Redo, their toolbar buttons and Ctrl+Z / Ctrl+Shift+Z / Ctrl+Y act on them rather than on the
document (panel_undo.UndoRedirect). OK writes the edits into the Segmentation
(EditedTriangles / EditedLabels, EditedPatchTriangles / EditedPatchIds) and recomputes; Cancel
leaves it untouched.

All the work is done by logic.patch_editing.PatchEditor; the public methods below are what the widgets
call, and what tests call to act as clicks would.
"""

import numpy as np

import FreeCAD
import FreeCADGui
from PySide import QtGui

from .. import core, paths
from ..guiutils.dialogs import show_error
from ..logic.patch_editing import LABEL_NAMES, PatchEditor, points_in_polygon
from ..logic.triangles import boundary_edges
from ..objects import segmentation
from ..viewproviders import coin_mesh
from . import panel_close, panel_undo, view_overlay

USER_ERRORS = (core.Error, ValueError)
PICK_MODES = ("facet", "patch", "face", "path")
SELECTION_COLOR = (1.0, 1.0, 1.0)
PATH_COLOR = (0.0, 0.0, 0.0)
PROBLEM_COLOR = (1.0, 0.0, 0.0)

_active = []


def active_panel():
    """The open Edit Patches panel, or None (for macros and tests)."""
    return _active[-1] if _active else None


class _TaskPanel:
    """Edit Patches over the HexDom Segmentation ``obj``."""

    def __init__(self, obj):
        self.obj = obj
        surface = segmentation.get_surface(obj)
        labels = np.asarray(obj.Labels, np.int32)
        face_ids = np.asarray(getattr(obj.Surface, "FaceId", []), np.int32)
        self.editor = PatchEditor(surface.V, surface.F, surface.patch,
                                  labels if len(labels) == len(surface.F) else None,
                                  face_ids if len(face_ids) == len(surface.F) else None,
                                  frame=segmentation.frame_matrix(obj),
                                  stretch=segmentation.stretch_factors(obj))
        self.pick_mode = "facet"
        self.highlighted = None
        self.last_error = ""
        self._closed = False
        self.form = FreeCADGui.PySideUic.loadUi(paths.ui("EditPatches.ui"))
        self.form.setWindowIcon(QtGui.QIcon(paths.icon("HexDom_EditPatches")))
        self.form.lw_problems.setWordWrap(True)
        self._connect()
        self.overlay = None
        self._hidden = []
        if view_overlay.active_view() is not None:
            self.overlay = view_overlay.ViewOverlay()
            self._build_scene()
            self.overlay.on_click = self._on_click
            self.overlay.on_box = self._on_box
            self.overlay.on_lasso = self._on_lasso
            self.overlay.install_mouse()
            # The panel draws the patches itself; hide the object, its surface and what is made
            # from it (a mesh in front of the patches would hide them).
            for o in [obj, obj.Surface] + list(obj.InListRecursive):
                vobj = getattr(o, "ViewObject", None)
                if vobj is not None and vobj.Visibility:
                    self._hidden.append(vobj)
                    vobj.Visibility = False
        self.editor.listeners.append(self._on_editor)
        self.undo_redirect = panel_undo.UndoRedirect(
            self.undo, self.redo, lambda: self.editor.can_undo, lambda: self.editor.can_redo)
        self._refresh_patches()
        self._refresh_selection()
        _active.append(self)

    # --------------------------------------------------------------------------------------------
    # FreeCAD task dialog protocol

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)

    def accept(self):
        """OK: writes the edits into the Segmentation, recomputes it and closes the panel."""
        try:
            self.apply()
        except USER_ERRORS as e:
            show_error("Edit patches", e)
            return False
        self._close()
        return True

    def reject(self):
        """Cancel: closes the panel; the Segmentation keeps what it had."""
        self._close()
        return True

    # --------------------------------------------------------------------------------------------
    # Selection

    def select_facets(self, triangles, mode="add"):
        return self.editor.select_facets(triangles, mode)

    def select_patch(self, patch_id, mode="add"):
        return self.editor.select_patch(patch_id, mode)

    def select_face(self, face_id, mode="add"):
        return self.editor.select_face(face_id, mode)

    def clear_selection(self):
        self.editor.clear_selection()
        self.editor.clear_path()

    def set_pick_mode(self, mode):
        """What a click picks: "facet", "patch", "face" (CAD face) or "path" (split path)."""
        if mode not in PICK_MODES:
            raise ValueError("pick mode '{}' is not one of {}".format(mode, PICK_MODES))
        self.pick_mode = mode
        index = PICK_MODES.index(mode)
        if self.form.cb_pick_mode.currentIndex() != index:
            self.form.cb_pick_mode.setCurrentIndex(index)

    def pick(self, x, y):
        """(triangle, point) under view pixel (x, y) (origin lower left), or (None, None)."""
        if self.overlay is None:
            return None, None
        origin, direction = self.overlay.ray(x, y)
        return view_overlay.pick_triangle(origin, direction, self.editor.V, self.editor.F)

    def click(self, x, y, ctrl=False, shift=False):
        """A left click at view pixel (x, y): toggles the facet, patch or CAD face under it, or
        adds its nearest vertex to the split path. Returns the picked triangle or None."""
        triangle, point = self.pick(x, y)
        if triangle is None:
            return None
        e = self.editor
        if self.pick_mode == "path":
            e.add_path_vertex(e.nearest_vertex(triangle, point))
            return triangle
        if self.pick_mode == "patch":
            group = np.flatnonzero(e.patches == e.patches[triangle])
        elif self.pick_mode == "face" and e.face_ids is not None:
            group = np.flatnonzero(e.face_ids == e.face_ids[triangle])
        else:
            group = [triangle]
        e.select_facets(group, "remove" if e.selection[triangle] else "add")
        return triangle

    def select_box(self, x0, y0, x1, y1, mode="add", hidden=None):
        """Selects the facets whose centroids lie in the view rectangle [x0, x1] x [y0, y1]
        (pixels, origin lower left) and that face the camera, only the visible ones unless
        ``hidden`` (None: the panel's "also take hidden facets" box). Returns the number
        selected."""
        return self._select_projected(
            lambda cxy: ((cxy[:, 0] >= min(x0, x1)) & (cxy[:, 0] <= max(x0, x1))
                         & (cxy[:, 1] >= min(y0, y1)) & (cxy[:, 1] <= max(y0, y1))),
            mode, hidden, "box")

    def select_polygon(self, points, mode="add", hidden=None):
        """Lasso: selects the facets whose centroids lie inside the view polygon ``points``
        (#P x 2 pixels, origin lower left, closed implicitly; even-odd rule where it crosses
        itself) and that face the camera, only the visible ones unless ``hidden`` (None: the
        panel's box). Returns the number selected."""
        polygon = np.asarray(points, float).reshape(-1, 2)
        if len(polygon) < 3:
            raise ValueError("a lasso needs three or more points, got {}".format(len(polygon)))
        return self._select_projected(
            lambda cxy: points_in_polygon(cxy, polygon), mode, hidden, "lasso")

    def _select_projected(self, inside_of, mode, hidden, what):
        if self.overlay is None:
            raise ValueError("{} selection needs a 3D view".format(what))
        if hidden is None:
            hidden = self.form.ck_hidden.isChecked()
        e = self.editor
        centroids = e.V[e.F].mean(axis=1)
        cxy, cdepth = self.overlay.project(centroids)
        inside = inside_of(cxy) & (np.abs(cdepth) <= 1.0)
        xy, depth = self.overlay.project(e.V)
        facing = view_overlay.front_facing(xy, e.F)
        chosen = np.flatnonzero(inside & facing)
        if not hidden and len(chosen):
            seen = view_overlay.visible_points(xy, depth, e.F, facing, cxy[chosen],
                                               cdepth[chosen])
            chosen = chosen[seen]
        return e.select_facets(chosen, mode)

    def start_box_selection(self, on=True):
        """Box mode: the next drag in the 3D view selects a rectangle (``on`` False cancels)."""
        if self.overlay is not None:
            self.overlay.set_box_mode(on)
        self._set_checked(self.form.pb_box, on)
        if on:
            self._set_checked(self.form.pb_lasso, False)

    def start_lasso_selection(self, on=True):
        """Lasso mode: the next drag in the 3D view draws a polygon and selects the facets
        inside it (``on`` False cancels)."""
        if self.overlay is not None:
            self.overlay.set_lasso_mode(on)
        self._set_checked(self.form.pb_lasso, on)
        if on:
            self._set_checked(self.form.pb_box, False)

    @staticmethod
    def _set_checked(button, on):
        if button.isChecked() != bool(on):
            button.blockSignals(True)
            button.setChecked(bool(on))
            button.blockSignals(False)

    def add_selected_cad_faces(self):
        """Selects the triangles of the faces selected (FreeCAD selection, "FaceN") on the
        Surface's source Part. Returns the number of faces taken."""
        source = getattr(self.obj.Surface, "Source", None)
        if source is None:
            raise ValueError("the Surface has no source Part: its triangles come from a file")
        faces = []
        for sel in FreeCADGui.Selection.getSelectionEx():
            if sel.Object != source:
                continue
            faces += [int(n[4:]) for n in sel.SubElementNames if n.startswith("Face")]
        if not faces:
            raise ValueError("select faces of {} first (click them in the 3D view or the tree)"
                             .format(source.Label))
        for f in faces:
            self.editor.select_face(f, "add")
        return len(faces)

    # --------------------------------------------------------------------------------------------
    # Edits

    def current_patch(self):
        """Patch id chosen in the patch box, or None."""
        data = self.form.cb_patch.currentData()
        return int(data) if data is not None else None

    def assign_to_patch(self, patch_id=None):
        if patch_id is None:
            patch_id = self.current_patch()
        if patch_id is None:
            raise ValueError("choose a patch")
        return self.editor.assign_to_patch(patch_id)

    def new_patch(self, label=None):
        return self.editor.new_patch(label=label)

    def assign_orientation(self, label):
        return self.editor.assign_orientation(label)

    def merge(self, a=None, b=None):
        return self.editor.merge(a, b)

    def split(self, patch_id=None, path=None):
        return self.editor.split(patch_id, path)

    def add_path_vertex(self, vertex):
        return self.editor.add_path_vertex(vertex)

    def clear_path(self):
        self.editor.clear_path()

    def undo(self):
        return self.editor.undo()

    def redo(self):
        return self.editor.redo()

    def reset(self):
        self.editor.reset()

    # --------------------------------------------------------------------------------------------
    # Problems

    def problems(self):
        """The listed problems (core.Violation; str() is the text shown)."""
        return self.editor.problems()

    def highlight_problem(self, index):
        """Shows problem ``index`` of the list: selects its facets, marks its vertex and zooms to
        them. Returns the selected triangles."""
        problems = self.editor.problems()
        if not 0 <= index < len(problems):
            raise ValueError("there is no problem {}".format(index))
        problem = problems[index]
        tris = self.editor.problem_triangles(problem)
        self.editor.select_facets(tris, "replace")
        self.highlighted = index
        self._show_marker(problem)
        if self.overlay is not None and len(tris):
            self._zoom(problem, tris)
        row = self.form.lw_problems
        if row.currentRow() != index:
            row.blockSignals(True)
            row.setCurrentRow(index)
            row.blockSignals(False)
        return tris

    # --------------------------------------------------------------------------------------------
    # Writing the result

    def apply(self):
        """Writes the panel's edits into the Segmentation as one undoable transaction and
        recomputes it. Returns True when something changed."""
        e, obj = self.editor, self.obj
        lt, ll, pt, _ = e.changes()
        if len(lt) == 0 and len(pt) == 0:
            return False
        pt = np.union1d(pt, lt)
        doc = obj.Document
        doc.openTransaction("Edit patches")
        try:
            labels = dict(zip(obj.EditedTriangles, obj.EditedLabels))
            for t, label in zip(lt.tolist(), ll.tolist()):
                labels.pop(t, None)
                labels[t] = label
            patch_edits = dict(zip(obj.EditedPatchTriangles, obj.EditedPatchIds))
            for t in pt.tolist():
                patch_edits[t] = int(e.patches[t])
            obj.EditedTriangles = list(labels.keys())
            obj.EditedLabels = list(labels.values())
            obj.EditedPatchTriangles = list(patch_edits.keys())
            obj.EditedPatchIds = list(patch_edits.values())
            obj.touch()
            doc.recompute()
            if not self._same_patches():
                # The method moved other triangles (the automatic segmentation re-runs with the
                # new labels): keep the panel's patches for every triangle.
                FreeCAD.Console.PrintLog("HexDom: {}: patch edits stored for every triangle\n"
                                         .format(obj.Label))
                obj.EditedPatchTriangles = list(range(e.triangle_count))
                obj.EditedPatchIds = e.patches.tolist()
                obj.touch()
                doc.recompute()
            if "Invalid" in obj.State or "Error" in obj.State:
                raise ValueError("{}: {}".format(obj.Label, obj.getStatusString()))
        except Exception:
            doc.abortTransaction()
            doc.recompute()
            raise
        doc.commitTransaction()
        return True

    def _same_patches(self):
        stored = np.asarray(self.obj.Patches, np.int32)
        if len(stored) != self.editor.triangle_count:
            return False
        e = self.editor
        a = core.number_patches(core.Surface(e.V, e.F, stored))
        b = core.number_patches(e.surface())
        return np.array_equal(np.asarray(a), np.asarray(b))

    # --------------------------------------------------------------------------------------------
    # Widgets

    def _connect(self):
        f = self.form
        f.cb_pick_mode.currentIndexChanged.connect(
            lambda i: self._run("Pick mode", self.set_pick_mode, PICK_MODES[i]))
        f.pb_box.toggled.connect(lambda on: self._run("Box select", self.start_box_selection, on))
        f.pb_lasso.toggled.connect(lambda on: self._run("Lasso select",
                                                        self.start_lasso_selection, on))
        f.pb_cad_faces.clicked.connect(lambda: self._run("CAD faces", self.add_selected_cad_faces))
        f.pb_clear.clicked.connect(lambda: self._run("Clear", self.clear_selection))
        f.pb_assign.clicked.connect(lambda: self._run("Assign to patch", self.assign_to_patch))
        f.pb_new.clicked.connect(lambda: self._run("New patch", self.new_patch))
        for name, label in (("pb_px", 1), ("pb_mx", 2), ("pb_py", 3), ("pb_my", 4), ("pb_pz", 5),
                            ("pb_mz", 6)):
            button = getattr(f, name)
            rgb = coin_mesh.label_color(label)
            button.setStyleSheet("QPushButton {{ background-color: rgb({},{},{}); color: {}; "
                                 "font-weight: bold; }}".format(
                                     *[int(255 * c) for c in rgb],
                                     "black" if sum(rgb) > 1.3 else "white"))
            button.setToolTip("The selected facets take orientation {} and join a neighbouring "
                              "{} patch (or make a new one)".format(LABEL_NAMES[label],
                                                                     LABEL_NAMES[label]))
            button.clicked.connect(lambda checked=False, lab=label: self._run(
                "Orientation", self.assign_orientation, lab))
        f.pb_merge.clicked.connect(lambda: self._run("Merge", self.merge))
        f.pb_split.clicked.connect(lambda: self._run("Split", self.split))
        f.pb_undo.clicked.connect(lambda: self._run("Undo", self.undo))
        f.pb_redo.clicked.connect(lambda: self._run("Redo", self.redo))
        f.pb_reset.clicked.connect(lambda: self._run("Revert", self.reset))
        f.lw_problems.currentRowChanged.connect(
            lambda row: row >= 0 and self._run("Problem", self.highlight_problem, row))

    def _run(self, title, fn, *args):
        try:
            return fn(*args)
        except USER_ERRORS as e:
            self.last_error = str(e)
            show_error(title, e)
            return None

    def _on_click(self, x, y, ctrl, shift):
        self._run("Pick", self.click, x, y, ctrl, shift)

    def _on_box(self, x0, y0, x1, y1):
        self._set_checked(self.form.pb_box, False)
        self._run("Box select", self.select_box, x0, y0, x1, y1)

    def _on_lasso(self, points):
        self._set_checked(self.form.pb_lasso, False)
        self._run("Lasso select", self.select_polygon, points)

    def _on_editor(self, what):
        if what == "patches":
            self.highlighted = None
            self._show_marker(None)
            self._refresh_patches()
            self._refresh_selection()
        elif what in ("selection", "path"):
            self._refresh_selection()

    def _refresh_patches(self):
        e, f = self.editor, self.form
        summary = e.patch_summary()
        keep = self.current_patch()
        f.cb_patch.blockSignals(True)
        f.cb_patch.clear()
        for pid, label, count in summary:
            f.cb_patch.addItem(self._swatch(label, pid), "{} ({}, {} facets)".format(
                pid, LABEL_NAMES.get(label, "?"), count), pid)
        if keep is not None:
            index = f.cb_patch.findData(keep)
            if index >= 0:
                f.cb_patch.setCurrentIndex(index)
        f.cb_patch.blockSignals(False)
        problems = e.problems()
        f.lw_problems.blockSignals(True)
        f.lw_problems.clear()
        for p in problems:
            item = QtGui.QListWidgetItem(str(p))
            item.setForeground(QtGui.QBrush(QtGui.QColor(170, 0, 0)))
            item.setToolTip(str(p))
            f.lw_problems.addItem(item)
        f.lw_problems.blockSignals(False)
        f.lbl_status.setText("{} patches, {} problem{}{}".format(
            len(summary), len(problems), "" if len(problems) == 1 else "s",
            ": the patches make a valid polycube" if not problems else
            " (click one to show it)"))
        f.pb_undo.setEnabled(e.can_undo)
        f.pb_redo.setEnabled(e.can_redo)
        self.undo_redirect.update()
        f.pb_reset.setEnabled(e.is_modified())
        f.pb_cad_faces.setEnabled(getattr(self.obj.Surface, "Source", None) is not None)
        if self.overlay is not None:
            material, colors = coin_mesh.palette_by_patch_label(e.patches, e.labels)
            self._scene.set(e.V, e.F, material, colors,
                            boundary_edges(e.F, e.patches), np.zeros((0, 2)))

    def _refresh_selection(self):
        e, f = self.editor, self.form
        tris = e.selected()
        if len(tris):
            ids = e.selected_patches()
            f.lbl_selection.setText("{} facet{} selected, in patch{} {}".format(
                len(tris), "" if len(tris) == 1 else "s", "" if len(ids) == 1 else "es",
                ", ".join(str(i) for i in ids[:12]) + (" ..." if len(ids) > 12 else "")))
            suggested = f.cb_patch.findData(e.suggested_patch())
            if suggested >= 0:
                f.cb_patch.setCurrentIndex(suggested)
        else:
            f.lbl_selection.setText("No facets selected")
        if e.path:
            f.lbl_selection.setText(f.lbl_selection.text() + "; split path: {} vertices".format(
                len(e.path)))
        has = len(tris) > 0
        for name in ("pb_assign", "pb_new", "pb_px", "pb_mx", "pb_py", "pb_my", "pb_pz",
                     "pb_mz"):
            getattr(f, name).setEnabled(has)
        f.pb_merge.setEnabled(len(e.selected_patches()) >= 2)
        f.pb_split.setEnabled(len(e.path) >= 2)
        if self.overlay is not None:
            view_overlay.set_ints(self._selection_faces.coordIndex,
                                  np.c_[e.F[tris], -np.ones(len(tris), np.int64)])
            path = np.asarray(e.path, np.int64)
            view_overlay.set_points(self._path_coords.point, e.V[path] if len(path) else [])
            view_overlay.set_points(self._path_marker_coords.point,
                                    e.V[path] if len(path) else [])
            view_overlay.set_ints(self._path_lines.coordIndex,
                                  list(range(len(path))) + [-1] if len(path) > 1 else [])

    @staticmethod
    def _swatch(label, pid):
        pix = QtGui.QPixmap(12, 12)
        pix.fill(QtGui.QColor(*[int(255 * c) for c in coin_mesh.shade(
            coin_mesh.label_color(label), 0)]))
        return QtGui.QIcon(pix)

    # --------------------------------------------------------------------------------------------
    # 3D view

    def _build_scene(self):
        from pivy import coin
        self._scene = coin_mesh.ColoredPolygons(("Shaded",))
        root = self.overlay.root
        root.addChild(self._scene.groups["Shaded"])
        self._scene.set_line_width(2.0)
        sel = coin.SoSeparator()
        sel.addChild(self._scene.coords)
        material = coin.SoMaterial()
        material.diffuseColor = SELECTION_COLOR
        material.emissiveColor = (0.35, 0.35, 0.35)
        hints = coin.SoShapeHints()
        hints.vertexOrdering = coin.SoShapeHints.COUNTERCLOCKWISE
        hints.shapeType = coin.SoShapeHints.UNKNOWN_SHAPE_TYPE
        self._selection_faces = coin.SoIndexedFaceSet()
        for node in (hints, material, self._selection_faces):
            sel.addChild(node)
        root.addChild(sel)
        annotation = coin.SoAnnotation()
        path_sep, self._path_coords, self._path_lines, _ = view_overlay.line_node(PATH_COLOR, 3.0)
        annotation.addChild(path_sep)
        sep, self._path_marker_coords, _, _ = view_overlay.marker_node(PATH_COLOR)
        annotation.addChild(sep)
        sep, self._marker_coords, self._marker, _ = view_overlay.marker_node(
            PROBLEM_COLOR, "CIRCLE_FILLED")
        annotation.addChild(sep)
        root.addChild(annotation)

    def _show_marker(self, problem):
        if self.overlay is None:
            return
        if problem is None or problem.vertex < 0:
            view_overlay.set_points(self._marker_coords.point, [])
        else:
            view_overlay.set_points(self._marker_coords.point,
                                    [self.editor.V[problem.vertex]])

    def _zoom(self, problem, tris):
        e = self.editor
        pts = e.V[e.F[tris].reshape(-1)]
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        diag = float(np.linalg.norm(e.V.max(axis=0) - e.V.min(axis=0)))
        if problem.vertex >= 0:
            centre = e.V[problem.vertex]
            r = min(max(0.5 * float(np.linalg.norm(hi - lo)), 0.12 * diag), 0.3 * diag)
            lo, hi = centre - r, centre + r
        self.overlay.zoom_to(lo, hi)

    def _close(self):
        panel_close.close_panel(self, _active, self.obj.Document.Name)
