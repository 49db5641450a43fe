"""Build Polycube: the task panel of a HexDom Polycube (GUI only).

Shows the polycube boundary a HexDom Segmentation asks for (core.polycube_boundary): its corners
as points, the curves between patches as lines and each patch as a quad or triangle over its
corners (strong colour while no block covers it, pale once one does). The user adds interior
vertices (at a clicked point, at the centroid of picked vertices, at typed coordinates) and makes
blocks from picked vertices: 8 give a hex, 6 a prism, 4 a tet, ordered by the tool so that the
block is not inverted. Blocks are listed, deleted and re-picked; the problems that keep the
blocks from filling the boundary are listed live and shown when clicked. Structure files (.k as
the original program's) are imported and exported. Undo and redo work inside the panel, and
while it is open FreeCAD's Edit > Undo / Redo and Ctrl+Z / Ctrl+Shift+Z / Ctrl+Y act on them
rather than on the document (panel_undo.UndoRedirect). OK writes the blocks into the Polycube (or a
new one), Cancel leaves the document as it was.

The work is done by logic.polycube_building.PolycubeBuilder; the public methods below are what the
widgets call, and what tests call to act as clicks would.
"""

import os

import numpy as np

import FreeCAD
import FreeCADGui
from PySide import QtGui

from .. import core, paths
from ..guiutils.dialogs import get_param, set_param, show_error
from ..logic.cells import BLOCK_FACES
from ..logic.labels import labels_from_normals
from ..logic.polycube_building import TYPE_NAMES, PolycubeBuilder
from ..objects import polycube, segmentation
from ..viewproviders import coin_mesh
from . import panel_close, panel_undo, view_overlay

USER_ERRORS = (core.Error, ValueError, OSError)
PICK_MODES = ("vertex", "point")
PICK_RADIUS = 12  # pixels
TYPE_COLORS = {core.HEX: (0.25, 0.52, 0.90), core.WEDGE: (1.00, 0.60, 0.10),
               core.TET: (0.80, 0.20, 0.80)}
CORNER_COLOR = (0.05, 0.05, 0.05)
INTERIOR_COLOR = (0.0, 0.6, 0.2)
PICKED_COLOR = (1.0, 0.45, 0.0)
PROBLEM_COLOR = (1.0, 0.0, 0.0)
BLOCK_SELECTED_COLOR = (1.0, 0.85, 0.0)

_active = []


def active_panel():
    """The open Build Polycube panel, or None (for macros and tests)."""
    return _active[-1] if _active else None


def segmentations(doc):
    return [o for o in doc.Objects if segmentation.is_segmentation(o)]


def find_segmentation(obj):
    """The Segmentation a Polycube goes with: the one a HexDom Mesh meshes it with, else its own
    (an automatic Polycube's, also when the Mesh no longer uses it: Mesh Part kept the overlay
    grid's mesh), else the only one in the document, else None."""
    for user in obj.InList:
        seg = getattr(user, "Segmentation", None)
        if seg is not None and getattr(user, "Polycube", None) == obj:
            return seg
    own = getattr(obj, "Segmentation", None)
    if own is not None and segmentation.is_segmentation(own):
        return own
    found = segmentations(obj.Document)
    return found[0] if len(found) == 1 else None


class _TaskPanel:
    """Build Polycube over HexDom Polycube ``obj``, against the patches of HexDom Segmentation
    ``segmentation`` (None: found from the document). With no ``obj``, OK makes a new Polycube
    with ``new_polycube(doc, structure)`` (the command passes make.make_polycube: the panel
    itself creates no document objects)."""

    def __init__(self, obj=None, segmentation=None, doc=None, new_polycube=None):
        if obj is None and new_polycube is None:
            raise ValueError("Build polycube: no Polycube to edit and no way to make one")
        self.obj = obj
        self.new_polycube = new_polycube
        self.doc = obj.Document if obj is not None else (
            segmentation.Document if segmentation is not None else doc or FreeCAD.ActiveDocument)
        if self.doc is None:
            raise ValueError("no document to build a polycube in")
        if segmentation is None and obj is not None:
            segmentation = find_segmentation(obj)
        self.segmentation = segmentation
        self.pick_mode = "vertex"
        self.highlighted = None
        self.selected_block = None
        self.last_error = ""
        self._closed = False
        structure = polycube.get_structure(obj) if obj is not None and obj.BlockTypes else None
        self.builder = self._make_builder(segmentation, structure)
        self.form = FreeCADGui.PySideUic.loadUi(paths.ui("BuildPolycube.ui"))
        self.form.setWindowIcon(QtGui.QIcon(paths.icon("HexDom_BuildPolycube")))
        self.form.lw_problems.setWordWrap(True)
        self._fill_segmentations()
        self._connect()
        self.overlay = None
        self._hidden = []
        if view_overlay.active_view() is not None:
            self.overlay = view_overlay.ViewOverlay()
            self._build_scene()
            self.overlay.on_click = self._on_click
            self.overlay.install_mouse()
            self._hide_objects()
        self.undo_redirect = panel_undo.UndoRedirect(
            self.undo, self.redo, lambda: self.builder.can_undo, lambda: self.builder.can_redo)
        self._refresh_all()
        _active.append(self)

    def _make_builder(self, seg, structure):
        surface = segmentation.get_surface(seg) if seg is not None else None
        own = polycube.get_patch_surface(self.obj) if self.obj is not None else None
        if own is not None:  # an automatic structure: its blocks go with its own patches
            surface = own
        self.surface = surface
        builder = PolycubeBuilder(surface, structure)
        builder.listeners.append(self._on_builder)
        self.patch_labels = {}
        if seg is not None and builder.boundary is not None:
            numbers = np.asarray(core.number_patches(surface), np.int32)
            labels = np.asarray(seg.Labels, np.int32)
            if own is not None:
                labels = labels_from_normals(surface.V, surface.F, surface.patch,
                                             frame=segmentation.frame_matrix(seg),
                                             stretch=segmentation.stretch_factors(seg))
            _, first = np.unique(numbers, return_index=True)
            for n, t in zip(np.unique(numbers).tolist(), first.tolist()):
                self.patch_labels[n] = int(labels[t]) if len(labels) > t else 0
        return builder

    # --------------------------------------------------------------------------------------------
    # FreeCAD task dialog protocol

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)

    def accept(self):
        """OK: writes the blocks into the Polycube (a new one when the panel has none),
        recomputes and closes."""
        try:
            self.apply()
        except USER_ERRORS as e:
            show_error("Build polycube", e)
            return False
        self._close()
        return True

    def reject(self):
        """Cancel: closes the panel; the document keeps what it had."""
        self._close()
        return True

    # --------------------------------------------------------------------------------------------
    # Segmentation

    def set_segmentation(self, seg):
        """Builds over the patches of ``seg`` (a HexDom Segmentation or None); the blocks stay,
        snapped to the new corners."""
        structure = self.builder.structure() if self.builder.blocks else None
        self.builder = self._make_builder(seg, structure)
        self.segmentation = seg
        self._hide_objects()
        self._refresh_all()

    # --------------------------------------------------------------------------------------------
    # Vertices

    def set_pick_mode(self, mode):
        """What a click does: "vertex" picks (or unpicks) a vertex, "point" adds an interior
        vertex where the click hits a face."""
        if mode not in PICK_MODES:
            raise ValueError("pick mode '{}' is not one of {}".format(mode, PICK_MODES))
        self.pick_mode = mode
        if self.form.cb_pick_mode.currentIndex() != PICK_MODES.index(mode):
            self.form.cb_pick_mode.setCurrentIndex(PICK_MODES.index(mode))

    def select_vertices(self, vertices, mode="add"):
        return self.builder.select_vertices(vertices, mode)

    def clear_selection(self):
        self.builder.clear_selection()

    def vertex_at(self, x, y):
        """Vertex drawn nearest view pixel (x, y) within PICK_RADIUS pixels (the front one when
        several are), or None."""
        if self.overlay is None or self.builder.vertex_count == 0:
            return None
        xy, depth = self.overlay.project(self.builder.points)
        d = np.hypot(xy[:, 0] - x, xy[:, 1] - y)
        near = np.flatnonzero((d <= PICK_RADIUS) & (np.abs(depth) <= 1.0))
        if len(near) == 0:
            return None
        return int(near[np.lexsort((d[near], np.round(depth[near], 4)))[0]])

    def point_at(self, x, y):
        """Point where the line of sight through (x, y) first meets a patch or block face, or
        None."""
        if self.overlay is None:
            return None
        V, F = self._pick_triangles()
        origin, direction = self.overlay.ray(x, y)
        _, point = view_overlay.pick_triangle(origin, direction, V, F)
        return point

    def click(self, x, y, ctrl=False, shift=False):
        """A left click at view pixel (x, y): toggles the vertex there, or (point mode) adds an
        interior vertex where the click meets a face. Returns the vertex or None."""
        if self.pick_mode == "point":
            point = self.point_at(x, y)
            if point is None:
                return None
            self._set_coordinates(point)
            return self.builder.add_vertex(point)
        v = self.vertex_at(x, y)
        if v is not None:
            self.builder.select_vertices([v], "toggle")
        return v

    def add_vertex(self, point=None):
        """Adds an interior vertex at ``point`` (default: the typed coordinates)."""
        if point is None:
            point = self.coordinates()
        return self.builder.add_vertex(point)

    def add_vertex_at_centroid(self, vertices=None):
        return self.builder.add_vertex_at_centroid(vertices)

    def move_vertex(self, vertex=None, point=None):
        """Moves the one picked interior vertex (or ``vertex``) to the typed coordinates (or
        ``point``)."""
        vertex = self._one_picked() if vertex is None else vertex
        self.builder.move_vertex(vertex, self.coordinates() if point is None else point)

    def delete_vertex(self, vertex=None):
        self.builder.delete_vertex(self._one_picked() if vertex is None else vertex)

    def coordinates(self):
        f = self.form
        return np.array([f.sb_x.value(), f.sb_y.value(), f.sb_z.value()], float)

    def set_coordinates(self, point):
        self._set_coordinates(point)

    def _one_picked(self):
        if len(self.builder.selection) != 1:
            raise ValueError("pick exactly one vertex")
        return self.builder.selection[0]

    # --------------------------------------------------------------------------------------------
    # Blocks

    def add_block(self, vertices=None):
        block = self.builder.add_block(vertices)
        self.select_block(block)
        return block

    def delete_block(self, block=None):
        block = self._current_block() if block is None else block
        self.selected_block = None
        self.builder.delete_block(block)

    def edit_block(self, block=None, vertices=None):
        block = self._current_block() if block is None else block
        return self.builder.edit_block(block, vertices)

    def select_block(self, block):
        """Shows block ``block`` (0-based) in the list and the view."""
        self.selected_block = None if block is None or block < 0 else int(block)
        lw = self.form.lw_blocks
        if self.selected_block is not None and lw.currentRow() != self.selected_block:
            lw.blockSignals(True)
            lw.setCurrentRow(self.selected_block)
            lw.blockSignals(False)
        self._refresh_highlight()

    def _current_block(self):
        if self.selected_block is None:
            raise ValueError("choose a block in the list")
        return self.selected_block

    def counts(self):
        return self.builder.counts()

    # --------------------------------------------------------------------------------------------
    # Files, undo

    def import_structure(self, path):
        """Reads a structure file (.k, .vtk, .vtu) into the panel (undoable)."""
        n = self.builder.import_structure(path)
        FreeCAD.Console.PrintLog("HexDom: {}: {} blocks, {} interior vertices\n".format(
            path, len(self.builder.blocks), n))
        return n

    def export_structure(self, path):
        self.builder.export_structure(path)

    def undo(self):
        return self.builder.undo()

    def redo(self):
        return self.builder.redo()

    # --------------------------------------------------------------------------------------------
    # Problems

    def problems(self):
        """The listed problems (polycube_building.Problem; str() is the text shown)."""
        return self.builder.problems()

    def highlight_problem(self, index):
        """Shows problem ``index``: its faces, blocks and vertices in red, the view zoomed to
        them. Returns the problem."""
        problems = self.builder.problems()
        if not 0 <= index < len(problems):
            raise ValueError("there is no problem {}".format(index))
        self.highlighted = index
        problem = problems[index]
        self._refresh_highlight()
        vertices = set(problem.vertices)
        for b in problem.blocks:
            vertices.update(self.builder.blocks[b][1])
        if self.overlay is not None and vertices:
            pts = self.builder.points[sorted(vertices)]
            lo, hi = pts.min(axis=0), pts.max(axis=0)
            pad = 0.05 * self.builder.scale
            self.overlay.zoom_to(lo - pad, hi + pad)
        lw = self.form.lw_problems
        if lw.currentRow() != index:
            lw.blockSignals(True)
            lw.setCurrentRow(index)
            lw.blockSignals(False)
        return problem

    # --------------------------------------------------------------------------------------------
    # Writing the result

    def apply(self):
        """Writes the blocks into the Polycube (or a new one) as one undoable transaction and
        recomputes. Returns the Polycube."""
        structure = self.builder.structure()
        problems = self.builder.problems()
        doc = self.doc
        doc.openTransaction("Build polycube")
        try:
            if self.obj is None:
                self.obj = self.new_polycube(doc, structure)
                if self.segmentation is not None:
                    self.obj.Label = self.segmentation.Label + "_polycube"
            else:
                polycube.store_structure(self.obj, structure)
                if getattr(self.obj, "Mode", "Manual") == "Automatic":
                    self.obj.Mode = "Manual"  # hand-edited now: keep it, do not rebuild it
                if self.obj.SourceFile:
                    self.obj.SourceFile = ""
                    self.obj.LoadedFile = ""
                self.obj.touch()
            doc.recompute()
            if "Invalid" in self.obj.State or "Error" in self.obj.State:
                raise ValueError("{}: {}".format(self.obj.Label, self.obj.getStatusString()))
        except Exception:
            doc.abortTransaction()
            doc.recompute()
            raise
        doc.commitTransaction()
        if problems:
            FreeCAD.Console.PrintWarning("HexDom: {} kept with {} problem{}: {}\n".format(
                self.obj.Label, len(problems), "" if len(problems) == 1 else "s", problems[0]))
        return self.obj

    # --------------------------------------------------------------------------------------------
    # Widgets

    def _fill_segmentations(self):
        cb = self.form.cb_segmentation
        cb.blockSignals(True)
        cb.clear()
        cb.addItem("(none: no boundary to fill)", "")
        for seg in segmentations(self.doc):
            cb.addItem(seg.Label, seg.Name)
        if self.segmentation is not None:
            cb.setCurrentIndex(max(0, cb.findData(self.segmentation.Name)))
        cb.blockSignals(False)

    def _connect(self):
        f = self.form
        f.cb_segmentation.currentIndexChanged.connect(lambda i: self._run(
            "Segmentation", self.set_segmentation,
            self.doc.getObject(f.cb_segmentation.itemData(i)) if f.cb_segmentation.itemData(i)
            else None))
        f.cb_pick_mode.currentIndexChanged.connect(
            lambda i: self._run("Pick mode", self.set_pick_mode, PICK_MODES[i]))
        f.pb_clear.clicked.connect(lambda: self._run("Clear", self.clear_selection))
        f.pb_add_xyz.clicked.connect(lambda: self._run("Add vertex", self.add_vertex))
        f.pb_add_centroid.clicked.connect(lambda: self._run("Add vertex",
                                                            self.add_vertex_at_centroid))
        f.pb_move.clicked.connect(lambda: self._run("Move vertex", self.move_vertex))
        f.pb_delete_vertex.clicked.connect(lambda: self._run("Delete vertex", self.delete_vertex))
        f.pb_add_block.clicked.connect(lambda: self._run("Add block", self.add_block))
        f.pb_edit_block.clicked.connect(lambda: self._run("Replace block", self.edit_block))
        f.pb_delete_block.clicked.connect(lambda: self._run("Delete block", self.delete_block))
        f.lw_blocks.currentRowChanged.connect(lambda row: self._run("Block", self._block_clicked,
                                                                    row))
        f.lw_problems.currentRowChanged.connect(
            lambda row: row >= 0 and self._run("Problem", self.highlight_problem, row))
        f.pb_import.clicked.connect(lambda: self._run("Import structure", self._import_dialog))
        f.pb_export.clicked.connect(lambda: self._run("Export structure", self._export_dialog))
        f.pb_undo.clicked.connect(lambda: self._run("Undo", self.undo))
        f.pb_redo.clicked.connect(lambda: self._run("Redo", self.redo))

    def _run(self, title, fn, *args):
        try:
            return fn(*args)
        except USER_ERRORS as e:
            self.last_error = str(e)
            show_error(title, e)
            return None

    def _block_clicked(self, row):
        self.select_block(row)
        if row >= 0:
            self.builder.select_vertices(list(self.builder.blocks[row][1]), "replace")

    def _import_dialog(self):
        path, _ = QtGui.QFileDialog.getOpenFileName(
            FreeCADGui.getMainWindow(), "Import polycube structure", get_param("LastDir"),
            "Structure files (*.k *.vtk *.vtu);;All files (*)")
        if path:
            set_param("LastDir", os.path.dirname(path))
            self.import_structure(path)

    def _export_dialog(self):
        path, _ = QtGui.QFileDialog.getSaveFileName(
            FreeCADGui.getMainWindow(), "Export polycube structure",
            os.path.join(get_param("LastDir"), "structure.k"),
            "LS-DYNA keyword (*.k);;VTK legacy (*.vtk);;VTK XML (*.vtu)")
        if path:
            if os.path.splitext(path)[1].lower() not in (".k", ".vtk", ".vtu"):
                path += ".k"
            set_param("LastDir", os.path.dirname(path))
            self.export_structure(path)

    def _on_click(self, x, y, ctrl, shift):
        self._run("Pick", self.click, x, y, ctrl, shift)

    def _on_builder(self, what):
        if what == "selection":
            self._refresh_selection()
        else:
            self.highlighted = None
            if self.selected_block is not None and self.selected_block >= len(
                    self.builder.blocks):
                self.selected_block = None
            self._refresh_all()

    def _set_coordinates(self, point):
        f = self.form
        for box, value in zip((f.sb_x, f.sb_y, f.sb_z), np.asarray(point, float).tolist()):
            box.setValue(value)

    def _refresh_all(self):
        b, f = self.builder, self.form
        if b.boundary is not None:
            f.lbl_boundary.setText("{} corners, {} curves, {} patches ({} quads, {} triangles)"
                                   .format(b.corner_count, len(b.boundary.edges),
                                           len(b.boundary.faces),
                                           sum(len(x["corners"]) == 4 for x in b.boundary.faces),
                                           sum(len(x["corners"]) == 3 for x in b.boundary.faces)))
        else:
            f.lbl_boundary.setText(b.boundary_error or "Choose the segmentation whose patches "
                                   "the blocks fill")
        f.lw_blocks.blockSignals(True)
        f.lw_blocks.clear()
        for i, (t, verts) in enumerate(b.blocks):
            item = QtGui.QListWidgetItem("{}: {}  {}".format(i + 1, TYPE_NAMES[t], " ".join(
                str(v) for v in verts)))
            item.setForeground(QtGui.QBrush(QtGui.QColor(*[int(200 * c) for c in TYPE_COLORS[t]])))
            f.lw_blocks.addItem(item)
        if self.selected_block is not None:
            f.lw_blocks.setCurrentRow(self.selected_block)
        f.lw_blocks.blockSignals(False)
        counts = b.counts()
        f.lbl_counts.setText("{} hex, {} prism, {} tet; {} vertices ({} interior)".format(
            counts["hex"], counts["prism"], counts["tet"], b.vertex_count,
            b.vertex_count - b.corner_count))
        problems = b.problems()
        f.lw_problems.blockSignals(True)
        f.lw_problems.clear()
        for p in problems:
            item = QtGui.QListWidgetItem(str(p))
            item.setForeground(QtGui.QBrush(QtGui.QColor(170, 0, 0)))
            f.lw_problems.addItem(item)
        f.lw_problems.blockSignals(False)
        if problems:
            f.lbl_status.setText("{} problem{} (click one to show it)".format(
                len(problems), "" if len(problems) == 1 else "s"))
        else:
            f.lbl_status.setText("No problems: the blocks fill the boundary exactly")
        f.pb_undo.setEnabled(b.can_undo)
        f.pb_redo.setEnabled(b.can_redo)
        self.undo_redirect.update()
        f.pb_export.setEnabled(bool(b.blocks))
        self._refresh_scene()
        self._refresh_selection()

    def _refresh_selection(self):
        b, f = self.builder, self.form
        sel = b.selection
        if sel:
            kinds = {8: "a hex", 6: "a prism", 4: "a tet"}
            f.lbl_selection.setText("Picked {}: {}{}".format(
                len(sel), " ".join(str(v) for v in sel),
                " (makes {})".format(kinds[len(sel)]) if len(sel) in kinds else ""))
            if len(sel) == 1:
                self._set_coordinates(b.points[sel[0]])
        else:
            f.lbl_selection.setText("No vertices picked")
        f.pb_add_block.setEnabled(len(sel) in (4, 6, 8))
        f.pb_edit_block.setEnabled(len(sel) in (4, 6, 8) and self.selected_block is not None)
        f.pb_delete_block.setEnabled(self.selected_block is not None)
        f.pb_add_centroid.setEnabled(bool(sel))
        one_interior = len(sel) == 1 and not b.is_corner(sel[0])
        f.pb_move.setEnabled(one_interior)
        f.pb_delete_vertex.setEnabled(one_interior)
        if self.overlay is None:
            return
        pts = b.points[sel] if sel else np.zeros((0, 3))
        view_overlay.set_points(self._picked_coords.point, pts)
        self._labels.removeAllChildren()
        from pivy import coin
        for k, v in enumerate(sel):
            sep = coin.SoSeparator()
            tr = coin.SoTranslation()
            tr.translation = tuple(float(c) for c in b.points[v])
            text = coin.SoText2()
            text.string = "  {} ({})".format(k + 1, v)
            sep.addChild(tr)
            sep.addChild(text)
            self._labels.addChild(sep)

    # --------------------------------------------------------------------------------------------
    # 3D view

    def _hide_objects(self):
        for vobj in self._hidden:
            try:
                vobj.Visibility = True
            except (RuntimeError, ReferenceError):
                pass
        self._hidden = []
        if self.overlay is None:
            return
        hide = [self.obj, self.segmentation]
        if self.segmentation is not None:
            hide += [self.segmentation.Surface] + list(self.segmentation.InListRecursive)
        if self.obj is not None:
            hide += list(self.obj.InListRecursive)
        for o in hide:
            vobj = getattr(o, "ViewObject", None) if o is not None else None
            if vobj is not None and vobj.Visibility:
                self._hidden.append(vobj)
                vobj.Visibility = False

    def _build_scene(self):
        from pivy import coin
        root = self.overlay.root
        self._patches = coin_mesh.ColoredPolygons(("Transparent",))
        root.addChild(self._patches.groups["Transparent"])
        sep, self._curve_coords, self._curves, _ = view_overlay.line_node((0.3, 0.3, 0.3), 1.0)
        root.addChild(sep)
        self._blocks = coin_mesh.ColoredPolygons(("Transparent",))
        root.addChild(self._blocks.groups["Transparent"])
        self._blocks.set_line_width(3.0)
        sep, self._hl_face_coords, self._hl_faces, _ = view_overlay.face_node(PROBLEM_COLOR, 0.3)
        root.addChild(sep)
        annotation = coin.SoAnnotation()
        sep, self._hl_line_coords, self._hl_lines, self._hl_line_color = view_overlay.line_node(
            PROBLEM_COLOR, 4.0)
        annotation.addChild(sep)
        sep, self._corner_coords, _, _ = view_overlay.marker_node(CORNER_COLOR, "CIRCLE_FILLED", 7)
        annotation.addChild(sep)
        sep, self._interior_coords, _, _ = view_overlay.marker_node(INTERIOR_COLOR,
                                                                    "CIRCLE_FILLED", 9)
        annotation.addChild(sep)
        sep, self._hl_vertex_coords, _, _ = view_overlay.marker_node(PROBLEM_COLOR,
                                                                     "CIRCLE_FILLED", 11)
        annotation.addChild(sep)
        sep, self._picked_coords, _, _ = view_overlay.marker_node(PICKED_COLOR,
                                                                  "CIRCLE_FILLED", 11)
        annotation.addChild(sep)
        label_sep = coin.SoSeparator()
        color = coin.SoBaseColor()
        color.rgb = (0.0, 0.0, 0.0)
        font = coin.SoFont()
        font.size = 14.0
        self._labels = coin.SoSeparator()
        for node in (color, font, self._labels):
            label_sep.addChild(node)
        annotation.addChild(label_sep)
        root.addChild(annotation)

    def _pick_triangles(self):
        """Triangles of the patch faces and block faces (for point picking)."""
        b = self.builder
        polys = []
        if b.boundary is not None:
            polys += [list(f["corners"]) for f in b.boundary.faces]
        for t, verts in b.blocks:
            polys += [[verts[i] for i in face] for face in BLOCK_FACES[t]]
        tris = []
        for p in polys:
            tris += [(p[0], p[k], p[k + 1]) for k in range(1, len(p) - 1)]
        return b.points, np.array(tris, np.int64).reshape(-1, 3)

    def _refresh_scene(self):
        if self.overlay is None:
            return
        b = self.builder
        P = b.points
        # Patch faces over the corners: strong while uncovered, pale once a block face covers it.
        block_keys = set()
        for t, verts in b.blocks:
            block_keys.update(tuple(sorted(verts[i] for i in face)) for face in BLOCK_FACES[t])
        if b.boundary is not None:
            faces = [list(f["corners"]) for f in b.boundary.faces]
            colors, material = [], []
            for f in b.boundary.faces:
                rgb = coin_mesh.label_color(self.patch_labels.get(f["patch"], 0))
                done = tuple(sorted(f["corners"])) in block_keys
                if done:
                    rgb = tuple(0.55 + 0.45 * c for c in rgb)
                material.append(len(colors))
                colors.append(rgb)
            edges = np.zeros((0, 2))
            self._patches.set(P, faces, material, colors, edges, edges, transparency=0.35)
            surface = self.surface
            lines, pts = [], []
            for e in b.boundary.edges:
                path = list(e["path"])
                start = len(pts)
                pts += [tuple(surface.V[v]) for v in path]
                lines += list(range(start, start + len(path))) + [-1]
            view_overlay.set_points(self._curve_coords.point, pts)
            view_overlay.set_ints(self._curves.coordIndex, lines)
        else:
            self._patches.clear()
            view_overlay.set_points(self._curve_coords.point, [])
            view_overlay.set_ints(self._curves.coordIndex, [])
        # Blocks: faces by type, outer faces only drawn once, all edges.
        faces, material, edges, kinds = [], [], set(), sorted({t for t, _ in b.blocks})
        for t, verts in b.blocks:
            for face in BLOCK_FACES[t]:
                ids = [verts[i] for i in face]
                faces.append(ids)
                material.append(kinds.index(t))
                for u, v in zip(ids, ids[1:] + ids[:1]):
                    edges.add((min(u, v), max(u, v)))
        edges = np.array(sorted(edges), np.int64).reshape(-1, 2)
        if faces:
            self._blocks.set(P, faces, material, [TYPE_COLORS[t] for t in kinds], edges,
                             np.zeros((0, 2)), transparency=0.55)
            self._blocks.feature_color.rgb.setValue(0.05, 0.2, 0.55)
        else:
            self._blocks.clear()
        view_overlay.set_points(self._corner_coords.point, P[:b.corner_count])
        view_overlay.set_points(self._interior_coords.point, P[b.corner_count:])
        self._refresh_highlight()

    def _refresh_highlight(self):
        if self.overlay is None:
            return
        b = self.builder
        faces, lines, vertices = [], set(), []
        color = PROBLEM_COLOR
        if self.highlighted is not None and self.highlighted < len(b.problems()):
            p = b.problems()[self.highlighted]
            faces = [list(f) for f in p.faces]
            vertices = list(p.vertices)
            blocks = p.blocks
        elif self.selected_block is not None and self.selected_block < len(b.blocks):
            blocks, color = [self.selected_block], BLOCK_SELECTED_COLOR
        else:
            blocks = []
        for i in blocks:
            t, verts = b.blocks[i]
            for face in BLOCK_FACES[t]:
                ids = [verts[k] for k in face]
                for u, v in zip(ids, ids[1:] + ids[:1]):
                    lines.add((min(u, v), max(u, v)))
        for f in faces:
            for u, v in zip(f, f[1:] + f[:1]):
                lines.add((min(u, v), max(u, v)))
        self._hl_line_color.rgb = color
        view_overlay.set_points(self._hl_face_coords.point, b.points)
        view_overlay.set_ints(self._hl_faces.coordIndex, view_overlay.polygon_index(faces))
        view_overlay.set_points(self._hl_line_coords.point, b.points)
        view_overlay.set_ints(self._hl_lines.coordIndex,
                              view_overlay.edge_index(sorted(lines)))
        view_overlay.set_points(self._hl_vertex_coords.point,
                                b.points[vertices] if vertices else np.zeros((0, 3)))

    def _close(self):
        panel_close.close_panel(self, _active, self.doc.Name)
