"""GUI test of the Build Polycube task panel, run by tests/freecad/run.sh as
`freecad gui_test_build_polycube.py` under xvfb.

A Part L-shape (three fused boxes, every CAD face a patch): HexDom_BuildPolycube on its
Segmentation opens the panel over the 16 corners of its 14 patches; the three hex blocks are
built from vertices picked by clicks at their screen positions (in an order the tool has to fix
up), an interior vertex comes and goes (centroid, typed coordinates, click on a face), OK makes
a HexDom Polycube, and its mesh (core.generate + core.improve, and a HexDom Mesh object) has no
inverted cell. Reopened by double-click, the panel finds the Segmentation through the mesh;
deleting a block lists the uncovered patches and the open faces, undo clears them; replacing a
block by a tet on four of its vertices shows as a tet with problems; a hex on typed vertices
poking into two blocks (no shared face) is listed as two overlaps and clicking one draws both
blocks red; Ctrl+Z and Edit > Undo take the steps back one by one without touching the
document. With the
paper's data: the rocker arm's patch file and rockerarm_polycube_withtet.k load as 60 hex, 11
prism and 2 tet blocks with no problem listed, and export again. Screenshots of the panel with
the 3D view go to artifacts/. Prints "GUI TEST PASSED" and exits 0, or lists the failures and
exits 1; a watchdog exits 2 on a hang.
"""

import os
import sys
import tempfile
import traceback

TEST_DIR = os.environ.get("HEXDOM_FC_TEST_DIR") or os.path.dirname(
    os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, TEST_DIR)

import gui_shots as g  # noqa: E402

g.start_watchdog(170.0)
check = g.check


def indices(field):
    """The values of a Coin multi-field (coordIndex) as a list."""
    return [int(field[i]) for i in range(field.getNum())]


def run():
    import numpy as np

    import FreeCAD
    import FreeCADGui
    import Part
    from PySide import QtGui

    import fc_testdata
    from HexDomWorkbench import api, core, make
    from HexDomWorkbench.objects import polycube, segmentation
    from HexDomWorkbench.logic import polycube_building
    from HexDomWorkbench.taskpanels import task_polycube

    errors = []
    QtGui.QMessageBox.critical = staticmethod(lambda parent, title, text, *a: errors.append(
        (title, text)))
    FreeCADGui.activateWorkbench("HexDomWorkbench")
    g.set_task_width()
    work = tempfile.mkdtemp(prefix="hexdom-gui-polycube-")

    # 1. The L-shape, its CAD faces as patches, the panel from the command.
    doc = FreeCAD.newDocument("BuildPolycube")
    boxes = [Part.makeBox(10, 10, 10), Part.makeBox(20, 10, 10, FreeCAD.Vector(10, 0, 0)),
             Part.makeBox(10, 20, 10, FreeCAD.Vector(0, 10, 0))]
    part = doc.addObject("Part::Feature", "LPart")
    part.Shape = boxes[0].fuse(boxes[1:])
    surf = make.make_surface(doc, source=part, size=2.0)
    seg = make.make_segmentation(doc, surf, method="Surface patches")
    api.recompute_document(doc, [surf, seg])
    check(seg.PatchCount == 14 and list(seg.Issues) == [], "the L-shape has 14 valid patches")
    view = FreeCADGui.ActiveDocument.ActiveView
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(seg)
    check(FreeCADGui.isCommandActive("HexDom_BuildPolycube"), "Build polycube active on it")
    count = len(doc.Objects)
    FreeCADGui.runCommand("HexDom_BuildPolycube")
    g.process_events()
    panel = task_polycube.active_panel()
    if not check(panel is not None and FreeCADGui.Control.activeDialog(),
                 "HexDom_BuildPolycube opens the task panel"):
        return
    f, b = panel.form, panel.builder
    check(len(doc.Objects) == count, "nothing is added before OK")
    check(b.corner_count == 16 and "16 corners" in f.lbl_boundary.text(),
          "the boundary: " + f.lbl_boundary.text())
    problems = panel.problems()
    check(len(problems) == 14 and {p.kind for p in problems} == {"uncovered_patch"}
          and f.lw_problems.count() == 14, "all 14 patches are listed as uncovered")
    # A view direction in which no two corners hide each other.
    view.setViewDirection((-0.55, 0.85, -0.62))
    view.fitAll()
    g.process_events()
    g.compose("build_polycube_start.png", f)
    # What the view draws: corners as points, curves as lines, patches as quads.
    curves = indices(panel._curves.coordIndex)
    patch_faces = indices(panel._patches.faces.coordIndex)
    sides = np.diff([-1] + [i for i, v in enumerate(patch_faces) if v < 0]) - 1
    edges = len(b.boundary.edges)
    check(panel._corner_coords.point.getNum() == 16 and curves.count(-1) == edges
          and 16 - edges + 14 == 2 and len(sides) == 14 and set(sides.tolist()) == {4},
          "the view draws 16 corner points, {} curves (Euler: 16 - {} + 14 = 2) and 14 quad "
          "patches ({} / {} / {})".format(edges, edges, panel._corner_coords.point.getNum(),
                                          curves.count(-1), len(sides)))

    def at(p):
        v, d = b.nearest_vertex(p)
        return v

    def click_vertex(v):
        xy, _ = panel.overlay.project(b.points[[v]])
        return panel.click(float(xy[0][0]), float(xy[0][1]))

    # 2. Three hex blocks, each from eight clicked corners in a scrambled order.
    f.cb_pick_mode.setCurrentIndex(0)
    for k, (x0, y0, x1, y1) in enumerate([(0, 0, 10, 10), (10, 0, 30, 10), (0, 10, 10, 30)]):
        corners = [at((x, y, z)) for z in (10, 0) for x in (x1, x0) for y in (y0, y1)]
        picked = [click_vertex(v) for v in corners]
        check(picked == corners and b.selection == corners,
              "block {}: eight clicks pick its corners {}".format(k + 1, corners))
        check(f.pb_add_block.isEnabled() and "makes a hex" in f.lbl_selection.text(),
              "the panel offers a hex: " + f.lbl_selection.text())
        f.pb_add_block.click()
        g.process_events()
        t, verts = b.blocks[-1]
        sj = float(b.block_jacobians()[-1])
        check(t == core.HEX and sorted(verts) == sorted(corners) and sj > 0.99,
              "block {} added as a hex, reordered to scaled Jacobian {:.3f}".format(k + 1, sj))
        if k == 1:
            g.compose("build_polycube_progress.png", f)
    check(panel.problems() == [] and f.lw_problems.count() == 0
          and "No problems" in f.lbl_status.text(), "three hexes fill the L: no problem listed")
    check(f.lw_blocks.count() == 3 and "3 hex, 0 prism, 0 tet" in f.lbl_counts.text(),
          "three blocks listed: " + f.lbl_counts.text())
    view.fitAll()
    g.compose("build_polycube_lpart.png", f)

    # 3. Interior vertices: at a centroid, moved to typed coordinates, at a clicked point.
    panel.select_vertices([at((0, 0, 0)), at((10, 10, 10))], "replace")
    f.pb_add_centroid.click()
    c = b.vertex_count - 1
    check(c == 16 and np.allclose(b.points[c], (5, 5, 5)),
          "'Add at centroid' makes interior vertex 16 at (5, 5, 5)")
    check([p.kind for p in panel.problems()] == ["unused_vertex"], "an unused vertex is listed")
    click_vertex(c)
    panel.set_coordinates((4.0, 5.0, 6.0))
    f.pb_move.click()
    check(np.allclose(b.points[c], (4, 5, 6)), "'Move picked vertex' takes the typed coordinates")
    f.pb_delete_vertex.click()
    check(b.vertex_count == 16 and panel.problems() == [], "'Delete picked vertex' removes it")
    panel.set_coordinates((20.0, 5.0, 5.0))
    f.pb_add_xyz.click()
    check(b.vertex_count == 17 and np.allclose(b.points[16], (20, 5, 5)),
          "'Add at coordinates' adds (20, 5, 5)")
    f.pb_undo.click()
    panel.set_pick_mode("point")
    top = np.array([25.0, 5.0, 10.0])
    xy, _ = panel.overlay.project(top[None, :])
    v = panel.click(float(xy[0][0]), float(xy[0][1]))
    check(v == 16 and np.allclose(b.points[16], top, atol=0.05),
          "a click in point mode adds a vertex on the face it hits: {}".format(
              np.round(b.points[v], 3).tolist() if v is not None else None))
    f.pb_undo.click()
    panel.set_pick_mode("vertex")
    check(b.vertex_count == 16 and panel.problems() == [], "undone: 16 vertices, no problem")

    # 4. OK makes the Polycube; generate its mesh.
    check(panel.accept(), "OK accepted")
    g.process_events()
    polys = [o for o in doc.Objects if getattr(getattr(o, "Proxy", None), "Type", "")
             == "HexDom::Polycube"]
    check(len(polys) == 1 and polys[0].HexBlocks == 3 and polys[0].PointCount == 16,
          "OK makes a HexDom Polycube with 3 hex blocks over 16 points")
    check("Build polycube" in doc.UndoNames and not FreeCADGui.Control.activeDialog(),
          "one undoable transaction, panel closed")
    poly = polys[0]
    surface = segmentation.get_surface(seg)
    mesh = core.improve(core.generate(surface, polycube.get_structure(poly), level=2), surface)
    report = core.quality_report(mesh)
    check(mesh.count(core.HEX) == 192 and report["hex"]["inverted"] == 0,
          "core.generate + core.improve: {} hexes, {} inverted, min SJ {:.3f}".format(
              mesh.count(core.HEX), report["hex"]["inverted"], report["hex"]["sj_min"]))
    mesh_obj = make.make_hex_mesh(doc, segmentation=seg, polycube=poly, level=2)
    api.recompute_document(doc, [mesh_obj])
    check(mesh_obj.HexCount == 192 and mesh_obj.InvertedCount == 0,
          "the HexDom Mesh of the panel's polycube: 192 hexes, none inverted")

    # 5. Reopen by double-click: the Segmentation comes from the mesh; a lost block shows.
    poly.ViewObject.Proxy.doubleClicked(poly.ViewObject)
    g.process_events()
    panel = task_polycube.active_panel()
    check(panel is not None and panel.segmentation == seg and len(panel.builder.blocks) == 3
          and panel.problems() == [], "double-click reopens it over the mesh's Segmentation")
    f, b = panel.form, panel.builder
    f.lw_blocks.setCurrentRow(1)
    check(panel.selected_block == 1 and sorted(b.selection) == sorted(b.blocks[1][1]),
          "clicking a block in the list shows it and picks its vertices")
    f.pb_delete_block.click()
    kinds = sorted({p.kind for p in panel.problems()})
    check(kinds == ["open_face", "uncovered_patch"] and len(panel.problems()) == 6,
          "without block 2: 5 uncovered patches and its open face ({})".format(
              len(panel.problems())))
    f.lw_problems.setCurrentRow(0)
    g.compose("build_polycube_problem.png", f)
    f.pb_undo.click()
    check(panel.problems() == [] and len(b.blocks) == 3, "undo brings the block back")

    # 6. Edit a block: block 2 re-picked as a tet on four of its vertices.
    f.lw_blocks.setCurrentRow(1)
    old = b.blocks[1]
    panel.select_vertices(list(old[1][:3]) + [old[1][4]], "replace")
    check(f.pb_edit_block.isEnabled(), "'Replace block' offered with 4 picks and a block chosen")
    f.pb_edit_block.click()
    check(len(b.blocks) == 3 and b.blocks[1][0] == core.TET and "tet" in f.lw_blocks.item(1)
          .text() and any(p.kind == "uncovered_patch" for p in panel.problems()),
          "block 2 is now a tet: {}; {} problems".format(f.lw_blocks.item(1).text(),
                                                          len(panel.problems())))
    f.pb_undo.click()
    check(b.blocks[1] == old and panel.problems() == [], "undo gives the hex back")

    # 7. A hex on typed vertices poking into blocks 1 and 2 without sharing a face with them.
    doc_undos = list(doc.UndoNames)
    for x in (5.0, 15.0):
        for y in (2.0, 8.0):
            for z in (2.0, 8.0):
                panel.set_coordinates((x, y, z))
                f.pb_add_xyz.click()
    panel.select_vertices(list(range(16, 24)), "replace")
    f.pb_add_block.click()
    overlaps = [p for p in panel.problems() if p.kind == "overlap"]
    check(sorted(p.blocks for p in overlaps) == [[0, 3], [1, 3]],
          "the poking hex overlaps blocks 1 and 2: {}".format([str(p) for p in overlaps]))
    row = [str(p) for p in panel.problems()].index(str(overlaps[0]))
    f.lw_problems.setCurrentRow(row)
    g.process_events()
    drawn = indices(panel._hl_lines.coordIndex)
    drawn = {tuple(sorted(drawn[i:i + 2])) for i in range(0, len(drawn), 3)}
    wanted = set()
    for k in overlaps[0].blocks:
        t, verts = b.blocks[k]
        for face in polycube_building.BLOCK_FACES[t]:
            ids = [verts[i] for i in face]
            wanted.update(tuple(sorted(e)) for e in zip(ids, ids[1:] + ids[:1]))
    check(drawn == wanted and len(wanted) == 24,
          "clicking the overlap draws the 24 edges of both blocks in red ({})".format(len(drawn)))
    view.fitAll()
    g.compose("build_polycube_overlap.png", f)
    undo = g.menu_action("Edit", "HexDomPanel_Std_Undo")
    check(undo is not None and g.menu_action("Edit", "Std_Undo") is None,
          "Edit > Undo is the panel's while it is open")
    f.sb_x.setFocus()
    g.key_click("Ctrl+Z", f.sb_x)
    check(len(b.blocks) == 4 and b.vertex_count == 24,
          "Ctrl+Z in a coordinate box is the box's own (the blocks stay)")
    g.key_click("Ctrl+Z")
    check(len(b.blocks) == 3 and b.vertex_count == 24, "Ctrl+Z takes the poking block away")
    for _ in range(7):
        g.key_click("Ctrl+Z")
    undo.trigger()
    check(b.vertex_count == 16 and panel.problems() == [] and list(doc.UndoNames) == doc_undos
          and poly.HexBlocks == 3, "seven Ctrl+Z and Edit > Undo take the 8 vertices back; the "
          "document is untouched")
    g.key_click("Ctrl+Y")
    check(b.vertex_count == 17, "Ctrl+Y redoes one")
    panel.reject()
    g.process_events()
    check(poly.HexBlocks == 3 and not FreeCADGui.Control.activeDialog(), "Cancel changes nothing")
    FreeCAD.closeDocument(doc.Name)
    g.process_events()

    # 6. The paper's rocker arm: its structure with tets over its patch file.
    root = os.path.join(fc_testdata.data_root(), "hexdom", "rockerarm")
    patches_k = os.path.join(root, "rockerarm_indexPatch_hexdom.k")
    structure_k = os.path.join(root, "rockerarm_polycube_withtet.k")
    if not (os.path.isfile(patches_k) and os.path.isfile(structure_k)):
        g.skip("rocker arm: paper data missing ({}; set HEXDOM_DATA)".format(
            patches_k if not os.path.isfile(patches_k) else structure_k))
    else:
        doc = FreeCAD.newDocument("Rockerarm")
        seg = api.import_patches(patches_k, doc)
        view = FreeCADGui.ActiveDocument.ActiveView
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(seg)
        FreeCADGui.runCommand("HexDom_BuildPolycube")
        g.process_events()
        panel = task_polycube.active_panel()
        f, b = panel.form, panel.builder
        check(b.corner_count == 141 and len(panel.problems()) == 145,
              "rocker arm: 141 corners, 145 patches to cover")
        patch_faces = indices(panel._patches.faces.coordIndex)
        sides = np.diff([-1] + [i for i, v in enumerate(patch_faces) if v < 0]) - 1
        check(sorted(np.unique(sides, return_counts=True)[1].tolist()) == [8, 137]
              and set(sides.tolist()) == {3, 4}, "its patches are drawn as 137 quads and 8 "
              "triangles: {}".format(dict(zip(*[x.tolist() for x in np.unique(
                  sides, return_counts=True)]))))
        interior = panel.import_structure(structure_k)
        check(panel.counts() == {"hex": 60, "prism": 11, "tet": 2} and interior == 12,
              "withtet structure: {} blocks, {} interior vertices".format(panel.counts(),
                                                                          interior))
        check(panel.problems() == [] and f.lw_problems.count() == 0,
              "no problem listed for the paper's structure: {}".format(
                  [str(p) for p in panel.problems()][:3]))
        check("60 hex, 11 prism, 2 tet" in f.lbl_counts.text(), f.lbl_counts.text())
        view.viewIsometric()
        view.fitAll()
        g.compose("build_polycube_rockerarm.png", f)
        out = os.path.join(work, "rockerarm_again.k")
        panel.export_structure(out)
        again = core.read_mesh(out)
        check(again.counts["hex"] == 60 and again.counts["prism"] == 11
              and again.counts["tet"] == 2, "exported .k reads back as 60 / 11 / 2")
        check(panel.accept(), "OK accepted")
        g.process_events()
        polys = [o for o in doc.Objects if getattr(getattr(o, "Proxy", None), "Type", "")
                 == "HexDom::Polycube"]
        check(len(polys) == 1 and (polys[0].HexBlocks, polys[0].PrismBlocks, polys[0].TetBlocks)
              == (60, 11, 2), "the rocker arm's Polycube object holds 60 / 11 / 2 blocks")
        FreeCAD.closeDocument(doc.Name)
    check(not errors, "no error message boxes: {}".format(errors))


try:
    run()
except Exception:  # any error fails the test; the GUI must still exit
    traceback.print_exc()
    g.failures.append("exception")
g.finish()
