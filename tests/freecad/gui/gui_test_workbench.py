"""GUI test, run by tests/freecad/run.sh as `freecad gui_test_workbench.py` under xvfb.

Activates the workbench, runs every command on a sample document (file dialogs and message
boxes are replaced by stubs), saves screenshots of the mesh coloured by cell type and by scaled
Jacobian under artifacts/, and checks that they are not blank and show the expected colours.
Prints "GUI TEST PASSED" and exits 0, or lists the failures and exits 1 (os._exit: FreeCAD's GUI
would otherwise keep running). A watchdog exits 2 if anything hangs.
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

_watchdog = threading.Timer(150.0, lambda: (print("GUI TEST TIMED OUT"), sys.stdout.flush(),
                                            os._exit(2)))
_watchdog.daemon = True
_watchdog.start()

failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)
    return condition


def process_events(times=5):
    from PySide import QtGui
    for _ in range(times):
        QtGui.QApplication.processEvents()


def screenshot(name, width=800, height=600):
    import FreeCADGui
    process_events()
    view = FreeCADGui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    process_events()
    path = os.path.join(ARTIFACTS, name)
    view.saveImage(path, width, height, "White")
    return path


def colour_census(path):
    """Fractions of non-background pixels and of pixels near each named hue."""
    from PySide import QtGui
    img = QtGui.QImage(path)
    hues = {"blue": 215, "orange": 35, "magenta": 300, "green": 110, "yellow": 65, "red": 10}
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
            if s < 0.35 or v < 0.2 or h < 0:
                continue
            deg = h * 360.0
            name = min(hues, key=lambda k: min(abs(deg - hues[k]), 360 - abs(deg - hues[k])))
            if min(abs(deg - hues[name]), 360 - abs(deg - hues[name])) < 18:
                counts[name] += 1
    return drawn / total, {k: v / max(drawn, 1) for k, v in counts.items()}


def run():
    import FreeCAD
    import FreeCADGui
    import ObjectsFem
    from PySide import QtGui

    import fc_testdata

    os.makedirs(ARTIFACTS, exist_ok=True)
    work = tempfile.mkdtemp(prefix="hexdom-gui-")

    # Workbench and commands.
    FreeCADGui.activateWorkbench("HexDomWorkbench")
    process_events()
    check(FreeCADGui.activeWorkbench().name() == "HexDomWorkbench", "workbench activates")
    names = ["HexDom_ImportMesh", "HexDom_QualityReport", "HexDom_ExportMesh",
             "HexDom_AddToAnalysis"]
    check(all(n in FreeCADGui.listCommands() for n in names), "all four commands registered")
    bars = [b.windowTitle() for b in FreeCADGui.getMainWindow().findChildren(QtGui.QToolBar)]
    check("HexDom" in bars, "HexDom toolbar present")

    # Stubs for the dialogs the commands open.
    errors = []
    next_open, next_save = [], []
    QtGui.QFileDialog.getOpenFileName = staticmethod(lambda *a, **k: (next_open.pop(0), ""))
    QtGui.QFileDialog.getSaveFileName = staticmethod(lambda *a, **k: next_save.pop(0))
    QtGui.QMessageBox.critical = staticmethod(lambda parent, title, text, *a: errors.append(
        (title, text)))

    from HexDomWorkbench import core
    from HexDomWorkbench.objects import hex_mesh
    from HexDomWorkbench.viewproviders import view_hex_mesh

    sample = os.path.join(work, "sample.vtk")
    core.write_mesh(sample, core.Mesh(*fc_testdata.mixed_sample()))
    doc = FreeCAD.newDocument("GuiSample")
    next_open.append(sample)
    FreeCADGui.runCommand("HexDom_ImportMesh")
    process_events()
    meshes = [o for o in doc.Objects if hex_mesh.is_hex_mesh(o)]
    check(len(meshes) == 1, "HexDom_ImportMesh creates one HexDom Mesh")
    obj = meshes[0]
    check(isinstance(obj.ViewObject.Proxy, view_hex_mesh.VPHexMesh), "view provider attached")
    check(obj.ViewObject.ColorBy == "Cell type", "coloured by cell type by default")
    check(not errors, "no error boxes so far {}".format(errors))

    by_type = screenshot("sample_by_type.png")
    window = FreeCADGui.getMainWindow()
    window.resize(1200, 900)
    process_events()
    check(window.grab().save(os.path.join(ARTIFACTS, "main_window.png")),
          "main window (toolbar, tree icons) saved")
    drawn, share = colour_census(by_type)
    print("  by type: drawn {:.3f} {}".format(drawn, {k: round(v, 3) for k, v in share.items()}))
    check(drawn > 0.05, "type screenshot is not blank")
    check(share["blue"] > 0.05, "hexes drawn blue")
    check(share["orange"] > 0.05, "prisms drawn orange")
    check(share["magenta"] > 0.05, "tets drawn magenta")

    obj.ViewObject.ColorBy = "Scaled Jacobian"
    by_sj = screenshot("sample_by_quality.png")
    drawn, share = colour_census(by_sj)
    print("  by SJ: drawn {:.3f} {}".format(drawn, {k: round(v, 3) for k, v in share.items()}))
    check(drawn > 0.05, "quality screenshot is not blank")
    check(share["green"] + share["yellow"] > 0.3, "good cells drawn green / yellow")
    check(share["blue"] < 0.01 and share["magenta"] < 0.01, "no type colours in quality mode")

    obj.ViewObject.ColorBy = "Plain"
    plain = screenshot("sample_plain.png")
    drawn, share = colour_census(plain)
    check(share["blue"] < 0.01 and share["magenta"] < 0.01, "plain mode drops the colours")
    obj.ViewObject.ColorBy = "Cell type"

    # Quality report.
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(obj)
    check(FreeCADGui.isCommandActive("HexDom_QualityReport"), "quality report active on mesh")
    FreeCADGui.runCommand("HexDom_QualityReport")
    process_events()
    dialogs = [w for w in QtGui.QApplication.topLevelWidgets()
               if w.objectName() == "HexDomQualityDialog" and w.isVisible()]
    if check(len(dialogs) == 1, "quality dialog shown"):
        text = dialogs[0].text.toPlainText()
        check("Hexahedra" in text and "Tetrahedra" in text and "0.577" in text,
              "report lists the types and the tet scaled Jacobian")
        dialogs[0].grab().save(os.path.join(ARTIFACTS, "quality_dialog.png"))
        dialogs[0].close()
        process_events()

    # Export.
    out = os.path.join(work, "exported.vtu")
    next_save.append((out, "VTK XML (*.vtu)"))
    FreeCADGui.runCommand("HexDom_ExportMesh")
    process_events()
    from HexDomWorkbench import fileio
    check(os.path.isfile(out) and fileio.read_mesh(out).counts["tet"] == 6,
          "HexDom_ExportMesh writes a readable .vtu")
    bad_out = os.path.join(work, "exported.unknown")
    next_save.append((bad_out, "Nothing (*.unknown)"))
    FreeCADGui.runCommand("HexDom_ExportMesh")
    process_events()
    check(os.path.isfile(bad_out + ".vtk") and not os.path.exists(bad_out),
          "export adds the extension of the chosen filter when none is known")

    # Add to analysis.
    check(not FreeCADGui.isCommandActive("HexDom_AddToAnalysis"), "add-to-analysis needs one")
    analysis = ObjectsFem.makeAnalysis(doc, "Analysis")
    import FemGui
    FemGui.setActiveAnalysis(analysis)
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(obj)
    process_events()
    check(FreeCADGui.isCommandActive("HexDom_AddToAnalysis"), "add-to-analysis active")
    FreeCADGui.runCommand("HexDom_AddToAnalysis")
    process_events()
    check(obj in analysis.Group, "HexDom_AddToAnalysis puts the mesh into the analysis")
    next_open.append(sample)
    FreeCADGui.runCommand("HexDom_ImportMesh")
    process_events()
    second = [o for o in doc.Objects if hex_mesh.is_hex_mesh(o) and o is not obj][0]
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(second)
    errors.clear()
    FreeCADGui.runCommand("HexDom_AddToAnalysis")
    process_events()
    check(len(errors) == 1 and "already holds the mesh" in errors[0][1],
          "a second mesh is refused with a message box: {}".format(errors))
    check(second not in analysis.Group, "refused mesh stays out of the analysis")

    # Errors from core become message boxes, the document is untouched.
    broken = os.path.join(work, "broken.k")
    with open(broken, "w") as f:
        f.write("*KEYWORD\n*ELEMENT_SOLID\n1 1 1 2\n*END\n")
    count = len(doc.Objects)
    errors.clear()
    next_open.append(broken)
    FreeCADGui.runCommand("HexDom_ImportMesh")
    process_events()
    check(len(errors) == 1 and "broken.k" in errors[0][1],
          "core.InputError shown in a message box: {}".format(errors))
    check(len(doc.Objects) == count, "failed import adds nothing")

    # Save and reopen: the view provider and its colouring come back.
    obj.ViewObject.ColorBy = "Scaled Jacobian"
    path = os.path.join(work, "gui_sample.FCStd")
    obj_name = obj.Name
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    process_events()
    doc = FreeCAD.openDocument(path)
    process_events()
    obj = doc.getObject(obj_name)
    check(isinstance(obj.ViewObject.Proxy, view_hex_mesh.VPHexMesh), "view provider restored")
    check(obj.ViewObject.ColorBy == "Scaled Jacobian", "ColorBy restored")
    for o in doc.Objects:
        if o is not obj and hex_mesh.is_hex_mesh(o):
            o.ViewObject.Visibility = False
    reopened = screenshot("sample_reopened_by_quality.png")
    drawn, share = colour_census(reopened)
    check(drawn > 0.05 and share["green"] + share["yellow"] > 0.3,
          "reopened document is drawn coloured by quality")
    FreeCAD.closeDocument(doc.Name)

    # The paper's rockerarm polycube structure, when present.
    rocker = fc_testdata.rockerarm_path()
    if rocker is None:
        print("SKIP rockerarm screenshots: paper data missing (set HEXDOM_DATA)")
    else:
        doc = FreeCAD.newDocument("Rockerarm")
        next_open.append(rocker)
        FreeCADGui.runCommand("HexDom_ImportMesh")
        obj = [o for o in doc.Objects if hex_mesh.is_hex_mesh(o)][0]
        drawn, share = colour_census(screenshot("rockerarm_by_type.png"))
        print("  rockerarm by type: {}".format({k: round(v, 3) for k, v in share.items()}))
        check(drawn > 0.05 and share["blue"] > 0.3 and share["orange"] > 0.005,
              "rockerarm drawn with blue hexes and orange prisms")
        obj.ViewObject.ColorBy = "Scaled Jacobian"
        drawn, share = colour_census(screenshot("rockerarm_by_quality.png"))
        print("  rockerarm by SJ: {}".format({k: round(v, 3) for k, v in share.items()}))
        check(share["green"] + share["yellow"] > 0.3 and share["red"] > 0.001,
              "rockerarm quality colours include good (green) and poor (red) cells")
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
