"""GUI test of the Edit Patches task panel, run by tests/freecad/run.sh as
`freecad gui_test_edit_patches.py` under xvfb.

On the bundled L-bracket's patches: HexDom_EditPatches opens the panel; facets picked by clicks at
their screen positions become a new patch inside patch 5 (a planted violation); the problem list
shows it, clicking a problem selects and zooms to it; assigning the facets back to patch 5 through
the widgets empties the list; undo/redo, the orientation buttons, a split along a clicked path
and a merge, box selection; a lasso (free polygon) around a planted patch picks exactly the
facets whose centroids FreeCAD's own projection puts inside it, and assigning them fixes the
violation; Ctrl+Z / Ctrl+Shift+Z / Ctrl+Y and Edit > Undo act on the panel, not on the
document, until the panel closes; Cancel leaves the Segmentation as it was, OK writes the edits (and
the document's undo takes them back). On a Part L-shape: whole CAD faces from FreeCAD's selection
and from clicks. Screenshots of the panel with the 3D view go to artifacts/. Prints
"GUI TEST PASSED" and exits 0, or lists the failures and exits 1; a watchdog exits 2 on a hang.
"""

import os
import sys
import traceback

TEST_DIR = os.environ.get("HEXDOM_FC_TEST_DIR") or os.path.dirname(
    os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, TEST_DIR)

import fc_testdata  # noqa: E402
import gui_shots as g  # noqa: E402

g.start_watchdog(170.0)
check = g.check


def screen_of(panel, points):
    xy, _ = panel.overlay.project(points)
    return xy


def freecad_screen(view, points):
    """Pixel positions (origin lower left) of ``points`` by FreeCAD's own projection
    (View3DInventor.getPointOnScreen), independent of the panel's."""
    import numpy as np
    import FreeCAD
    return np.array([tuple(view.getPointOnScreen(FreeCAD.Vector(*map(float, p))))
                     for p in points], float)


def toolbar_undo_names():
    """Object names of the undo / redo actions on the main window's toolbars ("" for FreeCAD's
    own, which have no name there)."""
    import FreeCADGui
    from PySide import QtGui
    names = []
    for bar in FreeCADGui.getMainWindow().findChildren(QtGui.QToolBar):
        for action in bar.actions():
            if action.text().replace("&", "") in ("Undo", "Redo"):
                names.append(action.objectName())
    return names


def inside_polygon(points, polygon):
    """Winding-angle test: the total angle the polygon turns about each point (2 pi inside)."""
    import numpy as np
    d = polygon[None, :, :] - points[:, None, :]
    e = np.roll(d, -1, axis=1)
    angle = np.arctan2(d[..., 0] * e[..., 1] - d[..., 1] * e[..., 0],
                       (d * e).sum(axis=2)).sum(axis=1)
    return np.abs(angle) > np.pi


def distance_to_polygon(points, polygon):
    import numpy as np
    a, b = polygon, np.roll(polygon, -1, axis=0)
    ab = b - a
    t = np.clip(np.einsum("pqk,qk->pq", points[:, None, :] - a[None], ab)
                / np.einsum("qk,qk->q", ab, ab), 0, 1)
    nearest = a[None] + t[..., None] * ab[None]
    return np.linalg.norm(points[:, None, :] - nearest, axis=2).min(axis=1)


def run():
    import numpy as np

    import FreeCAD
    import FreeCADGui
    import Part
    from PySide import QtGui

    from HexDomWorkbench import api, make, paths
    from HexDomWorkbench.taskpanels import task_segmentation

    errors = []
    QtGui.QMessageBox.critical = staticmethod(lambda parent, title, text, *a: errors.append(
        (title, text)))
    FreeCADGui.activateWorkbench("HexDomWorkbench")
    g.set_task_width()
    for name in ("HexDom_EditPatches", "HexDom_BuildPolycube"):
        check(name in FreeCADGui.listCommands() and os.path.isfile(paths.icon(name)),
              "{} registered with its icon".format(name))

    # 1. Open the panel on the bracket's patches through the command.
    doc = FreeCAD.newDocument("EditPatches")
    seg = api.import_patches(os.path.abspath(fc_testdata.example_path("lbracket_patches.k")), doc)
    view = FreeCADGui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    FreeCADGui.Selection.clearSelection()
    check(not FreeCADGui.isCommandActive("HexDom_EditPatches"), "Edit patches needs a selection")
    FreeCADGui.Selection.addSelection(seg)
    check(FreeCADGui.isCommandActive("HexDom_EditPatches"), "Edit patches active on a Segmentation")
    doc.openTransaction("Describe")  # a document edit that Ctrl+Z must not undo under the panel
    seg.Label2 = "bracket patches"
    doc.commitTransaction()
    doc_undos = list(doc.UndoNames)
    FreeCADGui.runCommand("HexDom_EditPatches")
    g.process_events()
    panel = task_segmentation.active_panel()
    if not check(panel is not None and FreeCADGui.Control.activeDialog(),
                 "HexDom_EditPatches opens the task panel"):
        return
    f = panel.form
    check(not seg.ViewObject.Visibility, "the Segmentation is hidden while its panel draws it")
    check(not FreeCADGui.isCommandActive("HexDom_EditPatches"), "no second panel while one is open")
    check(panel.problems() == [] and f.lw_problems.count() == 0
          and "valid polycube" in f.lbl_status.text(), "the bracket's patches start valid: {}"
          .format(f.lbl_status.text()))
    check(f.cb_patch.count() == 17, "17 patches offered in the patch box")
    # Each patch drawn in one colour of its own, a shade of its label's (same hue).
    import colorsys
    from HexDomWorkbench.viewproviders import coin_mesh
    field = panel._scene.faces.materialIndex
    material = np.array([int(field[i]) for i in range(field.getNum())])
    diffuse = panel._scene.material.diffuseColor
    colours = [tuple(diffuse[i].getValue()) for i in range(diffuse.getNum())]
    e0 = panel.editor
    per_patch = {pid: {colours[m] for m in material[e0.patches == pid].tolist()}
                 for pid in e0.patch_ids()}
    hue = lambda rgb: colorsys.rgb_to_hsv(*rgb)[0]  # noqa: E731
    same_hue = all(abs(hue(next(iter(c))) - hue(coin_mesh.label_color(e0.patch_label(pid))))
                   < 0.01 for pid, c in per_patch.items())
    check(len(material) == len(e0.F) and all(len(c) == 1 for c in per_patch.values())
          and len({next(iter(c)) for c in per_patch.values()}) == 17 and same_hue,
          "17 patches in 17 colours, each a shade of its label's colour")

    # 2. Plant a violation: click facets in the middle of patch 5 (+X, facing the camera).
    e = panel.editor
    planted = fc_testdata.island(e).tolist()
    f.cb_pick_mode.setCurrentIndex(0)
    picked = []
    for t in planted:
        xy = screen_of(panel, e.V[e.F[t]].mean(axis=0)[None, :])[0]
        picked.append(panel.click(float(xy[0]), float(xy[1])))
    check(picked == planted and sorted(e.selected().tolist()) == sorted(planted),
          "clicks at their screen positions pick the {} planted facets".format(len(planted)))
    check(f.pb_new.isEnabled() and "{} facets selected".format(len(planted))
          in f.lbl_selection.text(), "the panel shows the selection: " + f.lbl_selection.text())
    f.pb_new.click()
    g.process_events()
    kinds = [p.kind for p in panel.problems()]
    check(sorted(kinds) == ["curve_count", "not_disk", "two_patch_corner"]
          and f.lw_problems.count() == 3, "the planted patch is listed: {}".format(kinds))
    check(f.cb_patch.count() == 18 and e.selected().size == 0, "a new patch 18, selection used")
    row = kinds.index("curve_count")
    f.lw_problems.setCurrentRow(row)  # what a click on the list does
    g.process_events()
    check(sorted(e.selected().tolist()) == sorted(planted),
          "clicking the problem selects the planted facets")
    g.compose("edit_patches_problem.png", f)
    shown = g.view_image("_problem_shown.png", 400, 300)
    panel.clear_selection()
    panel._show_marker(None)
    hidden = g.view_image("_problem_hidden.png", 400, 300)
    white = g.changed_to(shown, hidden, (230, 230, 230), 25)
    marker = g.changed_to(shown, hidden, (255, 0, 0), 40)
    check(white > 0.005, "the selected facets are drawn white in the zoomed view ({:.3f})".format(
        white))
    check(marker > 0.0002, "the problem vertex is marked red ({:.4f})".format(marker))
    panel.highlight_problem(row)
    for tmp in (shown, hidden):
        os.remove(tmp)

    # 3. Fix it through the widgets: the patch box proposes the surrounding patch 5; assign.
    check(panel.current_patch() == 5, "the patch box proposes patch 5 around the selection")
    f.cb_patch.setCurrentIndex(f.cb_patch.findData(5))
    f.pb_assign.click()
    g.process_events()
    check(panel.problems() == [] and f.lw_problems.count() == 0 and not e.is_modified(),
          "assigning the facets back to patch 5 empties the problem list")
    f.pb_undo.click()
    check(len(panel.problems()) == 3, "undo brings the violation back")
    f.pb_redo.click()
    check(panel.problems() == [] and not f.pb_redo.isEnabled(), "redo fixes it again")
    f.pb_undo.click()
    panel.highlight_problem(row)
    getattr(f, "pb_px").click()  # patch 5 is +X: the facets join it again
    check(panel.problems() == [] and not e.is_modified(),
          "the +X button sends the facets back to their +X neighbour")
    view.viewIsometric()
    view.fitAll()
    g.compose("edit_patches_valid.png", f)

    # 4. Split along a clicked path across patch 5, then merge the halves again.
    corners = [v for v in np.unique(e.F[e.patches == 5]).tolist()
               if len(set(e.patches[e.vertex_triangles(v)].tolist())) >= 3]
    pc = e.V[corners]
    a_end, b_end = 0, int(np.argmax(np.linalg.norm(pc - pc[0], axis=1)))
    others = [k for k in range(len(corners)) if k not in (a_end, b_end)]
    # Midpoints of two opposite sides: corner 0 with one neighbour corner, the far corner with
    # the other.
    sides = [(pc[a_end] + pc[others[0]]) / 2, (pc[b_end] + pc[others[1]]) / 2]
    boundary = [v for v in np.unique(e.F[e.patches == 5]).tolist()
                if len(set(e.patches[e.vertex_triangles(v)].tolist())) == 2]
    ends = [boundary[int(np.argmin(np.linalg.norm(e.V[boundary] - s, axis=1)))] for s in sides]
    f.cb_pick_mode.setCurrentIndex(3)
    for v in ends:
        tri = int(e.vertex_triangles(v)[0])
        xy = screen_of(panel, (0.9 * e.V[v] + 0.1 * e.V[e.F[tri]].mean(axis=0))[None, :])[0]
        panel.click(float(xy[0]), float(xy[1]))
    check(e.path == ends and f.pb_split.isEnabled(), "two clicks give the split path {}".format(
        e.path))
    f.pb_split.click()
    g.process_events()
    check(len(e.patch_ids()) == 18 and [p.kind for p in panel.problems()]
          == ["curve_count", "curve_count"],
          "the split makes patch 18 and gives both neighbours a fifth curve")
    panel.select_facets(np.flatnonzero(e.patches == 5)[:1], "replace")
    panel.select_facets(np.flatnonzero(e.patches == 18)[:1], "add")
    check(f.pb_merge.isEnabled(), "merge enabled with facets of two patches")
    f.pb_merge.click()
    check(len(e.patch_ids()) == 17 and panel.problems() == [], "merging the halves restores it")

    # 5. Box selection: the visible facets facing the camera inside the rectangle; and the
    # mouse itself (Qt events through Quarter and Coin to the panel's callbacks).
    f.cb_pick_mode.setCurrentIndex(0)
    w, h = panel.overlay.size()
    n = panel.select_box(0, 0, w, h, "replace")
    facing = e.normals[e.selected()] @ np.array(tuple(view.getViewDirection()))
    n_all = panel.select_box(0, 0, w, h, "replace", hidden=True)
    check(n > 300 and np.all(facing < 0) and n < n_all,
          "box select over the view takes {} visible front facets ({} with hidden ones)".format(
              n, n_all))
    n_half = panel.select_box(0, 0, w / 2, h, "replace")
    check(0 < n_half < n, "a half-view box takes fewer ({})".format(n_half))
    panel.clear_selection()
    f.pb_box.click()
    check(panel.overlay.box_mode, "'Box select' waits for a drag")
    g.mouse_drag((0.2 * w, 0.2 * h), (0.8 * w, 0.8 * h))
    dragged = set(e.selected().tolist())
    check(not panel.overlay.box_mode and not f.pb_box.isChecked(), "box mode ends with the drag")
    panel.select_box(0.2 * w, 0.2 * h, 0.8 * w, 0.8 * h, "replace")
    expected = set(e.selected().tolist())
    common = len(dragged & expected) / max(len(dragged | expected), 1)
    check(len(dragged) > 100 and common > 0.95,
          "a mouse drag selects the box: {} facets, {:.0%} as the method's {}".format(
              len(dragged), common, len(expected)))
    panel.clear_selection()
    target = planted[0]
    xy = screen_of(panel, e.V[e.F[target]].mean(axis=0)[None, :])[0]
    g.mouse_click(float(xy[0]), float(xy[1]))
    check(e.selected().tolist() == [target], "a mouse click in the view picks facet {}: {}"
          .format(target, e.selected().tolist()))
    g.mouse_click(float(xy[0]), float(xy[1]))
    check(len(e.selected()) == 0, "a second click on it unpicks it")

    # 6. Lasso: a star drawn around the planted patch; the expectation from FreeCAD's projection.
    panel.select_facets(planted, "replace")
    panel.new_patch()
    check(len(panel.problems()) == 3, "the planted patch is back (3 problems)")
    centroids = e.V[e.F].mean(axis=1)
    fc_xy = freecad_screen(view, centroids)
    own_xy = screen_of(panel, centroids)
    shift = np.abs(fc_xy - own_xy).max()
    check(shift <= 1.0, "the panel projects as FreeCAD does (within {:.2f} px)".format(shift))
    centre = fc_xy[planted].mean(axis=0)
    reach = np.linalg.norm(fc_xy[planted] - centre, axis=1).max() + 3.0
    angles = np.linspace(0, 2 * np.pi, 16, endpoint=False)
    radius = np.where(np.arange(16) % 2 == 0, 2.2, 1.45) * reach
    star = centre + np.c_[np.cos(angles), np.sin(angles)] * radius[:, None]
    towards = np.array(tuple(view.getViewDirection()))
    facing = e.normals @ towards < 0
    inside = inside_polygon(fc_xy, star) & facing
    # Centroids within a pixel of the star's edge may fall either way (FreeCAD rounds to whole
    # pixels); every other facet must be decided as FreeCAD's projection decides.
    edge_distance = distance_to_polygon(fc_xy, star)
    clear = edge_distance > 1.0
    on_edge = int(np.count_nonzero(facing & ~clear))
    around = np.isin(np.arange(len(e.F)), np.flatnonzero(e.patches == 5)) | np.isin(
        np.arange(len(e.F)), planted)
    front = inside & around  # patch 5 faces the camera, nothing of the bracket before it

    def agrees(selected, wanted, band=1.0):
        chosen = np.zeros(len(e.F), bool)
        chosen[selected] = True
        sure = edge_distance > band
        return np.array_equal(chosen & sure, wanted & sure), np.flatnonzero(
            (chosen ^ wanted) & sure)[:8].tolist()

    check(set(planted) <= set(np.flatnonzero(front & clear).tolist())
          and not np.any(inside & clear & ~around & ~facing),
          "the star holds the {} planted facets and {} more of patch 5 ({} front facets "
          "behind them, {} on its edge)".format(len(planted), int(front.sum()) - len(planted),
                                                int((inside & ~around).sum()), on_edge))
    n_through = panel.select_polygon(star, "replace", hidden=True)
    same, differ = agrees(e.selected(), inside)
    check(same, "select_polygon(hidden=True) picks the {} front facets inside ({}; differing: "
          "{})".format(int(inside.sum()), n_through, differ))
    f.ck_hidden.setChecked(False)
    n_lasso = panel.select_polygon(star, "replace")
    same, differ = agrees(e.selected(), front)
    check(same and n_lasso < n_through, "select_polygon picks the {} visible ones, those of "
          "patch 5 ({}; differing: {})".format(int(front.sum()), n_lasso, differ))
    lassoed = set(e.selected().tolist())
    lo, hi = star.min(axis=0), star.max(axis=0)
    n_box = panel.select_box(lo[0], lo[1], hi[0], hi[1], "replace")
    check(n_box > n_lasso, "the star's bounding box would take more ({} > {})".format(
        n_box, n_lasso))
    panel.clear_selection()
    f.pb_lasso.click()
    check(panel.overlay.lasso_mode and not panel.overlay.box_mode
          and view.getViewer().isRedirectedToSceneGraph(),
          "'Lasso select' waits, the view's navigation off while the lasso is drawn")
    drawn = np.vstack([star, star[:1]])
    steps = np.vstack([a + (b - a) * k / 4.0 for a, b in zip(drawn[:-1], drawn[1:])
                       for k in range(4)])
    drawing = []

    def picture():  # the lasso as drawn, and the planted patch inside it
        panel.select_facets(planted, "replace")
        g.compose("edit_patches_lasso_drawn.png", f)
        band = panel.overlay._band
        shown = g.view_image("_lasso_shown.png", 400, 300)
        band.hide()
        hidden = g.view_image("_lasso_hidden.png", 400, 300)
        band.show_polygon(panel.overlay._lasso, panel.overlay.size())
        drawing.append(g.changed_to(shown, hidden, (25, 25, 25), 40))
        for tmp in (shown, hidden):
            os.remove(tmp)
        panel.clear_selection()

    g.mouse_path([tuple(p) for p in steps.tolist()], picture)
    dragged = set(e.selected().tolist())
    check(drawing and drawing[0] > 0.001, "the lasso line is drawn while the button is down "
          "({:.4f} of the view turns dark with it)".format(drawing[0] if drawing else 0.0))
    check(not panel.overlay.lasso_mode and not f.pb_lasso.isChecked()
          and not view.getViewer().isRedirectedToSceneGraph(),
          "lasso mode ends when the button is released, navigation back on")
    # The mouse moves in whole pixels of the widget (and Coin counts rows from the other
    # end): the drawn polygon is the star to within 2 pixels.
    same, differ = agrees(sorted(dragged), front, band=2.5)
    check(same and set(planted) <= dragged,
          "the lasso drawn with the mouse picks the same facets but within 2.5 px of the edge "
          "({} picked, {} by the method; differing: {})".format(len(dragged), len(lassoed),
                                                              differ))
    g.compose("edit_patches_lasso.png", f)
    f.cb_patch.setCurrentIndex(f.cb_patch.findData(5))
    f.pb_assign.click()
    g.process_events()
    check(panel.problems() == [] and f.lw_problems.count() == 0,
          "assigning the lassoed facets to patch 5 removes the planted violation")
    full = [(1, 1), (w - 1, 1), (w - 1, h - 1), (1, h - 1)]
    n_visible = panel.select_polygon(full, "replace", hidden=False)
    f.ck_hidden.setChecked(True)
    n_through = panel.select_polygon(full, "replace")
    f.ck_hidden.setChecked(False)
    check(0 < n_visible < n_through, "'also take hidden facets' adds the hidden ones ({} > {})"
          .format(n_through, n_visible))
    panel.clear_selection()

    # 7. FreeCAD's Undo / Redo act on the panel while it is open.
    undo = g.menu_action("Edit", "HexDomPanel_Std_Undo")
    check(undo is not None and g.menu_action("Edit", "Std_Undo") is None and undo.isEnabled(),
          "Edit > Undo is the panel's while it is open")
    bar_names = toolbar_undo_names()
    check("HexDomPanel_Std_Undo" in bar_names and "HexDomPanel_Std_Redo" in bar_names,
          "the toolbar's Undo and Redo buttons are the panel's too: {}".format(bar_names))
    g.key_click("Ctrl+Z")
    check(len(panel.problems()) == 3 and list(doc.UndoNames) == doc_undos
          and seg.Label2 == "bracket patches",
          "Ctrl+Z undoes the panel's last edit (the violation is back), not the document's")
    g.key_click("Ctrl+Shift+Z")
    check(panel.problems() == [], "Ctrl+Shift+Z redoes it")
    g.key_click("Ctrl+Z")
    g.key_click("Ctrl+Y")
    check(panel.problems() == [] and not e.can_redo, "Ctrl+Z then Ctrl+Y: fixed again")
    undo.trigger()
    check(len(panel.problems()) == 3 and list(doc.UndoNames) == doc_undos,
          "Edit > Undo undoes one panel edit")
    g.menu_action("Edit", "HexDomPanel_Std_Redo").trigger()
    check(panel.problems() == [] and list(doc.UndoNames) == doc_undos,
          "Edit > Redo redoes it; the document's undo list is untouched")

    # 8. Cancel leaves the Segmentation untouched.
    panel.select_facets(planted, "replace")
    panel.new_patch()
    panel.reject()
    g.process_events()
    check(task_segmentation.active_panel() is None and not FreeCADGui.Control.activeDialog(),
          "Cancel closes the panel")
    check(seg.PatchCount == 17 and list(seg.Issues) == [] and list(seg.EditedPatchTriangles) == []
          and seg.ViewObject.Visibility, "Cancel keeps the Segmentation as it was, shown again")
    std_undo = g.menu_action("Edit", "Std_Undo")
    check(std_undo is not None and g.menu_action("Edit", "HexDomPanel_Std_Undo") is None
          and std_undo.shortcut().toString() == "Ctrl+Z"
          and not any(n.startswith("HexDomPanel") for n in toolbar_undo_names())
          and len(toolbar_undo_names()) == len(bar_names),
          "FreeCAD's Edit > Undo and its toolbar buttons are back")
    g.key_click("Ctrl+Z")
    check(seg.Label2 == "" and "Describe" in doc.RedoNames,
          "with the panel closed Ctrl+Z undoes the document again")
    doc.redo()
    check(seg.Label2 == "bracket patches", "and the document's redo restores it")

    # 9. OK writes the edits (double-click opens the panel).
    seg.ViewObject.Proxy.doubleClicked(seg.ViewObject)
    g.process_events()
    panel = task_segmentation.active_panel()
    check(panel is not None, "a double-click opens the panel")
    panel.select_facets(planted, "replace")
    panel.new_patch()
    messages = [str(p) for p in panel.problems()]
    check(panel.accept(), "OK accepted")
    g.process_events()
    check(seg.PatchCount == 18 and sorted(seg.Issues) == sorted(messages)
          and sorted(seg.EditedPatchTriangles) == sorted(planted),
          "OK stores the planted patch: {} patches, the same {} issues".format(
              seg.PatchCount, len(seg.Issues)))
    check("Edit patches" in doc.UndoNames, "OK is one undoable transaction")
    FreeCADGui.ActiveDocument.setEdit(seg.Name, 0)
    g.process_events()
    panel = task_segmentation.active_panel()
    check(len(panel.problems()) == 3, "reopened, the panel lists the stored violation")
    panel.highlight_problem([p.kind for p in panel.problems()].index("curve_count"))
    panel.assign_to_patch(5)
    panel.accept()
    g.process_events()
    check(seg.PatchCount == 17 and list(seg.Issues) == [], "fixed through the panel and OK: valid")
    doc.undo()
    doc.recompute()
    check(seg.PatchCount == 18, "the document's undo takes the fix back")
    doc.redo()
    doc.recompute()
    check(seg.PatchCount == 17 and list(seg.Issues) == [], "and redo restores it")
    FreeCAD.closeDocument(doc.Name)
    g.process_events()

    # 10. Whole CAD faces on a Part L-shape (three fused boxes: every face a quad patch).
    doc = FreeCAD.newDocument("EditCadFaces")
    boxes = [Part.makeBox(10, 10, 10), Part.makeBox(20, 10, 10, FreeCAD.Vector(10, 0, 0)),
             Part.makeBox(10, 20, 10, FreeCAD.Vector(0, 10, 0))]
    part = doc.addObject("Part::Feature", "LPart")
    part.Shape = boxes[0].fuse(boxes[1:])
    surf = make.make_surface(doc, source=part, size=2.0)
    cad_seg = make.make_segmentation(doc, surf, method="Surface patches")
    api.recompute_document(doc, [surf, cad_seg])
    view = FreeCADGui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    FreeCADGui.ActiveDocument.setEdit(cad_seg.Name, 0)
    g.process_events()
    panel = task_segmentation.active_panel()
    e = panel.editor
    check(panel.problems() == [] and e.face_ids is not None, "the L-shape's CAD faces are valid")
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(part, ["Face3", "Face5"])
    panel.form.pb_cad_faces.click()
    expected = np.flatnonzero(np.isin(e.face_ids, [3, 5]))
    check(sorted(e.selected().tolist()) == expected.tolist(),
          "'Add selected CAD faces' takes Face3 and Face5 ({} facets)".format(len(expected)))
    panel.clear_selection()
    panel.set_pick_mode("face")
    tri = int(np.flatnonzero(e.normals @ np.array(tuple(view.getViewDirection())) < -0.5)[0])
    xy = screen_of(panel, e.V[e.F[tri]].mean(axis=0)[None, :])[0]
    picked = panel.click(float(xy[0]), float(xy[1]))
    face = e.face_ids[picked] if picked is not None else -1
    check(picked is not None and sorted(e.selected().tolist())
          == np.flatnonzero(e.face_ids == face).tolist(),
          "a click in CAD-face mode selects the whole Face{}".format(face))
    g.compose("edit_patches_cad_faces.png", panel.form)
    panel.reject()
    g.process_events()
    check(not errors, "no error message boxes: {}".format(errors))
    FreeCAD.closeDocument(doc.Name)


try:
    run()
except Exception:  # any error fails the test; the GUI must still exit
    traceback.print_exc()
    g.failures.append("exception")
g.finish()
