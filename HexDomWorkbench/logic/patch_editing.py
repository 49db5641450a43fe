"""What the Edit Patches panel does, without Qt or FreeCAD: the patch map of a segmented surface
under edit, a facet selection, undo and redo, and the live list of problems (core.check_patches).

    editor = PatchEditor(V, F, patches, labels, face_ids)
    editor.select_facets([10, 11, 12])
    editor.assign_to_patch(7)            # or new_patch(), assign_orientation("+Z")
    editor.merge(3, 4); editor.split(5, [120, 131, 140])
    editor.problems()                    # core.Violation list, empty when the polycube is valid
    editor.undo(); editor.redo()
    editor.changes()                     # what differs from the map the editor started with

Patch ids are the segmentation's (part ids: one id may name several disconnected regions); a
patch in core.check_patches is a connected region of one id, numbered 1.. in the order of its
first triangle (core.number_patches), and violations name those numbers. Labels are the polycube
orientations 1..6 (+X -X +Y -Y +Z -Z), one per triangle; every edit keeps one label per patch id.
"""

import numpy as np

from .. import core
from .labels import (LABEL_NAMES, apply_label_edits, label_number,  # noqa: F401
                     labels_from_normals, nearest_label)
from .triangles import triangle_normals
from .undo_stack import UndoableEditor, UndoStack

SELECT_MODES = ("replace", "add", "remove", "toggle")


def points_in_polygon(points, polygon):
    """Which of ``points`` (#P x 2) lie inside ``polygon`` (#Q x 2 vertices, closed implicitly,
    may cross itself: even-odd rule)."""
    p = np.asarray(points, float).reshape(-1, 2)
    q = np.asarray(polygon, float).reshape(-1, 2)
    inside = np.zeros(len(p), bool)
    if len(q) < 3:
        return inside
    a, b = q, np.roll(q, -1, axis=0)
    for (ax, ay), (bx, by) in zip(a.tolist(), b.tolist()):
        if ay == by:
            continue
        crosses = (ay > p[:, 1]) != (by > p[:, 1])
        x = ax + (p[:, 1] - ay) * (bx - ax) / (by - ay)
        inside ^= crosses & (p[:, 0] < x)
    return inside



class PatchEditor(UndoableEditor):
    """Patch map of a surface under edit.

    V (#V x 3), F (#F x 3): the triangles; patches (#F): patch id per triangle (positive);
    labels (#F): label 1..6 per triangle (None: the axis nearest each patch's mean normal);
    face_ids (#F): CAD face (or file part) id per triangle, for selecting whole faces.
    ``check_options`` go to core.check_patches. frame (3 x 3 rotation, the Segmentation's Frame):
    the axes the labels name, for the labels taken from normals (None: the model's axes); stretch
    (the Segmentation's Stretch): factors along those axes the normals are taken stretched by.
    """

    def __init__(self, V, F, patches, labels=None, face_ids=None, check_options=None, frame=None,
                 stretch=None):
        self.frame = np.eye(3) if frame is None else np.asarray(frame, float).reshape(3, 3)
        # Normals (and sums of area vectors) of the stretched surface in the frame: diag(1 / f) R n.
        self.normal_map = (self.frame if stretch is None
                           else np.diag(1.0 / np.asarray(stretch, float)) @ self.frame)
        self.V = np.ascontiguousarray(V, float).reshape(-1, 3)
        self.F = np.ascontiguousarray(F, np.int32).reshape(-1, 3)
        n = len(self.F)
        self.patches = np.array(patches, np.int32).reshape(-1)
        if len(self.patches) != n:
            raise ValueError("{} patch ids for {} triangles".format(len(self.patches), n))
        if n and self.patches.min() <= 0:
            raise ValueError("patch ids must be positive")
        self.normals, self.areas = triangle_normals(self.V, self.F)
        if labels is None:
            labels = labels_from_normals(self.V, self.F, self.patches, frame=self.frame,
                                         stretch=stretch)
        self.labels = np.array(labels, np.int32).reshape(-1)
        if len(self.labels) != n:
            raise ValueError("{} labels for {} triangles".format(len(self.labels), n))
        self.face_ids = None if face_ids is None else np.array(face_ids, np.int32).reshape(-1)
        if self.face_ids is not None and len(self.face_ids) != n:
            self.face_ids = None
        self.check_options = dict(check_options or {})
        self.original_patches = self.patches.copy()
        self.original_labels = self.labels.copy()
        self.selection = np.zeros(n, bool)
        self.path = []
        self._history = UndoStack()
        self._check = None
        self._vertex_triangles = None
        self.listeners = []

    # --------------------------------------------------------------------------------------------
    # State

    @property
    def triangle_count(self):
        return len(self.F)

    def surface(self):
        """core.Surface with the current patch ids."""
        return core.Surface(self.V, self.F, self.patches)

    def patch_ids(self):
        return sorted(set(self.patches.tolist()))

    def patch_label(self, patch_id):
        """Label of patch ``patch_id`` (the most common label of its triangles), or 0."""
        mask = self.patches == int(patch_id)
        if not np.any(mask):
            return 0
        return int(np.bincount(self.labels[mask], minlength=7).argmax())

    def patch_summary(self):
        """[(patch id, label, triangle count)] in id order."""
        ids, counts = np.unique(self.patches, return_counts=True)
        return [(int(i), self.patch_label(i), int(c)) for i, c in zip(ids, counts)]

    def is_modified(self):
        return not (np.array_equal(self.patches, self.original_patches)
                    and np.array_equal(self.labels, self.original_labels))

    def changes(self):
        """Triangles whose label or patch id differs from the start: (label triangles, their
        labels, patch triangles, their patch ids), each an int array."""
        lt = np.flatnonzero(self.labels != self.original_labels)
        pt = np.flatnonzero(self.patches != self.original_patches)
        return lt, self.labels[lt].copy(), pt, self.patches[pt].copy()

    def _notify(self, what):
        for listener in list(self.listeners):
            listener(what)

    # --------------------------------------------------------------------------------------------
    # Selection

    def selected(self):
        """Selected triangles (ascending indices)."""
        return np.flatnonzero(self.selection)

    def selected_patches(self):
        """Patch ids of the selection, in the order of their first selected triangle."""
        ids = self.patches[self.selection]
        _, first = np.unique(ids, return_index=True)
        return [int(ids[i]) for i in sorted(first)]

    def suggested_patch(self):
        """The patch most of the selection's neighbouring facets (sharing a vertex) belong to:
        where selected facets most likely go. None without a selection."""
        if not self.selection.any():
            return None
        verts = np.unique(self.F[self.selection])
        self.vertex_triangles(0)
        tri_of, starts = self._vertex_triangles
        around = np.concatenate([tri_of[starts[v]:starts[v + 1]] for v in verts.tolist()])
        around = around[~self.selection[around]]
        ids = self.patches[around] if len(around) else self.patches[self.selection]
        values, counts = np.unique(ids, return_counts=True)
        return int(values[np.argmax(counts)])

    def select_facets(self, triangles, mode="add"):
        """Changes the selection by ``triangles`` (indices): mode "replace", "add", "remove" or
        "toggle". Returns the number of selected triangles."""
        if mode not in SELECT_MODES:
            raise ValueError("selection mode '{}' is not one of {}".format(mode, SELECT_MODES))
        tris = np.unique(np.asarray(triangles, np.int64).reshape(-1))
        if len(tris) and (tris[0] < 0 or tris[-1] >= self.triangle_count):
            raise ValueError("facet {} is not one of 0..{}".format(
                int(tris[0] if tris[0] < 0 else tris[-1]), self.triangle_count - 1))
        if mode == "replace":
            self.selection[:] = False
        if mode in ("replace", "add"):
            self.selection[tris] = True
        elif mode == "remove":
            self.selection[tris] = False
        else:
            self.selection[tris] = ~self.selection[tris]
        self._notify("selection")
        return int(np.count_nonzero(self.selection))

    def select_patch(self, patch_id, mode="add"):
        """Selects every triangle of patch id ``patch_id``."""
        tris = np.flatnonzero(self.patches == int(patch_id))
        if len(tris) == 0:
            raise ValueError("there is no patch {}".format(patch_id))
        return self.select_facets(tris, mode)

    def select_face(self, face_id, mode="add"):
        """Selects every triangle of CAD face ``face_id`` (FreeCAD's Face<face_id>)."""
        if self.face_ids is None:
            raise ValueError("the surface has no CAD face ids")
        tris = np.flatnonzero(self.face_ids == int(face_id))
        if len(tris) == 0:
            raise ValueError("the surface has no triangle on Face{}".format(face_id))
        return self.select_facets(tris, mode)

    def clear_selection(self):
        self.selection[:] = False
        self._notify("selection")

    def _triangles(self, triangles):
        tris = self.selected() if triangles is None else np.unique(
            np.asarray(triangles, np.int64).reshape(-1))
        if len(tris) == 0:
            raise ValueError("no facets selected")
        if tris[0] < 0 or tris[-1] >= self.triangle_count:
            raise ValueError("facet index outside 0..{}".format(self.triangle_count - 1))
        return tris

    # --------------------------------------------------------------------------------------------
    # Split path

    def vertex_triangles(self, vertex):
        if self._vertex_triangles is None:
            order = np.argsort(self.F.reshape(-1), kind="stable")
            starts = np.searchsorted(self.F.reshape(-1)[order], np.arange(len(self.V) + 1))
            self._vertex_triangles = (order // 3, starts)
        tri_of, starts = self._vertex_triangles
        return tri_of[starts[vertex]:starts[vertex + 1]]

    def nearest_vertex(self, triangle, point):
        """Vertex of ``triangle`` nearest ``point``."""
        corners = self.F[int(triangle)]
        d = np.linalg.norm(self.V[corners] - np.asarray(point, float).reshape(1, 3), axis=1)
        return int(corners[int(np.argmin(d))])

    def add_path_vertex(self, vertex):
        """Appends a vertex to the split path (consecutive repeats ignored)."""
        vertex = int(vertex)
        if not 0 <= vertex < len(self.V):
            raise ValueError("vertex {} is not one of 0..{}".format(vertex, len(self.V) - 1))
        if not self.path or self.path[-1] != vertex:
            self.path.append(vertex)
        self._notify("path")
        return list(self.path)

    def clear_path(self):
        self.path = []
        self._notify("path")

    def path_patch(self, path=None):
        """The one patch id every vertex of ``path`` touches (the patch a split cuts), or None."""
        path = self.path if path is None else list(path)
        common = None
        for v in path:
            ids = set(self.patches[self.vertex_triangles(int(v))].tolist())
            common = ids if common is None else common & ids
        if not common:
            return None
        if len(common) == 1:
            return next(iter(common))
        # Every vertex on one curve between two patches: take the one its inner vertices lean to.
        return min(common)

    # --------------------------------------------------------------------------------------------
    # Edits (each one undoable)

    def _push(self):
        self._history.push((self.patches.copy(), self.labels.copy()))

    def _changed(self, patches, labels):
        self._push()
        self.patches = np.asarray(patches, np.int32).reshape(-1).copy()
        self.labels = np.asarray(labels, np.int32).reshape(-1).copy()
        self._check = None
        self.selection[:] = False
        self.path = []
        self._notify("patches")

    def assign_to_patch(self, patch_id, triangles=None):
        """The selected triangles (or ``triangles``) join patch id ``patch_id`` and take its
        label."""
        patch_id = int(patch_id)
        if patch_id not in set(self.patches.tolist()):
            raise ValueError("there is no patch {}".format(patch_id))
        tris = self._triangles(triangles)
        label = self.patch_label(patch_id)
        patches = core.reassign_triangles(self.surface(), tris, patch_id)
        labels = self.labels.copy()
        labels[tris] = label
        self._changed(patches, labels)
        return patch_id

    def new_patch(self, triangles=None, label=None):
        """The selected triangles (or ``triangles``) become a new patch (id = largest + 1) with
        ``label`` (default: the axis nearest their mean normal). Returns the new id."""
        tris = self._triangles(triangles)
        if label is None:
            mean = (self.normals[tris] * self.areas[tris, None]).sum(axis=0)
            label = int(nearest_label(self.normal_map @ mean)[0])
        label = label_number(label)
        patches = np.asarray(core.reassign_triangles(self.surface(), tris, 0), np.int32)
        new_id = int(patches[tris[0]])
        labels = self.labels.copy()
        labels[tris] = label
        self._changed(patches, labels)
        return new_id

    def assign_orientation(self, label, triangles=None):
        """The selected triangles (or ``triangles``) take orientation ``label`` (1..6 or "+X"
        ... "-Z"): they join a neighbouring patch of that label, grown from the patches they
        touch; regions touching none become new patches. Returns the patch ids they went to."""
        label = label_number(label)
        tris = self._triangles(triangles)
        labels, patches = apply_label_edits(self.F, self.labels, self.patches, tris,
                                            np.full(len(tris), label, np.int32),
                                            keep_patches=True)
        self._changed(patches, labels)
        return sorted(set(patches[tris].tolist()))

    def merge(self, a=None, b=None):
        """Patch id ``b`` joins patch id ``a`` and takes its label (they must share an edge).
        With no ids, the patches of the selection merge into the first one. Returns ``a``."""
        if a is None:
            ids = self.selected_patches()
            if len(ids) < 2:
                raise ValueError("select facets of two or more patches to merge them")
            a, others = ids[0], ids[1:]
        else:
            others = [b] if b is not None else []
            if not others:
                raise ValueError("merge needs two patch ids")
        a = int(a)
        patches = self.surface().patch
        label = self.patch_label(a)
        labels = self.labels.copy()
        for b in others:
            patches = np.asarray(core.merge_patches(core.Surface(self.V, self.F, patches), a,
                                                    int(b)), np.int32)
        labels[patches == a] = label
        self._changed(patches, labels)
        return a

    def split(self, patch_id=None, path=None):
        """Cuts patch id ``patch_id`` along ``path`` (vertices; default: the picked path, and the
        patch it runs across); the part without the patch's first triangle gets a new id with the
        same label. Returns the new ids."""
        path = list(self.path if path is None else path)
        if len(path) < 2:
            raise ValueError("pick a path of two or more vertices across the patch")
        if patch_id is None:
            patch_id = self.path_patch(path)
            if patch_id is None:
                raise ValueError("the path does not run across one patch")
        before = set(self.patches.tolist())
        patches = np.asarray(core.split_patch(self.surface(), int(patch_id), path), np.int32)
        new_ids = sorted(set(patches.tolist()) - before)
        labels = self.labels.copy()
        label = self.patch_label(patch_id)
        for i in new_ids:
            labels[patches == i] = label
        self._changed(patches, labels)
        return new_ids

    def reset(self):
        """Back to the patch map the editor started with (undoable)."""
        self._changed(self.original_patches, self.original_labels)

    def _state(self):
        return (self.patches, self.labels)

    def _restore(self, state):
        if state is None:
            return False
        self.patches, self.labels = state
        self._check = None
        self.selection[:] = False
        self._notify("patches")
        return True

    # --------------------------------------------------------------------------------------------
    # Problems

    def check(self):
        """(core.PatchCheck or None, patch number per triangle, error text): the polycube check
        of the current map, cached until the next edit."""
        if self._check is None:
            surface = self.surface()
            numbers = np.asarray(core.number_patches(surface), np.int32).reshape(-1)
            try:
                result, error = core.check_patches(surface, **self.check_options), ""
            except core.Error as e:
                result, error = None, str(e)
            self._check = (result, numbers, error)
        return self._check

    def problems(self):
        """Violations of the polycube conditions (core.Violation; str() is the message)."""
        result, _, error = self.check()
        if result is None:
            return [core.Violation("unfit_surface", [], -1, np.zeros(3), error)]
        return list(result.violations)

    def problem_triangles(self, problem):
        """Triangles a problem is about: the ring of its vertex for a corner problem, else the
        patches it names."""
        _, numbers, _ = self.check()
        if problem.kind == "two_patch_corner" and problem.vertex >= 0:
            ring = self.vertex_triangles(problem.vertex)
            return np.unique(ring)
        if problem.patches:
            return np.flatnonzero(np.isin(numbers, np.asarray(problem.patches, np.int32)))
        if problem.vertex >= 0:
            return np.unique(self.vertex_triangles(problem.vertex))
        return np.zeros(0, np.int64)

    def patch_of_number(self, number):
        """Patch id of the region numbered ``number`` (as violations name them)."""
        _, numbers, _ = self.check()
        tris = np.flatnonzero(numbers == int(number))
        return int(self.patches[tris[0]]) if len(tris) else None
