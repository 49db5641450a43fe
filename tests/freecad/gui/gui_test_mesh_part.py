"""GUI test of Mesh Part, run by tests/freecad/run.sh as `freecad gui_test_mesh_part.py` under xvfb.

1. HexDom_MeshPart is registered with an icon and a tooltip, and sits in the "HexDom pipeline"
   toolbar; triggering that toolbar action on the selected STEP bracket (examples/data) adds a
   HexDom Surface, Segmentation, Polycube (Mode Automatic) and Mesh, all valid, the mesh with no
   inverted cell. Then HexDom_MeshRegion on the Mesh adds a FreeCAD FEM mesh region; on the hole's
   face with a length of 1 the recomputed mesh is refined there (mesh_region_bracket.png). Before that,
   ElementOrder 2nd gives 20-node hexes, drawn plain (FreeCAD 0.20 cannot colour quadratic cells
   one by one; mesh_part_bracket_2nd.png), and 1st the first mesh back, coloured again. While the core works the GUI keeps processing events (a 50 ms timer keeps
   ticking; the longest gap is printed and checked). Screenshot of the mesh coloured by cell type
   (artifacts/mesh_part_bracket.png): hex blue must show; one of the patches
   (mesh_part_patches.png) too.
2. Cancel: on a box, the progress dialog's Cancel button is clicked as soon as the pipeline (the
   Mesh's `hexdom mesh`) runs. The command keeps the objects, shows no message box, the Mesh is
   marked failed with "cancelled" and holds no node; a plain recompute afterwards makes every
   object valid: the document was left consistent.
3. Cancel during HexDom_GenerateMesh: the command's transaction is aborted, nothing is added.
4. Mesh Part on a 15 degree knife edge: the automatic Polycube has prism blocks; Build Polycube opens
   on it with no problem and OK keeps them (hex, prism, tet counts and corner positions).
5. Mesh Part (the command) on a torus at element size 10, where the core's automatic choice keeps the
   overlay grid's mesh: no message box, the Mesh says "overlay" (MeshingPath) and why (PolycubeNote),
   the Segmentation and the Polycube are kept, the Mesh no longer uses the Polycube; Edit Patches
   opens on the Segmentation, Build Polycube on the Polycube (against its own Segmentation) with no
   problem and OK keeps its blocks, the overlay mesh stays valid.
6. Cancel inside a long core call: Mesh Part on a sphere at a fine size, Cancel clicked 1.5 s into
   the pipeline (the core then meshes on two threads): Mesh Part returns within 3 s of the click
   (the latency is printed), with no message box, and the Surface stays valid.
7. Mesh Part on an STL opened in FreeCAD (Mesh.insert: a mesh object) holding two boxes that touch
   along a face, one of them inside out: the toolbar action is enabled with the mesh object
   selected, no message box, four objects, the Mesh's cells in two regions (one per box) with no
   inverted cell (mesh_part_stl.png).
Prints "GUI TEST PASSED" and exits 0, or lists the failures and exits 1; a watchdog exits 2.
"""

import os
import sys
import time
import traceback

TEST_DIR = os.environ.get("HEXDOM_FC_TEST_DIR") or os.path.dirname(
    os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, TEST_DIR)

import gui_shots as g  # noqa: E402

g.start_watchdog(170.0)
check = g.check

TYPE_HUES = {"hex blue": 215, "prism orange": 35, "tet magenta": 300}


def colour_shares(path, hues, tolerance=16, min_saturation=0.3):
    """Fraction of drawn (non-white) pixels, and of those the share near each named hue."""
    from PySide import QtGui
    img = QtGui.QImage(path)
    counts = dict.fromkeys(hues, 0)
    drawn = total = 0
    for y in range(0, img.height(), 2):
        for x in range(0, img.width(), 2):
            c = QtGui.QColor(img.pixel(x, y))
            total += 1
            if c.red() > 245 and c.green() > 245 and c.blue() > 245:
                continue
            drawn += 1
            h, s, v, _ = c.getHsvF()
            if not hues or s < min_saturation or v < 0.2 or h < 0:
                continue
            deg = h * 360.0
            dist = {k: min(abs(deg - hv), 360 - abs(deg - hv)) for k, hv in hues.items()}
            name = min(dist, key=dist.get)
            if dist[name] < tolerance:
                counts[name] += 1
    return drawn / max(total, 1), {k: v / max(drawn, 1) for k, v in counts.items()}


def screenshot(name, objs):
    import FreeCADGui
    doc = objs[0].Document
    for o in doc.Objects:
        if getattr(o, "ViewObject", None) is not None:
            o.ViewObject.Visibility = o in objs
    g.process_events()
    view = FreeCADGui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    return g.view_image(name, 800, 600)


def toolbar_action(toolbar_title, text):
    import FreeCADGui
    from PySide import QtGui
    for bar in FreeCADGui.getMainWindow().findChildren(QtGui.QToolBar):
        if bar.windowTitle() == toolbar_title:
            for action in bar.actions():
                if action.text().replace("&", "") == text:
                    return action
    return None


def edit_automatic_polycube(poly, mesh):
    """The automatic Polycube opens in Build Polycube against its own patches with no problem; OK
    switches it to Manual and keeps its blocks (hex, prism and tet), and the Mesh recomputes."""
    from HexDomWorkbench.taskpanels import task_polycube

    def block_set(obj):  # blocks as sets of corner positions: independent of the numbering
        P = [tuple(round(c, 6) for c in p) for p in obj.Points]
        B = list(obj.Blocks)
        return sorted(tuple(sorted(P[v] for v in B[i:i + 8] if v >= 0))
                      for i in range(0, len(B), 8))

    import FreeCADGui
    blocks = block_set(poly)
    counts = {"hex": poly.HexBlocks, "prism": poly.PrismBlocks, "tet": poly.TetBlocks}
    FreeCADGui.ActiveDocument.setEdit(poly.Name, 0)
    g.process_events()
    panel = task_polycube.active_panel()
    check(panel is not None, "Build Polycube opens on the automatic Polycube {}".format(counts))
    if panel is None:
        return
    problems = [str(p) for p in panel.problems()]
    check(not problems, "its blocks fit its patches, no problem listed: {}".format(problems[:3]))
    check(panel.counts() == counts, "the panel holds the Polycube's blocks: {} for {}".format(
        panel.counts(), counts))
    panel.accept()
    g.process_events()
    check(poly.Mode == "Manual", "OK switched the Polycube to Manual ({})".format(poly.Mode))
    check(block_set(poly) == blocks, "and kept its blocks")
    check("Invalid" not in mesh.State and mesh.InvertedCount == 0,
          "the Mesh recomputed from the kept blocks")


def mesh_region(doc, part, mesh):
    """HexDom_MeshRegion on the selected Mesh: a FreeCAD FEM mesh region in its MeshRegionList,
    its task panel open; given the hole's face and a length of 1, the recomputed Mesh is the
    overlay grid's, refined there (more than 3 times the hexes), with no inverted cell."""
    import FreeCADGui
    import Part
    action = toolbar_action("HexDom pipeline", "Mesh region")
    check(action is not None, "Mesh region is in the HexDom pipeline toolbar")
    if action is None:
        return
    hexes = mesh.HexCount
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(mesh)
    deadline = time.time() + 2.0  # (FreeCAD updates the actions' states on a timer)
    while not action.isEnabled() and time.time() < deadline:
        g.process_events()
        time.sleep(0.05)
    check(action.isEnabled(), "Mesh region is enabled with the HexDom Mesh selected")
    action.trigger()
    g.process_events()
    regions = list(mesh.MeshRegionList)
    check(len(regions) == 1, "one mesh region added to the Mesh's MeshRegionList")
    check(FreeCADGui.Control.activeDialog(), "its task panel is open")
    if len(regions) != 1:
        return
    hole = next("Face{}".format(i) for i, f in enumerate(part.Shape.Faces, 1)
                if isinstance(f.Surface, Part.Cylinder) and abs(f.Surface.Radius - 6) < 1e-9
                and abs(f.Surface.Center.x - 40) < 1e-9)  # (the fillet has radius 6 too)
    regions[0].References = [(part, hole)]
    regions[0].CharacteristicLength = 1.0
    FreeCADGui.Control.closeDialog()
    FreeCADGui.ActiveDocument.resetEdit()
    mesh.Pipeline = True  # (the Polycube was edited above: the Mesh had left the pipeline)
    doc.recompute()
    g.process_events()
    check(mesh.InvertedCount == 0 and mesh.HexCount > 3 * hexes and len(mesh.LocalSizes) == 1
          and "(within 20%)" in mesh.LocalSizes[0],
          "with the region on {}: {} hex ({} before), {} inverted, path {}, {}".format(
              hole, mesh.HexCount, hexes, mesh.InvertedCount, mesh.MeshingPath, list(mesh.LocalSizes)))
    path = screenshot("mesh_region_bracket.png", [mesh])
    drawn, _ = colour_shares(path, {})
    check(drawn > 0.05, "the refined mesh shows")


def second_order(doc, mesh):
    """ElementOrder 2nd on the bracket's Mesh: the FEM mesh holds 20-node hexes (a node per edge:
    more nodes than corners), is drawn plain (mesh_part_bracket_2nd.png), and 1st gives the first
    mesh back, coloured by cell type again."""
    nodes, hexes = mesh.FemMesh.NodeCount, mesh.HexCount
    mesh.ElementOrder = "2nd"
    doc.recompute()
    g.process_events()
    fem = mesh.FemMesh
    quadratic = fem.NodeCount > nodes and all(len(fem.getElementNodes(e)) == 20 for e in list(fem.Volumes)[:50])
    check(quadratic and mesh.HexCount == hexes and mesh.InvertedCount == 0,
          "ElementOrder 2nd: {} nodes ({} first order), {} hex, 20 nodes each, {} inverted".format(
              fem.NodeCount, nodes, mesh.HexCount, mesh.InvertedCount))
    path = screenshot("mesh_part_bracket_2nd.png", [mesh])
    drawn, share = colour_shares(path, {"green": 120})
    # Drawn plain: FreeCAD 0.20's per-element colours do not fit quadratic faces (the cells past
    # the colours it has would show green).
    check(drawn > 0.05 and share["green"] < 0.01, "the second-order mesh shows, drawn plain (green {:.3f})".format(
        share["green"]))
    mesh.ElementOrder = "1st"
    doc.recompute()
    g.process_events()
    check(mesh.FemMesh.NodeCount == nodes, "1st gives the first-order mesh back")
    drawn, share = colour_shares(screenshot("mesh_part_bracket_1st_again.png", [mesh]), TYPE_HUES)
    check(share["hex blue"] > 0.2, "coloured by cell type again")


def run():
    import FreeCAD
    import FreeCADGui
    import Part
    from PySide import QtCore, QtGui

    import fc_testdata
    from HexDomWorkbench import paths, progress
    from HexDomWorkbench.objects import polycube

    FreeCADGui.activateWorkbench("HexDomWorkbench")
    g.process_events()
    check("HexDom_MeshPart" in FreeCADGui.listCommands(), "HexDom_MeshPart registered")
    check(os.path.isfile(paths.icon("HexDom_MeshPart")), "HexDom_MeshPart has its icon")
    action = toolbar_action("HexDom pipeline", "Mesh part")
    check(action is not None, "Mesh part is in the HexDom pipeline toolbar")
    if action is None:
        return
    check(len(action.toolTip()) > 40 and not action.icon().isNull(),
          "the toolbar action has a tooltip and an icon")
    errors = []
    QtGui.QMessageBox.critical = staticmethod(lambda parent, title, text, *a: errors.append(
        (title, text)))

    # 1. The STEP bracket, from the toolbar action.
    doc = FreeCAD.newDocument("MeshPartGui")
    part = doc.addObject("Part::Feature", "Bracket")
    part.Shape = Part.read(fc_testdata.example_path("bracket.step"))
    doc.recompute()
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(part)
    g.process_events()
    check(action.isEnabled(), "Mesh part is enabled with a Part solid selected")
    ticks = []
    timer = QtCore.QTimer()
    timer.timeout.connect(lambda: ticks.append(time.time()))
    timer.start(50)
    start = time.time()
    action.trigger()
    elapsed = time.time() - start
    timer.stop()
    gaps = [b - a for a, b in zip([start] + ticks, ticks + [start + elapsed])]
    print("  mesh part: {:.1f} s, {} timer ticks, longest gap {:.2f} s".format(
        elapsed, len(ticks), max(gaps)))
    check(not errors, "Mesh part reported no error: {}".format(errors))
    types = {"HexDom::Surface": [], "HexDom::Segmentation": [], "HexDom::Polycube": [],
             "HexDom::Mesh": []}
    for o in doc.Objects:
        t = getattr(getattr(o, "Proxy", None), "Type", None)
        if t in types:
            types[t].append(o)
    check(all(len(v) == 1 for v in types.values()),
          "one object of each HexDom type: {}".format({k: len(v) for k, v in types.items()}))
    if not all(len(v) == 1 for v in types.values()):
        return
    seg, poly, mesh = (types[k][0] for k in ("HexDom::Segmentation", "HexDom::Polycube",
                                             "HexDom::Mesh"))
    check(all("Invalid" not in v[0].State and "Error" not in v[0].State for v in types.values()),
          "every object recomputed")
    check(poly.Mode == "Automatic" and polycube.has_patch_surface(poly),
          "the Polycube is automatic, with its patch surface")
    check(mesh.HexCount > 0 and mesh.InvertedCount == 0 and mesh.MinHexSJ >= 0.3,
          "mesh: {} hex, {} prism, {} tet, {} inverted, worst hex SJ {:.3f}".format(
              mesh.HexCount, mesh.PrismCount, mesh.TetCount, mesh.InvertedCount, mesh.MinHexSJ))
    check(elapsed < 2.0 or max(gaps) < 1.0,
          "the GUI kept processing events while the core worked (longest gap {:.2f} s of "
          "{:.1f} s)".format(max(gaps), elapsed))
    check(progress.current() is None, "no progress session left open")
    dialogs = [w for w in QtGui.QApplication.topLevelWidgets()
               if w.objectName() == "HexDomProgress" and w.isVisible()]
    check(not dialogs, "the progress dialog is closed")

    check(mesh.ViewObject.ColorBy == "Cell type", "the mesh is coloured by cell type")
    path = screenshot("mesh_part_bracket.png", [mesh])
    drawn, share = colour_shares(path, TYPE_HUES)
    print("  mesh by type: drawn {:.3f} {}".format(drawn, {k: round(v, 3)
                                                           for k, v in share.items()}))
    check(drawn > 0.05 and share["hex blue"] > 0.2, "the mesh shows, hexes in blue")
    path = screenshot("mesh_part_patches.png", [seg])
    drawn, _ = colour_shares(path, {})
    check(drawn > 0.05, "the segmentation shows")
    second_order(doc, mesh)

    edit_automatic_polycube(poly, mesh)
    mesh_region(doc, part, mesh)
    FreeCAD.closeDocument(doc.Name)
    g.process_events()

    # 2. Cancel as soon as the progress dialog shows.
    doc = FreeCAD.newDocument("MeshPartCancel")
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = 40.0, 20.0, 10.0
    doc.recompute()
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(box)
    clicked = []

    def click_cancel():  # once a stage after the tessellation runs
        if clicked:
            return
        for w in QtGui.QApplication.topLevelWidgets():
            if w.objectName() == "HexDomProgress" and w.isVisible() and \
                    "tessellate" not in w.label.text():
                button = w.findChild(QtGui.QPushButton, "HexDomProgressCancel")
                if button is not None and button.isEnabled():
                    clicked.append(w.label.text())
                    button.click()

    canceller = QtCore.QTimer()
    canceller.timeout.connect(click_cancel)
    canceller.start(0)  # at every pass of the event loop
    errors.clear()
    action.trigger()
    canceller.stop()
    print("  cancel clicked during: {}".format(clicked))
    check(bool(clicked), "the Cancel button was clicked")
    check(not errors, "no message box after Cancel: {}".format(errors))
    objs = {getattr(o.Proxy, "Type", ""): o for o in doc.Objects if hasattr(o, "Proxy")}
    check(len(objs) == 4, "the four objects are kept after Cancel")
    if len(objs) != 4:
        return
    failed = [o for o in objs.values() if "Invalid" in o.State or "Error" in o.State]
    check(len(failed) == 1 and "cancelled" in failed[0].getStatusString()
          and failed[0] != objs["HexDom::Surface"],
          "exactly one stage after the tessellation is marked cancelled: {}".format(
              [(o.Label, o.getStatusString()) for o in failed]))
    mesh = objs["HexDom::Mesh"]
    check(mesh.FemMesh.NodeCount == 0, "no stage after the cancelled one stored anything")
    check("Invalid" not in objs["HexDom::Surface"].State, "the finished Surface stays valid")
    doc.recompute()
    g.process_events()
    check(all("Invalid" not in o.State and "Error" not in o.State for o in objs.values())
          and mesh.HexCount > 0,
          "recomputing after Cancel meshes the part ({} hex)".format(mesh.HexCount))
    check(mesh.InvertedCount == 0, "and the mesh has no inverted cell")

    # 3. Cancel during HexDom_GenerateMesh: its transaction is aborted, nothing is added.
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(objs["HexDom::Segmentation"])
    FreeCADGui.Selection.addSelection(objs["HexDom::Polycube"])
    names = [o.Name for o in doc.Objects]
    clicked.clear()
    errors.clear()
    canceller.start(0)
    FreeCADGui.runCommand("HexDom_GenerateMesh")
    canceller.stop()
    print("  cancel clicked during: {}".format(clicked))
    check(bool(clicked), "Cancel clicked during Generate mesh")
    check([o.Name for o in doc.Objects] == names and not errors,
          "cancelled Generate mesh added nothing and showed no message box: {}".format(errors))
    check(all("Invalid" not in o.State and "Error" not in o.State for o in objs.values()),
          "the document's objects are still valid")
    FreeCAD.closeDocument(doc.Name)

    # 4. A 15 degree knife edge: its automatic Polycube has prism blocks, and Build Polycube takes
    # them as they are.
    import math
    from HexDomWorkbench import api
    doc = FreeCAD.newDocument("MeshPartKnife")
    V = FreeCAD.Vector
    h = 40 * math.tan(math.radians(15))
    knife = doc.addObject("Part::Feature", "Knife")
    knife.Shape = Part.Face(Part.makePolygon([V(0, 0, 0), V(40, 0, 0), V(0, 0, h), V(0, 0, 0)])).extrude(
        V(0, 30, 0))
    doc.recompute()
    objs = api.mesh_part(doc, knife, level=1)
    poly, mesh = objs["polycube"], objs["mesh"]
    check(poly.PrismBlocks > 0 and mesh.PrismCount > 0 and mesh.InvertedCount == 0,
          "knife edge: {} hex and {} prism blocks, mesh {} hex {} prism, {} inverted".format(
              poly.HexBlocks, poly.PrismBlocks, mesh.HexCount, mesh.PrismCount, mesh.InvertedCount))
    edit_automatic_polycube(poly, mesh)
    check(not errors, "no message box on the knife edge: {}".format(errors))
    FreeCAD.closeDocument(doc.Name)

    # 5. A torus at size 10: the overlay grid's mesh is kept; the polycube objects stay editable.
    from HexDomWorkbench.commands import commands
    from HexDomWorkbench.taskpanels import task_polycube, task_segmentation
    doc = FreeCAD.newDocument("MeshPartTorus")
    torus = doc.addObject("Part::Feature", "Torus")
    torus.Shape = Part.makeTorus(30, 10)
    doc.recompute()
    errors.clear()
    objs = commands._MeshPart().mesh_part(torus, size=10.0)
    check(objs is not None and set(objs) == {"surface", "segmentation", "polycube", "mesh"},
          "Mesh part on the torus keeps the four objects: {}".format(sorted(objs or {})))
    if not objs or len(objs) != 4:
        return
    seg, poly, mesh = objs["segmentation"], objs["polycube"], objs["mesh"]
    print("  torus: {} hex, path {} ({})".format(mesh.HexCount, mesh.MeshingPath, mesh.PolycubeNote))
    check(not errors, "no message box on the torus: {}".format(errors))
    check(mesh.MeshingPath == "overlay" and "volume" in mesh.PolycubeNote
          and mesh.HexCount > 0 and mesh.InvertedCount == 0 and "Invalid" not in mesh.State,
          "the Mesh says the overlay grid made it, and why")
    check(mesh.Polycube is None and "Invalid" not in poly.State and poly.HexBlocks > 0,
          "the Polycube is kept, valid, unused by the Mesh")
    FreeCADGui.ActiveDocument.setEdit(seg.Name, 0)
    g.process_events()
    panel = task_segmentation.active_panel()
    check(panel is not None, "Edit Patches opens on the torus's Segmentation")
    if panel is not None:
        panel.reject()
        g.process_events()
    check(task_polycube.find_segmentation(poly) == seg,
          "the unused Polycube goes with its own Segmentation")
    counts = (mesh.HexCount, mesh.PrismCount, mesh.TetCount)
    edit_automatic_polycube(poly, mesh)
    check(mesh.MeshingPath == "overlay" and (mesh.HexCount, mesh.PrismCount, mesh.TetCount) == counts,
          "editing the Polycube leaves the overlay mesh as it was")
    check(not errors, "no message box while editing: {}".format(errors))
    FreeCAD.closeDocument(doc.Name)

    # 6. Cancel stops a running core call, not only the next stage.
    doc = FreeCAD.newDocument("MeshPartCancelInside")
    sphere = doc.addObject("Part::Feature", "Sphere")
    sphere.Shape = Part.makeSphere(40)
    doc.recompute()
    shown, click_at = {}, []

    def click_late():  # 1.5 s after the pipeline's dialog shows
        if click_at:
            return
        for w in QtGui.QApplication.topLevelWidgets():
            if w.objectName() == "HexDomProgress" and w.isVisible() and "hexdom mesh" in w.label.text():
                shown.setdefault("t", time.time())
                button = w.findChild(QtGui.QPushButton, "HexDomProgressCancel")
                if time.time() - shown["t"] > 1.5 and button is not None and button.isEnabled():
                    click_at.append(time.time())
                    button.click()

    errors.clear()
    canceller = QtCore.QTimer()
    canceller.timeout.connect(click_late)
    canceller.start(10)
    objs = commands._MeshPart().mesh_part(sphere, size=1.5)
    returned = time.time()
    canceller.stop()
    latency = returned - click_at[0] if click_at else float("nan")
    print("  cancel inside the core: returned {:.3f} s after the click".format(latency))
    check(bool(click_at) and latency < 3.0, "Mesh Part returns within 3 s of Cancel ({:.3f} s)".format(latency))
    check(not errors, "no message box after Cancel: {}".format(errors))
    surfaces = [o for o in doc.Objects if getattr(getattr(o, "Proxy", None), "Type", "") == "HexDom::Surface"]
    check(len(surfaces) == 1 and "Invalid" not in surfaces[0].State,
          "the Surface stays valid (empty: the pipeline was stopped before it filled it)")
    FreeCAD.closeDocument(doc.Name)
    mesh_object(action, errors)


def mesh_object(action, errors):
    """7. Mesh Part on an STL opened in FreeCAD."""
    import FreeCAD
    import FreeCADGui
    import Mesh
    import fc_testdata
    path = fc_testdata.write_stl(os.path.join(g.ARTIFACTS, "two_boxes.stl"),
                                 fc_testdata.box_triangles((0, 0, 0), (20, 20, 20))
                                 + fc_testdata.box_triangles((20, 5, 5), (30, 15, 15), reverse=True))
    doc = FreeCAD.newDocument("MeshPartStl")
    Mesh.insert(path, doc.Name)
    doc.recompute()
    opened = [o for o in doc.Objects if o.TypeId.startswith("Mesh::")]
    check(len(opened) == 1, "the STL opens as one mesh object")
    if not opened:
        return
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(opened[0])
    g.process_events()
    check(action.isEnabled(), "Mesh part is enabled with a mesh object selected")
    errors.clear()
    action.trigger()
    g.process_events()
    check(not errors, "no message box on the STL: {}".format(errors))
    meshes = [o for o in doc.Objects if getattr(getattr(o, "Proxy", None), "Type", "") == "HexDom::Mesh"]
    check(len(meshes) == 1 and len([o for o in doc.Objects if hasattr(getattr(o, "Proxy", None), "Type")]) == 4,
          "Mesh part on the mesh object adds four objects")
    if len(meshes) == 1:
        mesh = meshes[0]
        print("  STL: {} hex, {} prism, {} tet, regions {}".format(
            mesh.HexCount, mesh.PrismCount, mesh.TetCount, sorted(set(mesh.Region))))
        check(mesh.HexCount > 0 and mesh.InvertedCount == 0 and sorted(set(mesh.Region)) == [1, 2],
              "the mesh has both boxes, each its own region, no inverted cell")
        path = screenshot("mesh_part_stl.png", [mesh])
        drawn, _ = colour_shares(path, {})
        check(drawn > 0.05, "the STL's mesh shows")
    FreeCAD.closeDocument(doc.Name)


try:
    run()
except Exception:  # any error fails the test; the GUI must still exit
    traceback.print_exc()
    g.failures.append("exception")
g.finish()
