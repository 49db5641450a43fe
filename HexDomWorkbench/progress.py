"""Progress, a responsive GUI and cancellation for long core calls.

``with Progress("Meshing Part", 4) as bar: mesh = bar.run("generate", core.generate, ...)``

Without the GUI (scripts, freecadcmd, plain Python) ``run`` just calls the function. With the
GUI up, the outermost Progress shows FreeCAD's progress bar (Base.ProgressIndicator, one step per
``step``) and a modal dialog with the stage's text and a Cancel button; ``run`` calls the core
function in a worker thread (the bindings release the GIL around every long call) while the GUI
thread keeps processing events. Progress blocks nest: a command's Progress spans the recompute,
and the objects' own Progress blocks inside it share its dialog and its Cancel state.

Cancel stops the running core call within a fraction of a second: the worker runs it under the
session's core.Interrupt, which Cancel raises; the call ends with core.Interrupted, leaving its
inputs as they were, and ``run`` raises Cancelled (a call that returned meanwhile has its result
discarded); every later ``run`` in the same Progress raises Cancelled before it starts. The
document is never left half-written, because objects store results only after ``run`` returns.
"""

import threading

from . import core


class Cancelled(core.Error):
    """The user pressed Cancel; the stage's result was discarded."""


_sessions = []  # the active outermost Progress first


def current():
    """The outermost active Progress, or None."""
    return _sessions[0] if _sessions else None


def _gui_up():
    try:
        import FreeCAD
    except ImportError:
        return False
    return bool(FreeCAD.GuiUp)


class Progress:
    """Context manager: ``with Progress("Meshing", 3) as p: ...; p.run(text, fn, *args);
    p.step("improved")``. See the module doc."""

    def __init__(self, title, steps):
        self.title, self.steps, self.bar = title, steps, None
        self.dialog = None
        self.cancelled = False
        self.interrupt = core.Interrupt()  # raised by cancel(); the worker's core calls stop on it
        self.stage = ""
        self._outer = None

    # Sessions ------------------------------------------------------------------------------------

    def __enter__(self):
        outer = current()
        if outer is not None:
            self._outer = outer
            _sessions.append(self)
            return self
        _sessions.append(self)
        if _gui_up():
            import FreeCAD
            self.bar = FreeCAD.Base.ProgressIndicator()
            self.bar.start(self.title, max(1, int(self.steps)))
        return self

    def __exit__(self, *exc):
        _sessions.remove(self)
        if self._outer is not None:
            return False
        if self.bar is not None:
            self.bar.stop()
            self.bar = None
        if self.dialog is not None:
            self.dialog.hide()
            self.dialog.deleteLater()
            self.dialog = None
            _reactivate_main_window()
        return False

    @property
    def session(self):
        return self._outer or self

    def is_cancelled(self):
        return self.session.cancelled

    def cancel(self):
        """What the Cancel button does: the running stage's result is discarded when it returns,
        and no later stage starts."""
        s = self.session
        if not s.cancelled:
            s.cancelled = True
            s.interrupt.cancel()
            _log("{}: cancelling; stopping '{}'".format(s.title, s.stage))
            if s.dialog is not None:
                s.dialog.setLabelText("Cancelling {}...".format(s.stage))
                s.dialog.button.setEnabled(False)

    # Steps ---------------------------------------------------------------------------------------

    def step(self, text=None):
        if text:
            _log("{}: {}".format(self.title, text))
        s = self.session
        if s.bar is not None and s is self:
            s.bar.next()

    def run(self, text, fn, *args, **kwargs):
        """fn(*args, **kwargs), the stage called ``text``. With the GUI up it runs in a worker
        thread while the GUI stays responsive; raises Cancelled if the user cancels (before it
        starts, or while it runs: its result is then discarded)."""
        s = self.session
        if s.cancelled:
            raise Cancelled("{}: cancelled by the user before {}".format(s.title, text))
        s.stage = text
        if s.bar is None:  # no GUI: call directly
            return fn(*args, **kwargs)
        dialog = s._show_dialog()
        dialog.setLabelText("{}: {}...".format(self.title, text))
        outcome = {}

        def work():
            try:
                with s.interrupt:
                    outcome["value"] = fn(*args, **kwargs)
            except BaseException as e:  # handed to the GUI thread, which raises it
                outcome["error"] = e

        from PySide import QtCore, QtGui
        worker = threading.Thread(target=work, name="HexDom: " + text, daemon=True)
        worker.start()
        app = QtGui.QApplication.instance()
        while worker.is_alive():
            app.processEvents(QtCore.QEventLoop.AllEvents, 50)
            worker.join(0.02)
        app.processEvents()
        if s.cancelled:
            raise Cancelled("{}: cancelled by the user during {} (its result was discarded)"
                            .format(s.title, text))
        if "error" in outcome:
            raise outcome["error"]
        return outcome["value"]

    def _show_dialog(self):
        if self.dialog is None:
            self.dialog = _ProgressDialog(self)
            self.dialog.show()
        return self.dialog


def _reactivate_main_window():
    """Gives the keyboard back to FreeCAD's main window once the modal dialog is gone: without a
    window manager (or with some) no window is active afterwards, and window shortcuts such as
    Ctrl+Z would go nowhere."""
    import FreeCADGui
    from PySide import QtGui
    mw = FreeCADGui.getMainWindow()
    if mw is not None and QtGui.QApplication.activeWindow() is None:
        mw.activateWindow()


def _ProgressDialog(progress):
    """A modal dialog with the stage's text, a busy bar and a Cancel button (objectName
    HexDomProgress; the button is HexDomProgressCancel)."""
    import FreeCADGui
    from PySide import QtCore, QtGui

    class Dialog(QtGui.QDialog):
        def __init__(self):
            super().__init__(FreeCADGui.getMainWindow())
            self.setObjectName("HexDomProgress")
            self.setWindowTitle("HexDom: " + progress.title)
            self.setWindowModality(QtCore.Qt.WindowModal)
            self.setMinimumWidth(420)
            layout = QtGui.QVBoxLayout(self)
            self.label = QtGui.QLabel(progress.title)
            self.label.setWordWrap(True)
            bar = QtGui.QProgressBar()
            bar.setRange(0, 0)  # busy: the core reports no fraction
            self.button = QtGui.QPushButton("Cancel")
            self.button.setObjectName("HexDomProgressCancel")
            self.button.clicked.connect(progress.cancel)
            layout.addWidget(self.label)
            layout.addWidget(bar)
            layout.addWidget(self.button, 0, QtCore.Qt.AlignRight)

        def setLabelText(self, text):
            self.label.setText(text)

        def reject(self):  # Esc or the window's close button: cancel, stay open until done
            progress.cancel()

    return Dialog()


def _log(text):
    try:
        import FreeCAD
        FreeCAD.Console.PrintLog("HexDom: {}\n".format(text))
    except ImportError:
        pass
