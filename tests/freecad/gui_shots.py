"""Helpers of the GUI test scripts (run inside freecad under xvfb): event processing, checks that
count, and screenshots of a task panel beside the 3D view.

The main window's grab() leaves the OpenGL view blank, so a dialog picture is composed: the 3D
view from View3DInventor.saveImage (offscreen rendering) on the right, the panel's own grab() on
the left, as FreeCAD lays them out.
"""

import os
import sys
import threading

TEST_DIR = os.environ.get("HEXDOM_FC_TEST_DIR") or os.path.dirname(os.path.abspath(__file__))
ARTIFACTS = os.environ.get("HEXDOM_FC_ARTIFACTS", os.path.join(TEST_DIR, "artifacts"))

failures = []


def start_watchdog(seconds):
    timer = threading.Timer(seconds, lambda: (print("GUI TEST TIMED OUT"), sys.stdout.flush(),
                                              os._exit(2)))
    timer.daemon = True
    timer.start()
    return timer


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    sys.stdout.flush()
    if not condition:
        failures.append(message)
    return condition


def skip(message):
    print("SKIP " + message)
    sys.stdout.flush()


def process_events(times=5):
    from PySide import QtGui
    for _ in range(times):
        QtGui.QApplication.processEvents()


def set_task_width(width=430):
    """Widens the Combo View dock (where task panels live) to ``width`` pixels."""
    import FreeCADGui
    from PySide import QtCore, QtGui
    mw = FreeCADGui.getMainWindow()
    mw.resize(1280, 1000)
    docks = [d for d in mw.findChildren(QtGui.QDockWidget)
             if d.objectName() in ("Combo View", "ComboView") and d.isVisible()]
    if docks and hasattr(mw, "resizeDocks"):
        mw.resizeDocks(docks, [width], QtCore.Qt.Horizontal)
    process_events()


def _viewport_and_scale():
    """(the 3D view's OpenGL widget, Coin pixels per widget pixel)."""
    import FreeCADGui
    view = FreeCADGui.ActiveDocument.ActiveView
    widget = view.graphicsView().viewport()
    region = view.getViewer().getSoRenderManager().getViewportRegion()
    w, h = region.getViewportSizePixels().getValue()
    return widget, w / float(widget.width()), h


def _park_cursor():
    """Puts the (virtual) pointer in the screen's corner, off the 3D view: when widgets change,
    Qt sends the widget under the pointer a synthetic move with the real (released) buttons,
    which would end a drag made of sent events half-way."""
    from PySide import QtGui
    QtGui.QCursor.setPos(0, 0)
    process_events()


def _send_mouse(kind, x, y, buttons):
    """A Qt mouse event at Coin pixel (x, y) (origin lower left) on the 3D view."""
    from PySide import QtCore, QtGui
    widget, scale, h = _viewport_and_scale()
    pos = QtCore.QPointF(x / scale, (h - y) / scale)
    button = QtCore.Qt.NoButton if kind == QtCore.QEvent.MouseMove else QtCore.Qt.LeftButton
    event = QtGui.QMouseEvent(kind, pos, button, buttons, QtCore.Qt.NoModifier)
    QtGui.QApplication.sendEvent(widget, event)


def mouse_click(x, y):
    """Presses and releases the left button at Coin pixel (x, y) of the 3D view, as a user
    would (the event goes through Qt, Quarter and Coin to the event callbacks)."""
    _park_cursor()
    from PySide import QtCore
    _send_mouse(QtCore.QEvent.MouseButtonPress, x, y, QtCore.Qt.LeftButton)
    _send_mouse(QtCore.QEvent.MouseButtonRelease, x, y, QtCore.Qt.NoButton)
    process_events()


def mouse_drag(a, b, steps=6):
    """Drags with the left button from Coin pixel ``a`` to ``b`` on the 3D view."""
    _park_cursor()
    from PySide import QtCore
    _send_mouse(QtCore.QEvent.MouseButtonPress, a[0], a[1], QtCore.Qt.LeftButton)
    for k in range(1, steps + 1):
        x = a[0] + (b[0] - a[0]) * k / steps
        y = a[1] + (b[1] - a[1]) * k / steps
        _send_mouse(QtCore.QEvent.MouseMove, x, y, QtCore.Qt.LeftButton)
    _send_mouse(QtCore.QEvent.MouseButtonRelease, b[0], b[1], QtCore.Qt.NoButton)
    process_events()


def mouse_path(points, before_release=None):
    """Presses the left button at the first of ``points`` (Coin pixels), moves through the
    others and releases at the last: a lasso drawn by hand. ``before_release()`` runs with the
    button still down (to take a picture of the drawing)."""
    _park_cursor()
    from PySide import QtCore
    _send_mouse(QtCore.QEvent.MouseButtonPress, points[0][0], points[0][1], QtCore.Qt.LeftButton)
    for x, y in points[1:]:
        _send_mouse(QtCore.QEvent.MouseMove, x, y, QtCore.Qt.LeftButton)
    if before_release is not None:
        before_release()
    _send_mouse(QtCore.QEvent.MouseButtonRelease, points[-1][0], points[-1][1],
                QtCore.Qt.NoButton)
    process_events()


def key_click(sequence, widget=None):
    """Types ``sequence`` ("Ctrl+Z") on ``widget`` (default: the 3D view, focused) as a key press
    and release. The press goes through Qt's shortcut map first, as a key typed by the user."""
    from PySide import QtCore, QtGui
    if widget is None:
        widget, _, _ = _viewport_and_scale()
        widget.setFocus()
    combined = QtGui.QKeySequence(sequence)[0]
    modifiers = QtCore.Qt.KeyboardModifiers(combined & int(QtCore.Qt.KeyboardModifierMask))
    key = combined & ~int(QtCore.Qt.KeyboardModifierMask)
    for kind in (QtCore.QEvent.KeyPress, QtCore.QEvent.KeyRelease):
        QtGui.QApplication.sendEvent(widget, QtGui.QKeyEvent(kind, key, modifiers))
    process_events()


def menu_action(menu_title, object_name):
    """The action named ``object_name`` in the main window's menu ``menu_title`` ("&Edit"), or
    None."""
    import FreeCADGui
    from PySide import QtGui
    bar = FreeCADGui.getMainWindow().menuBar()
    for top in bar.actions():
        menu = top.menu()
        if menu is None or top.text().replace("&", "") != menu_title.replace("&", ""):
            continue
        for action in menu.actions():
            if action.objectName() == object_name:
                return action
    return None


def view_image(name, width=760, height=620):
    """Saves the active 3D view (as it is, no refit) to artifacts/<name>; returns the path."""
    import FreeCADGui
    process_events()
    os.makedirs(ARTIFACTS, exist_ok=True)
    path = os.path.join(ARTIFACTS, name)
    FreeCADGui.ActiveDocument.ActiveView.saveImage(path, width, height, "White")
    return path


def compose(name, panel_widget, view_width=760, view_height=None):
    """artifacts/<name>: the task panel (grabbed) on the left, the 3D view (rendered at the
    panel's height unless given) on the right. Returns the path."""
    from PySide import QtCore, QtGui
    process_events()
    panel = panel_widget.grab()
    height = view_height or max(panel.height(), 480)
    view_path = view_image("_view_" + name, view_width, height)
    view = QtGui.QImage(view_path)
    out = QtGui.QImage(panel.width() + view.width() + 6, max(panel.height(), view.height()),
                       QtGui.QImage.Format_RGB32)
    out.fill(QtGui.QColor(255, 255, 255))
    p = QtGui.QPainter(out)
    p.fillRect(QtCore.QRect(0, 0, panel.width(), out.height()), QtGui.QColor(239, 239, 239))
    p.drawPixmap(0, 0, panel)
    p.setPen(QtGui.QColor(160, 160, 160))
    p.drawLine(panel.width() + 2, 0, panel.width() + 2, out.height())
    p.drawImage(panel.width() + 6, 0, view)
    p.end()
    path = os.path.join(ARTIFACTS, name)
    out.save(path)
    os.remove(view_path)
    return path


def drawn_fraction(path, colour=None, tolerance=40, region=None):
    """Fraction of sampled pixels (every third) that are not white background, or (with
    ``colour``) near that RGB; ``region`` (x0, y0, x1, y1) limits the count to part of the
    image."""
    from PySide import QtGui
    img = QtGui.QImage(path)
    x0, y0, x1, y1 = region or (0, 0, img.width(), img.height())
    hits = total = 0
    for y in range(y0, min(y1, img.height()), 3):
        for x in range(x0, min(x1, img.width()), 3):
            c = QtGui.QColor(img.pixel(x, y))
            rgb = (c.red(), c.green(), c.blue())
            total += 1
            if colour is None:
                hits += not all(v > 245 for v in rgb)
            else:
                hits += all(abs(a - b) <= tolerance for a, b in zip(rgb, colour))
    return hits / max(total, 1)


def changed_to(path_a, path_b, colour, tolerance=8):
    """Fraction of sampled pixels that are near ``colour`` in image a but not in image b (the
    same view before and after a change)."""
    from PySide import QtGui
    a, b = QtGui.QImage(path_a), QtGui.QImage(path_b)
    hits = total = 0
    for y in range(0, min(a.height(), b.height()), 2):
        for x in range(0, min(a.width(), b.width()), 2):
            total += 1
            ca, cb = QtGui.QColor(a.pixel(x, y)), QtGui.QColor(b.pixel(x, y))
            near_a = all(abs(u - v) <= tolerance for u, v in zip(
                (ca.red(), ca.green(), ca.blue()), colour))
            near_b = all(abs(u - v) <= tolerance for u, v in zip(
                (cb.red(), cb.green(), cb.blue()), colour))
            hits += near_a and not near_b
    return hits / max(total, 1)


def finish():
    """Prints the verdict and leaves FreeCAD with its exit code (os._exit: the GUI would
    otherwise keep running)."""
    rc = 0 if not failures else 1
    print("GUI TEST PASSED" if rc == 0 else "GUI TEST FAILED: {}".format(failures))
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(rc)
