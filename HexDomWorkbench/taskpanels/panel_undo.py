"""FreeCAD's Undo and Redo acting on a task panel's own undo stack while the panel is open (GUI
only).

Edit > Undo (Std_Undo) undoes the last document transaction. While a panel edits a copy of an
object's data, that would undo something underneath the edit in progress (or nothing the user
can see), while the user means the panel's last edit. UndoRedirect therefore puts, for as long
as the panel is open, its own actions where FreeCAD's Std_Undo and Std_Redo actions sit (the
Edit menu, toolbars), with their text, icon and shortcuts (Ctrl+Z; Ctrl+Shift+Z and Ctrl+Y for
redo), and takes the shortcuts off FreeCAD's actions; ``remove`` puts everything back. A key in a
text field (a coordinate box) still undoes the typing there: Qt gives the field the key first.
"""

from PySide import QtCore, QtGui

import FreeCADGui

EXTRA_SHORTCUTS = {"Std_Redo": ("Ctrl+Y",)}


def _alive(qobject):
    try:
        qobject.objectName()
        return True
    except RuntimeError:  # the C++ object is gone (menus are rebuilt on a workbench switch)
        return False


def freecad_actions(command):
    """FreeCAD's QActions of ``command`` ("Std_Undo"): the menu action and the toolbar variant
    of the undo and redo commands (an unnamed action with the same text and a drop-down list of
    the steps). QObject.parent() is not called on them: PySide would tie the action's wrapper to
    a temporary wrapper of FreeCAD's Gui::Action and invalidate it with that."""
    try:
        actions = [a for a in FreeCADGui.Command.get(command).getAction() if _alive(a)]
    except (AttributeError, RuntimeError):
        return []
    texts = {a.text() for a in actions}
    for bar in FreeCADGui.getMainWindow().findChildren(QtGui.QToolBar):
        try:
            for action in bar.actions():
                if (action.objectName() == "" and action.text() in texts
                        and action.menu() is not None and all(action is not a for a in actions)):
                    actions.append(action)
        except RuntimeError:  # a toolbar rebuilt since (workbench switch)
            continue
    return actions


class UndoRedirect:
    """Routes FreeCAD's Undo / Redo (menu, toolbar, shortcuts) to ``undo`` / ``redo`` until
    ``remove``; ``can_undo`` / ``can_redo`` (callables) enable the actions (call ``update`` after
    each edit)."""

    def __init__(self, undo, redo, can_undo, can_redo):
        self.actions = {}
        self._enabled = {"Std_Undo": can_undo, "Std_Redo": can_redo}
        self._toolbar_actions = {}  # command: FreeCAD's toolbar variants, swapped out
        self._shortcuts = []  # (FreeCAD's action, its shortcuts)
        mw = FreeCADGui.getMainWindow()
        for command, fn in (("Std_Undo", undo), ("Std_Redo", redo)):
            originals = freecad_actions(command)
            action = QtGui.QAction(mw)
            action.setObjectName("HexDomPanel_" + command)
            keys = []
            if originals:
                first = originals[0]
                action.setText(first.text())
                action.setIcon(first.icon())
                keys = list(first.shortcuts())
            else:
                action.setText("&Undo" if command == "Std_Undo" else "&Redo")
            if not keys:
                keys = [QtGui.QKeySequence(QtGui.QKeySequence.Undo if command == "Std_Undo"
                                           else QtGui.QKeySequence.Redo)]
            for extra in EXTRA_SHORTCUTS.get(command, ()):
                sequence = QtGui.QKeySequence(extra)
                if all(sequence != k for k in keys):
                    keys.append(sequence)
            action.setToolTip("{} the last edit in the task panel".format(
                "Undoes" if command == "Std_Undo" else "Redoes"))
            action.setStatusTip(action.toolTip())
            action.triggered.connect(lambda checked=False, fn=fn: fn())
            for original in originals:
                self._shortcuts.append((original, list(original.shortcuts())))
                original.setShortcuts([])
                widgets = list(original.associatedWidgets())
                for widget in widgets:
                    if isinstance(widget, QtGui.QToolBar):
                        self._toolbar_actions.setdefault(command, []).append(original)
                    if isinstance(widget, (QtGui.QMenu, QtGui.QToolBar)):
                        widget.insertAction(original, action)
                        widget.removeAction(original)
            action.setShortcuts(keys)
            action.setShortcutContext(QtCore.Qt.WindowShortcut)
            mw.addAction(action)  # the shortcuts work with the Edit menu gone (other workbench)
            self.actions[command] = action
        self.update()

    def update(self):
        """Enables the actions as the panel can undo and redo."""
        for command, action in self.actions.items():
            if _alive(action):
                action.setEnabled(bool(self._enabled[command]()))

    def remove(self):
        """Puts FreeCAD's actions and shortcuts back."""
        # Widgets are found again from our actions: PySide may have dropped the wrappers of
        # FreeCAD's menus since.
        for command, action in self.actions.items():
            if not _alive(action):
                continue
            widgets = list(action.associatedWidgets())
            for widget in widgets:
                if isinstance(widget, QtGui.QMenu):
                    originals = freecad_actions(command)
                    originals = [a for a in originals if a.objectName() == command]
                elif isinstance(widget, QtGui.QToolBar):
                    originals = [a for a in self._toolbar_actions.get(command, []) if _alive(a)]
                else:
                    continue
                for original in originals:
                    widget.insertAction(action, original)
                widget.removeAction(action)
        self._toolbar_actions = {}
        for original, keys in self._shortcuts:
            if _alive(original):
                original.setShortcuts(keys)
        self._shortcuts = []
        mw = FreeCADGui.getMainWindow()
        for action in self.actions.values():
            if _alive(action):
                mw.removeAction(action)
                action.setShortcuts([])
                action.deleteLater()
        self.actions = {}
