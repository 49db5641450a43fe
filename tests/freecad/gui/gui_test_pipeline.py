"""GUI test of the meshing pipeline, run by tests/freecad/run.sh as `freecad gui_test_pipeline.py`
under xvfb.

Runs the pipeline commands on sample documents (file dialogs and message boxes replaced by
stubs): HexDom_Tessellate on a Part solid, HexDom_Segment, HexDom_ImportPatches and
HexDom_ImportStructure on the bundled L-bracket, HexDom_GenerateMesh (from the selection and from
files), HexDom_ImproveQuality, HexDom_ExportStructure, and the error paths (message box, nothing
added). Saves screenshots under artifacts/: the CAD faces, the patches coloured by label from two
opposite sides, the polycube, the mesh; checks that each shows the colours it should. Prints
"GUI TEST PASSED" and exits 0, or lists the failures and exits 1; a watchdog exits 2 on a hang.
"""

import os
import sys
import tempfile
import threading
import traceback

TEST_DIR = os.environ.get("HEXDOM_FC_TEST_DIR") or os.path.dirname(
    os.path.dirname(os.path.abspath(__file__)))
ARTIFACTS = os.environ.get("HEXDOM_FC_ARTIFACTS", os.path.join(TEST_DIR, "artifacts"))
sys.path.insert(0, TEST_DIR)

_watchdog = threading.Timer(160.0, lambda: (print("GUI TEST TIMED OUT"), sys.stdout.flush(),
                                            os._exit(2)))
_watchdog.daemon = True
_watchdog.start()

failures = []

# Hues (degrees) of the label colours of the Segmentation view and of the block / cell types.
LABEL_HUES = {"+X red": 0, "-X cyan": 183, "+Y green": 120, "-Y magenta": 300, "+Z blue": 228,
              "-Z yellow": 54}
TYPE_HUES = {"hex blue": 215, "prism orange": 35}


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)
    return condition


def process_events(times=5):
    from PySide import QtGui
    for _ in range(times):
        QtGui.QApplication.processEvents()


def show_only(doc, objs):
    for o in doc.Objects:
        if getattr(o, "ViewObject", None) is not None:
            o.ViewObject.Visibility = o in objs


def screenshot(name, direction=None, width=800, height=600):
    import FreeCAD
    import FreeCADGui
    process_events()
    view = FreeCADGui.ActiveDocument.ActiveView
    view.viewIsometric()
    if direction is not None:
        process_events()
        view.setViewDirection(tuple(float(c) for c in direction))
        process_events()
        d = view.getViewDirection()
        check(FreeCAD.Vector(*direction).normalize().dot(d) > 0.99,
              "{}: camera looks along {}".format(name, direction))
    view.fitAll()
    process_events()
    path = os.path.join(ARTIFACTS, name)
    view.saveImage(path, width, height, "White")
    return path


def colour_census(path, hues, tolerance=16, min_saturation=0.35):
    """Fraction of non-background pixels, and of those the fraction near each named hue."""
    from PySide import QtGui
    img = QtGui.QImage(path)
    counts = dict.fromkeys(hues, 0)
    drawn = dark = total = 0
    for y in range(0, img.height(), 2):
        for x in range(0, img.width(), 2):
            c = QtGui.QColor(img.pixel(x, y))
            total += 1
            if c.red() > 245 and c.green() > 245 and c.blue() > 245:
                continue
            drawn += 1
            h, s, v, _ = c.getHsvF()
            if v < 0.3:
                dark += 1
            if not hues or s < min_saturation or v < 0.2 or h < 0:
                continue
            deg = h * 360.0
            dist = {k: min(abs(deg - hv), 360 - abs(deg - hv)) for k, hv in hues.items()}
            name = min(dist, key=dist.get)
            if dist[name] < tolerance:
                counts[name] += 1
    share = {k: v / max(drawn, 1) for k, v in counts.items()}
    share["dark"] = dark / max(drawn, 1)
    return drawn / total, share


def report(name, drawn, share):
    print("  {}: drawn {:.3f} {}".format(name, drawn, {k: round(v, 3) for k, v in share.items()}))


def hue_buckets(path, bucket=30):
    """Number of distinct 30-degree hue buckets holding at least 1% of the drawn pixels."""
    from PySide import QtGui
    img = QtGui.QImage(path)
    counts, drawn = {}, 0
    for y in range(0, img.height(), 2):
        for x in range(0, img.width(), 2):
            c = QtGui.QColor(img.pixel(x, y))
            if c.red() > 245 and c.green() > 245 and c.blue() > 245:
                continue
            drawn += 1
            h, s, v, _ = c.getHsvF()
            if s >= 0.3 and v >= 0.3 and h >= 0:
                counts[int(h * 360) // bucket] = counts.get(int(h * 360) // bucket, 0) + 1
    return len([b for b, n in counts.items() if n > 0.01 * max(drawn, 1)])


def run():
    import FreeCAD
    import FreeCADGui
    import Part
    from PySide import QtGui

    import fc_testdata

    os.makedirs(ARTIFACTS, exist_ok=True)
    work = tempfile.mkdtemp(prefix="hexdom-gui-pipeline-")
    patches_k = os.path.abspath(fc_testdata.example_path("lbracket_patches.k"))
    structure_k = os.path.abspath(fc_testdata.example_path("lbracket_structure.k"))

    FreeCADGui.activateWorkbench("HexDomWorkbench")
    process_events()
    names = ["HexDom_Tessellate", "HexDom_Segment", "HexDom_ImportPatches",
             "HexDom_ImportStructure", "HexDom_GenerateMesh", "HexDom_ImproveQuality",
             "HexDom_ExportStructure"]
    missing = [n for n in names if n not in FreeCADGui.listCommands()]
    check(not missing, "pipeline commands registered (missing: {})".format(missing))
    bars = [b.windowTitle() for b in FreeCADGui.getMainWindow().findChildren(QtGui.QToolBar)]
    check("HexDom pipeline" in bars and "HexDom" in bars, "both HexDom toolbars present")
    from HexDomWorkbench import paths
    for n in names:
        cmd = FreeCADGui.Command.get(n) if hasattr(FreeCADGui, "Command") else None
        info = cmd.getInfo() if cmd is not None and hasattr(cmd, "getInfo") else {}
        tip = info.get("toolTip", "") if info else ""
        check(os.path.isfile(paths.icon(n)) and (not info or len(tip) > 20),
              "{} has an icon and a tooltip".format(n))

    errors = []
    next_open, next_save = [], []
    QtGui.QFileDialog.getOpenFileName = staticmethod(lambda *a, **k: (next_open.pop(0), ""))
    QtGui.QFileDialog.getSaveFileName = staticmethod(lambda *a, **k: next_save.pop(0))
    QtGui.QMessageBox.critical = staticmethod(lambda parent, title, text, *a: errors.append(
        (title, text)))

    from HexDomWorkbench import api, core
    from HexDomWorkbench.objects import hex_mesh
    from HexDomWorkbench.viewproviders import (view_hex_mesh, view_polycube, view_segmentation,
                                               view_tessellation)

    def of_type(doc, type_name):
        return [o for o in doc.Objects
                if getattr(getattr(o, "Proxy", None), "Type", None) == type_name]

    # 1. A Part solid with planar and curved faces -> HexDom_Tessellate.
    doc = FreeCAD.newDocument("PipelinePart")
    shape = Part.makeBox(30, 12, 6).fuse(Part.makeBox(8, 12, 24)).removeSplitter()
    shape = shape.cut(Part.makeCylinder(2.5, 8, FreeCAD.Vector(0, 6, 16), FreeCAD.Vector(1, 0, 0)))
    shape = shape.cut(Part.makeCylinder(2.5, 6, FreeCAD.Vector(20, 6, 0)))
    part = doc.addObject("Part::Feature", "Bracket")
    part.Shape = shape
    doc.recompute()
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(part)
    check(FreeCADGui.isCommandActive("HexDom_Tessellate"), "tessellate active on a Part solid")
    check(not FreeCADGui.isCommandActive("HexDom_Segment"), "segment inactive on a Part solid")
    FreeCADGui.runCommand("HexDom_Tessellate")
    process_events()
    surfaces = of_type(doc, "HexDom::Surface")
    if check(len(surfaces) == 1, "HexDom_Tessellate creates one HexDom Surface"):
        surf = surfaces[0]
        check(isinstance(surf.ViewObject.Proxy, view_tessellation.VPSurface),
              "Surface view provider attached")
        check(surf.FaceCount == len(shape.Faces) and surf.TriangleCount > 500,
              "every CAD face tessellated: {} faces, {} triangles ({})".format(
                  surf.FaceCount, surf.TriangleCount, surf.Method))
        check(not part.ViewObject.Visibility, "the source part is hidden")
        show_only(doc, [surf])
        path = screenshot("surface_by_face.png")
        drawn, _ = colour_census(path, {})
        buckets = hue_buckets(path)
        print("  surface by face: drawn {:.3f}, {} hue buckets".format(drawn, buckets))
        check(drawn > 0.05 and buckets >= 4, "surface drawn with one colour per CAD face")
        surf.ViewObject.DisplayMode = "Flat Lines"
        screenshot("surface_flat_lines.png")
        surf.ViewObject.DisplayMode = "Shaded"

        # 2. HexDom_Segment: core.segment when built in, else a message box.
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(surf)
        check(FreeCADGui.isCommandActive("HexDom_Segment"), "segment active on a Surface")
        count = len(doc.Objects)
        errors.clear()
        FreeCADGui.runCommand("HexDom_Segment")
        process_events()
        if api.has_segmentation():
            segs = of_type(doc, "HexDom::Segmentation")
            check(len(segs) == 1 and "Invalid" not in segs[0].State,
                  "HexDom_Segment makes a Segmentation")
            if segs:
                show_only(doc, segs)
                screenshot("part_segmentation_by_label.png")
        else:
            check(len(errors) == 1 and "segmentation not available in this build" in errors[0][1],
                  "without core.segment: message box {}".format(errors))
            check(len(doc.Objects) == count, "nothing added when segmentation is missing")
    FreeCAD.closeDocument(doc.Name)
    process_events()

    # 3. The bundled L-bracket: patches and structure from files.
    doc = FreeCAD.newDocument("PipelineBracket")
    errors.clear()
    next_open.append(patches_k)
    FreeCADGui.runCommand("HexDom_ImportPatches")
    process_events()
    segs = of_type(doc, "HexDom::Segmentation")
    check(len(segs) == 1 and len(of_type(doc, "HexDom::Surface")) == 1,
          "HexDom_ImportPatches makes a Surface and a Segmentation")
    seg = segs[0]
    check(isinstance(seg.ViewObject.Proxy, view_segmentation.VPSegmentation),
          "Segmentation view provider attached")
    check(seg.PatchCount == 17 and seg.ViewObject.ColorBy == "Label",
          "17 patches, coloured by label")
    show_only(doc, [seg])
    front = screenshot("patches_by_label.png")
    drawn, share = colour_census(front, LABEL_HUES)
    report("patches, isometric", drawn, share)
    check(drawn > 0.05, "patch screenshot is not blank")
    # FreeCAD's isometric view looks along (-1, 1, -1): the +X, -Y and +Z sides face the camera.
    for name in ("+X red", "-Y magenta", "+Z blue"):
        check(share[name] > 0.03, "{} patches seen from the front ({:.3f})".format(
            name, share[name]))
    check(share["dark"] > 0.003, "patch boundaries drawn as lines")
    back = screenshot("patches_by_label_back.png", direction=(1, -1, 1))
    drawn, share = colour_census(back, LABEL_HUES)
    report("patches, opposite side", drawn, share)
    for name in ("-X cyan", "+Y green", "-Z yellow"):
        check(share[name] > 0.03, "{} patches seen from behind ({:.3f})".format(
            name, share[name]))
    seg.ViewObject.ColorBy = "Patch"
    by_patch = screenshot("patches_by_patch.png")
    check(hue_buckets(by_patch) >= 4, "colour by patch gives many colours")
    seg.ViewObject.ColorBy = "Label"

    errors.clear()
    next_open.append(structure_k)
    FreeCADGui.runCommand("HexDom_ImportStructure")
    process_events()
    polys = of_type(doc, "HexDom::Polycube")
    check(len(polys) == 1, "HexDom_ImportStructure makes a Polycube")
    poly = polys[0]
    check(isinstance(poly.ViewObject.Proxy, view_polycube.VPPolycube),
          "Polycube view provider attached")
    check((poly.HexBlocks, poly.PrismBlocks) == (3, 1), "3 hex blocks and 1 prism block")
    check("Import structure" in doc.UndoNames, "the import is one undoable transaction")
    show_only(doc, [poly])
    path = screenshot("polycube.png")
    drawn, share = colour_census(path, TYPE_HUES, min_saturation=0.2)
    report("polycube", drawn, share)
    check(drawn > 0.05 and share["hex blue"] > 0.05 and share["prism orange"] > 0.01,
          "polycube faces drawn blue (hex) and orange (prism)")
    check(share["dark"] > 0.01, "block wireframe drawn")
    poly.ViewObject.DisplayMode = "Wireframe"
    screenshot("polycube_wireframe.png")
    poly.ViewObject.DisplayMode = "Transparent"

    # 4. HexDom_GenerateMesh from the selected Segmentation and Polycube.
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(seg)
    FreeCADGui.Selection.addSelection(poly)
    FreeCADGui.runCommand("HexDom_GenerateMesh")
    process_events()
    meshes = [o for o in doc.Objects if hex_mesh.is_hex_mesh(o)]
    check(len(meshes) == 1 and not errors, "HexDom_GenerateMesh makes a HexDom Mesh {}".format(
        errors))
    mesh = meshes[0]
    check((mesh.HexCount, mesh.PrismCount, mesh.InvertedCount) == (192, 64, 0),
          "192 hex + 64 prism, none inverted: {} {} {}".format(
              mesh.HexCount, mesh.PrismCount, mesh.InvertedCount))
    check(mesh.Segmentation == seg and mesh.Polycube == poly and mesh.Improve,
          "mesh links its inputs and is improved")
    check(isinstance(mesh.ViewObject.Proxy, view_hex_mesh.VPHexMesh), "mesh view provider")
    children = mesh.ViewObject.Proxy.claimChildren()
    check(seg in children and poly in children, "inputs sit under the mesh in the tree")
    show_only(doc, [mesh])
    path = screenshot("lbracket_mesh.png")
    drawn, share = colour_census(path, TYPE_HUES, min_saturation=0.2)
    report("mesh", drawn, share)
    check(drawn > 0.05 and share["hex blue"] > 0.2 and share["prism orange"] > 0.02,
          "mesh drawn with blue hexes and orange prisms")

    # 5. HexDom_ImproveQuality on a generated mesh that is not improved yet.
    mesh.Improve = False
    doc.recompute()
    raw = (mesh.MinHexSJ, mesh.MinPrismSJ)
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(mesh)
    check(FreeCADGui.isCommandActive("HexDom_ImproveQuality"), "improve active on the mesh")
    FreeCADGui.runCommand("HexDom_ImproveQuality")
    process_events()
    check(mesh.Improve and (mesh.MinHexSJ, mesh.MinPrismSJ) != raw and mesh.InvertedCount == 0,
          "HexDom_ImproveQuality switches Improve on: min SJ {} -> {}".format(
              [round(v, 3) for v in raw], [round(mesh.MinHexSJ, 3), round(mesh.MinPrismSJ, 3)]))

    # 6. HexDom_ExportStructure.
    out = os.path.join(work, "exported_structure.k")
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(poly)
    next_save.append((out, "LS-DYNA keyword (*.k)"))
    FreeCADGui.runCommand("HexDom_ExportStructure")
    process_events()
    check(os.path.isfile(out) and core.read_mesh(out).counts["hex"] == 3,
          "HexDom_ExportStructure writes a readable .k")

    # 7. Errors: message boxes, nothing added.
    broken = os.path.join(work, "broken.k")
    with open(broken, "w") as f:
        f.write("*KEYWORD\n*ELEMENT_SOLID\n1 1 1 2\n*END\n")
    count = len(doc.Objects)
    errors.clear()
    next_open.append(broken)
    FreeCADGui.runCommand("HexDom_ImportStructure")
    process_events()
    check(len(errors) == 1 and "broken.k" in errors[0][1],
          "a broken structure file gives a message box: {}".format(errors))
    check(len(doc.Objects) == count, "failed import adds nothing")

    cube = os.path.join(work, "cube.k")
    V, cells, types = fc_testdata.box_structure(1.0, 1.0, 1.0)
    import numpy as np
    core.write_mesh(cube, core.Mesh(V, cells, types, np.ones(1, np.int32)))
    FreeCADGui.Selection.clearSelection()
    errors.clear()
    next_open.extend([patches_k, cube])
    FreeCADGui.runCommand("HexDom_GenerateMesh")
    process_events()
    check(len(errors) == 1 and "structure" in errors[0][1],
          "patches that do not fit the structure give a message box: {}".format(errors))
    check(len(doc.Objects) == count, "the failed generation is rolled back")
    check(all("Invalid" not in o.State for o in doc.Objects), "no object left invalid")

    # 8. HexDom_GenerateMesh from files, nothing selected.
    errors.clear()
    next_open.extend([patches_k, structure_k])
    FreeCADGui.runCommand("HexDom_GenerateMesh")
    process_events()
    meshes = [o for o in doc.Objects if hex_mesh.is_hex_mesh(o)]
    check(len(meshes) == 2 and not errors, "HexDom_GenerateMesh from files: {}".format(errors))
    if len(meshes) == 2:
        check((meshes[1].HexCount, meshes[1].PrismCount) == (192, 64),
              "the mesh from files has 192 hex + 64 prism")

    # 9. Save and reopen: view providers and colours come back.
    seg_name, poly_name = seg.Name, poly.Name
    path = os.path.join(work, "pipeline.FCStd")
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    process_events()
    doc = FreeCAD.openDocument(path)
    process_events()
    seg, poly = doc.getObject(seg_name), doc.getObject(poly_name)
    check(isinstance(seg.ViewObject.Proxy, view_segmentation.VPSegmentation)
          and isinstance(poly.ViewObject.Proxy, view_polycube.VPPolycube),
          "view providers restored")
    show_only(doc, [seg])
    drawn, share = colour_census(screenshot("patches_reopened.png"), LABEL_HUES)
    report("patches after reopening", drawn, share)
    check(drawn > 0.05 and share["+X red"] > 0.03 and share["+Z blue"] > 0.03,
          "reopened segmentation drawn by label")
    show_only(doc, [poly])
    drawn, share = colour_census(screenshot("polycube_reopened.png"), TYPE_HUES,
                                 min_saturation=0.2)
    check(drawn > 0.05 and share["hex blue"] > 0.05, "reopened polycube drawn")
    FreeCAD.closeDocument(doc.Name)


rc = 1
try:
    run()
    rc = 0 if not failures else 1
except Exception:  # any error fails the test; the GUI must still exit
    traceback.print_exc()
    failures.append("exception")
print("GUI TEST PASSED" if rc == 0 else "GUI TEST FAILED: {}".format(failures))
sys.stdout.flush()
sys.stderr.flush()
os._exit(rc)
