"""Bounded undo / redo of whole editor states, shared by the Qt-free editors of the two panels
(patch_editing.PatchEditor, polycube_building.PolycubeBuilder)."""

MAX_UNDO = 200


class UndoStack:
    """States (any values) to go back and forth to. ``push(state)`` before an edit stores the state
    it leaves (and forgets the redo list); ``undo(current)`` / ``redo(current)`` take the current
    state and return the one to restore, or None when there is none."""

    def __init__(self, limit=MAX_UNDO):
        self.limit = limit
        self._undo, self._redo = [], []

    @property
    def can_undo(self):
        return bool(self._undo)

    @property
    def can_redo(self):
        return bool(self._redo)

    def push(self, state):
        self._undo.append(state)
        if len(self._undo) > self.limit:
            self._undo.pop(0)
        self._redo.clear()

    def undo(self, current):
        if not self._undo:
            return None
        self._redo.append(current)
        return self._undo.pop()

    def redo(self, current):
        if not self._redo:
            return None
        self._undo.append(current)
        return self._redo.pop()


class UndoableEditor:
    """Undo and redo for an editor whose state is a tuple of values: the editor keeps an UndoStack
    in ``self._history``, pushes ``self._state()`` before each edit, and restores a state with
    ``self._restore(state)`` (which returns False for None)."""

    @property
    def can_undo(self):
        return self._history.can_undo

    @property
    def can_redo(self):
        return self._history.can_redo

    def undo(self):
        return self._restore(self._history.undo(self._state()))

    def redo(self):
        return self._restore(self._history.redo(self._state()))
