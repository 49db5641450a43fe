"""What the Build Polycube panel does, without Qt or FreeCAD: the polycube structure under
construction over the boundary a segmentation asks for, with undo, redo and a live list of
problems.

    builder = PolycubeBuilder(surface)        # core.Surface with patch ids
    c = builder.add_vertex_at_centroid([0, 5, 9, 12])
    builder.select_vertices([0, 1, 3, 2, 4, 5, 7, 6])
    builder.add_block()                       # 8 vertices: hex, 6: prism, 4: tet; order fixed up
    builder.problems()                        # [] when the structure fills the boundary exactly
    builder.structure()                       # core.Mesh for core.generate / the Polycube object

Vertices 0..C-1 are the corners of core.polycube_boundary (in its order); interior vertices the
user adds follow. Blocks keep VTK node order (hex 8, prism 6, tet 4 vertices). A structure read
from a .k file is snapped to the corners (relative distance below ``snap``); the vertices that
snap to no corner become interior vertices.
"""

import itertools
from dataclasses import dataclass, field

import numpy as np

from .. import core
from .cells import BLOCK_FACES, HEX, NODE_COUNT, TET, WEDGE, block_faces, face_key  # noqa: F401
from .stages import read_structure
from .undo_stack import UndoableEditor, UndoStack

TYPE_OF_COUNT = {8: HEX, 6: WEDGE, 4: TET}
TYPE_NAMES = {HEX: "hex", WEDGE: "prism", TET: "tet"}
_PERMUTATIONS = {}


@dataclass
class Problem:
    """One reason the structure cannot be meshed: kind ("uncovered_patch", "patch_covered_twice",
    "patches_share_corners", "open_face", "face_shared", "inverted", "overlap",
    "duplicate_block", "unused_vertex", "no_boundary"), a message, and what to highlight: 0-based blocks and vertices, 1-based
    patches, faces as vertex lists."""

    kind: str
    message: str
    blocks: list = field(default_factory=list)
    vertices: list = field(default_factory=list)
    patches: list = field(default_factory=list)
    faces: list = field(default_factory=list)

    def __str__(self):
        return self.message


def _permutations(n):
    if n not in _PERMUTATIONS:
        perms = np.array(list(itertools.permutations(range(n))), np.int32)
        _PERMUTATIONS[n] = perms
    return _PERMUTATIONS[n]


def scaled_jacobians(points, cells, block_type):
    """Scaled Jacobian (core.cell_metrics, Verdict's definition) of each row of ``cells``
    (indices into ``points``, VTK order of ``block_type``)."""
    cells = np.asarray(cells, np.int32).reshape(len(cells), -1)
    padded = np.full((len(cells), 8), -1, np.int32)
    padded[:, :cells.shape[1]] = cells
    mesh = core.Mesh(np.asarray(points, float).reshape(-1, 3), padded,
                     np.full(len(cells), block_type, np.int32), np.ones(len(cells), np.int32))
    return np.asarray(core.cell_metrics(mesh)[0], float)


def order_block(points, vertices, known_faces=()):
    """(type, vertices in VTK order) of the block on ``vertices`` (8 hex, 6 prism, 4 tet; indices
    into ``points``): of the orderings with positive scaled Jacobian, the one with the most faces
    in ``known_faces`` (sorted vertex tuples: patches, faces of other blocks), then the largest
    scaled Jacobian, then the one nearest the given order. Raises ValueError when no ordering is
    positive."""
    vertices = [int(v) for v in vertices]
    n = len(vertices)
    if n not in TYPE_OF_COUNT:
        raise ValueError("{} vertices picked: a block needs 8 (hex), 6 (prism) or 4 (tet)"
                         .format(n))
    if len(set(vertices)) != n:
        raise ValueError("a vertex is picked twice")
    block_type = TYPE_OF_COUNT[n]
    perms = _permutations(n)
    P = np.asarray(points, float)[vertices]
    sj = scaled_jacobians(P, perms, block_type)
    sj = np.where(np.isfinite(sj) & (sj <= 1.0 + 1e-9), sj, -np.inf)
    best_sj = float(sj.max())
    if not best_sj > 0:
        raise ValueError("these {} vertices make no {} that is not inverted (best scaled "
                         "Jacobian {:.3g})".format(n, TYPE_NAMES[block_type], best_sj))
    good = np.flatnonzero(sj > 0)
    known = set(known_faces)
    ids = np.asarray(vertices)
    scored = []
    for p in good.tolist():
        order = ids[perms[p]]
        matches = sum(face_key(f) in known for f in block_faces(block_type, order))
        displaced = int(np.count_nonzero(perms[p] != np.arange(n)))
        scored.append((-matches, -round(float(sj[p]), 9), displaced, p))
    scored.sort()
    return block_type, [int(v) for v in ids[perms[scored[0][3]]]]


OVERLAP_LEVELS = 4  # lattice steps per parameter direction of the overlap samples
OVERLAP_MARGIN = 0.08  # how far the samples are pulled from a block's faces to its middle
_SAMPLE_WEIGHTS = {}


def _lattice(dims, level):
    """Barycentric lattice points of a simplex with ``dims`` + 1 corners, ``level`` steps."""
    out = [c + (level - sum(c),) for c in itertools.product(range(level + 1), repeat=dims)
           if sum(c) <= level]
    return np.array(out, float) / level


def sample_weights(block_type, level=OVERLAP_LEVELS, margin=OVERLAP_MARGIN):
    """Weights (#samples x corners) of the overlap samples of a block: a lattice over its
    parameter space (trilinear for a hex, triangle x segment for a prism, barycentric for a
    tet), shrunk by ``margin`` towards the parametric middle."""
    key = (block_type, level, margin)
    if key not in _SAMPLE_WEIGHTS:
        ticks = np.linspace(0.0, 1.0, level + 1)
        if block_type == HEX:
            u, v, w = (g.reshape(-1) for g in np.meshgrid(ticks, ticks, ticks, indexing="ij"))
            u, v, w = (margin * 0.5 + (1 - margin) * x for x in (u, v, w))
            cu = [(1 - u), u, u, (1 - u)]
            cv = [(1 - v), (1 - v), v, v]
            W = np.stack([cu[k % 4] * cv[k % 4] * (w if k >= 4 else 1 - w) for k in range(8)],
                         axis=1)
        elif block_type == WEDGE:
            tri = _lattice(2, level)
            tri = (1 - margin) * tri + margin / 3.0
            w = margin * 0.5 + (1 - margin) * ticks
            W = np.vstack([np.hstack([tri * (1 - z), tri * z]) for z in w])
        else:
            W = (1 - margin) * _lattice(3, level) + margin / 4.0
        _SAMPLE_WEIGHTS[key] = W
    return _SAMPLE_WEIGHTS[key]


def block_samples(block_type, corners):
    """Points spread through a block with corner positions ``corners`` (VTK order)."""
    return sample_weights(block_type) @ np.asarray(corners, float).reshape(-1, 3)


def _shape(block_type, xi):
    """(N, dN): the block's shape functions at parameters ``xi`` (#Q x 3; hex: u v w in 0..1,
    prism: r s (triangle) and t, tet: r s t) and their derivatives (#Q x corners x 3)."""
    u, v, w = xi[:, 0], xi[:, 1], xi[:, 2]
    one, zero = np.ones_like(u), np.zeros_like(u)
    if block_type == HEX:
        fu = [(1 - u, -one), (u, one), (u, one), (1 - u, -one)]
        fv = [(1 - v, -one), (1 - v, -one), (v, one), (v, one)]
        N, dN = [], []
        for k in range(8):
            (a, da), (b, db) = fu[k % 4], fv[k % 4]
            c, dc = (w, one) if k >= 4 else (1 - w, -one)
            N.append(a * b * c)
            dN.append(np.stack([da * b * c, a * db * c, a * b * dc], axis=1))
        return np.stack(N, axis=1), np.stack(dN, axis=1)
    if block_type == WEDGE:
        tri = [(1 - u - v, -one, -one), (u, one, zero), (v, zero, one)]
        N, dN = [], []
        for c, dc in ((1 - w, -one), (w, one)):
            for a, da, db in tri:
                N.append(a * c)
                dN.append(np.stack([da * c, db * c, a * dc], axis=1))
        return np.stack(N, axis=1), np.stack(dN, axis=1)
    N = np.stack([1 - u - v - w, u, v, w], axis=1)
    d = np.array([[-1, -1, -1], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    return N, np.broadcast_to(d, (len(u), 4, 3))


_MIDDLE = {HEX: (0.5, 0.5, 0.5), WEDGE: (1 / 3.0, 1 / 3.0, 0.5), TET: (0.25, 0.25, 0.25)}


def inside_block(block_type, corners, points, margin=1e-3, iterations=25):
    """Which ``points`` (#Q x 3) lie inside the block with corner positions ``corners`` (VTK
    order; one block, or #Q x corners x 3: one block per point): the parameters of each point
    under the block's map (trilinear hex, linear x linear prism, linear tet; found by Newton's
    method) are inside its parameter domain by more than ``margin``. Points the iteration
    cannot place count as outside."""
    X = np.asarray(points, float).reshape(-1, 3)
    n = NODE_COUNT[block_type]
    C = np.asarray(corners, float)
    C = np.broadcast_to(C.reshape(-1, n, 3), (len(X), n, 3)) if C.ndim < 3 else C
    if len(X) == 0:
        return np.zeros(0, bool)
    size = np.linalg.norm(C.max(axis=1) - C.min(axis=1), axis=1)
    size = np.where(size > 0, size, 1.0)
    xi = np.tile(np.array(_MIDDLE[block_type], float), (len(X), 1))
    active = np.arange(len(X))
    for _ in range(iterations):
        N, dN = _shape(block_type, xi[active])
        Ca = C[active]
        r = np.einsum("qk,qkj->qj", N, Ca) - X[active]
        # Columns of the Jacobian (d x / d xi_i), then Cramer's rule.
        a, b, c = (np.einsum("qk,qkj->qj", dN[:, :, i], Ca) for i in range(3))
        bc = np.cross(b, c)
        det = np.einsum("qj,qj->q", a, bc)
        ok = np.abs(det) > 1e-30 * size[active] ** 3
        inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        step = np.stack([np.einsum("qj,qj->q", r, bc),
                         np.einsum("qj,qj->q", a, np.cross(r, c)),
                         np.einsum("qj,qj->q", a, np.cross(b, r))], axis=1) * inv[:, None]
        xi[active] = np.clip(xi[active] - step, -1.0, 2.0)
        # Done: converged, or (after a few steps) far outside the domain, where it stays.
        far = np.any((xi[active] < -0.5) | (xi[active] > 1.5), axis=1) & (_ > 3)
        active = active[(np.abs(step).max(axis=1) > 1e-12) & ~far]
        if len(active) == 0:
            break
    N, _ = _shape(block_type, xi)
    converged = np.linalg.norm(np.einsum("qk,qkj->qj", N, C) - X, axis=1) <= 1e-7 * size
    u, v, w = xi[:, 0], xi[:, 1], xi[:, 2]
    lo, hi = margin, 1.0 - margin
    if block_type == HEX:
        inside = (u > lo) & (u < hi) & (v > lo) & (v < hi) & (w > lo) & (w < hi)
    elif block_type == WEDGE:
        inside = (u > lo) & (v > lo) & (u + v < hi) & (w > lo) & (w < hi)
    else:
        inside = (u > lo) & (v > lo) & (w > lo) & (u + v + w < hi)
    return inside & converged


class PolycubeBuilder(UndoableEditor):
    """Polycube structure under construction.

    surface: core.Surface with patch ids (the segmentation), or None to edit blocks without a
    boundary to fill; structure: a core.Mesh of blocks to start from (snapped to the corners).
    """

    def __init__(self, surface=None, structure=None, snap=1e-4):
        self.boundary, self.boundary_error = None, ""
        self.snap = float(snap)
        corners = np.zeros((0, 3))
        self.scale = 1.0
        if surface is not None:
            V = np.asarray(surface.V, float)
            if len(V):
                self.scale = float(np.linalg.norm(V.max(axis=0) - V.min(axis=0))) or 1.0
            try:
                self.boundary = core.polycube_boundary(surface)
                corners = np.asarray(self.boundary.corners, float).reshape(-1, 3)
            except core.Error as e:
                self.boundary_error = str(e)
        self.corner_count = len(corners)
        self.points = corners.copy()
        self.blocks = []  # (type, tuple of vertex ids in VTK order)
        self.selection = []
        self._history = UndoStack()
        self._problems = None
        self.listeners = []
        self.patch_faces = {}
        if self.boundary is not None:
            for face in self.boundary.faces:
                self.patch_faces[face_key(face["corners"])] = face
        if structure is not None:
            self.load_structure(structure, undoable=False)

    # --------------------------------------------------------------------------------------------
    # State

    @property
    def vertex_count(self):
        return len(self.points)

    def is_corner(self, vertex):
        return 0 <= int(vertex) < self.corner_count

    def counts(self):
        """{"hex": n, "prism": n, "tet": n}."""
        types = [t for t, _ in self.blocks]
        return {name: types.count(t) for t, name in TYPE_NAMES.items()}

    def used_vertices(self):
        return sorted({v for _, b in self.blocks for v in b})

    def structure(self):
        """core.Mesh of the blocks over the vertices they use (region = 1-based block number)."""
        used = self.used_vertices()
        remap = {v: i for i, v in enumerate(used)}
        cells = np.full((len(self.blocks), 8), -1, np.int32)
        for r, (_, b) in enumerate(self.blocks):
            cells[r, :len(b)] = [remap[v] for v in b]
        types = np.array([t for t, _ in self.blocks], np.int32)
        V = self.points[used] if used else np.zeros((0, 3))
        return core.Mesh(np.asarray(V, float).reshape(-1, 3), cells, types,
                         np.arange(1, len(self.blocks) + 1, dtype=np.int32))

    def known_faces(self, skip_block=None):
        """Sorted vertex tuples of the patch faces and of the faces of the blocks."""
        known = set(self.patch_faces)
        for i, (t, b) in enumerate(self.blocks):
            if i != skip_block:
                known.update(face_key(f) for f in block_faces(t, b))
        return known

    def _notify(self, what):
        for listener in list(self.listeners):
            listener(what)

    # --------------------------------------------------------------------------------------------
    # Selection (vertices, in the order picked)

    def select_vertices(self, vertices, mode="add"):
        """Changes the vertex selection: mode "replace", "add", "remove" or "toggle"; the
        selection keeps the order of picking. Returns it."""
        vertices = [int(v) for v in np.asarray(vertices, np.int64).reshape(-1).tolist()]
        for v in vertices:
            if not 0 <= v < self.vertex_count:
                raise ValueError("vertex {} is not one of 0..{}".format(v, self.vertex_count - 1))
        if mode == "replace":
            self.selection = []
        for v in vertices:
            if mode in ("replace", "add"):
                if v not in self.selection:
                    self.selection.append(v)
            elif mode == "remove":
                if v in self.selection:
                    self.selection.remove(v)
            elif mode == "toggle":
                if v in self.selection:
                    self.selection.remove(v)
                else:
                    self.selection.append(v)
            else:
                raise ValueError("selection mode '{}' is not replace, add, remove or toggle"
                                 .format(mode))
        self._notify("selection")
        return list(self.selection)

    def clear_selection(self):
        self.selection = []
        self._notify("selection")

    def nearest_vertex(self, point):
        """(vertex, distance) nearest ``point``."""
        d = np.linalg.norm(self.points - np.asarray(point, float).reshape(1, 3), axis=1)
        i = int(np.argmin(d))
        return i, float(d[i])

    # --------------------------------------------------------------------------------------------
    # Edits (each one undoable)

    def _push(self):
        self._history.push((self.points.copy(), list(self.blocks)))

    def _changed(self, what="structure"):
        self._problems = None
        self._notify(what)

    def add_vertex(self, point):
        """Adds an interior vertex at ``point`` (typed coordinates or a picked point); returns its
        index."""
        p = np.asarray(point, float).reshape(3)
        if not np.all(np.isfinite(p)):
            raise ValueError("vertex coordinates must be finite numbers")
        self._push()
        self.points = np.vstack([self.points, p[None, :]])
        self.selection = []
        self._changed()
        return self.vertex_count - 1

    def add_vertex_at_centroid(self, vertices=None):
        """Adds an interior vertex at the centroid of ``vertices`` (default: the selection)."""
        vertices = list(self.selection if vertices is None else vertices)
        if not vertices:
            raise ValueError("pick the vertices whose centroid the new vertex takes")
        return self.add_vertex(self.points[np.asarray(vertices, np.int64)].mean(axis=0))

    def move_vertex(self, vertex, point):
        """Moves interior vertex ``vertex`` to ``point`` (corners stay on the surface)."""
        vertex = int(vertex)
        if self.is_corner(vertex):
            raise ValueError("vertex {} is a corner of the surface; only interior vertices move"
                             .format(vertex))
        if not 0 <= vertex < self.vertex_count:
            raise ValueError("there is no vertex {}".format(vertex))
        self._push()
        self.points = self.points.copy()
        self.points[vertex] = np.asarray(point, float).reshape(3)
        self._changed()

    def delete_vertex(self, vertex):
        """Deletes interior vertex ``vertex``, which no block may use; later vertices shift
        down by one."""
        vertex = int(vertex)
        if self.is_corner(vertex):
            raise ValueError("vertex {} is a corner of the surface and stays".format(vertex))
        if not 0 <= vertex < self.vertex_count:
            raise ValueError("there is no vertex {}".format(vertex))
        users = [i for i, (_, b) in enumerate(self.blocks) if vertex in b]
        if users:
            raise ValueError("vertex {} is used by block {}; delete the block first".format(
                vertex, users[0] + 1))
        self._push()
        self.points = np.delete(self.points, vertex, axis=0)
        self.blocks = [(t, tuple(v - (v > vertex) for v in b)) for t, b in self.blocks]
        self.selection = []
        self._changed()

    def add_block(self, vertices=None):
        """Adds the block on ``vertices`` (default: the selection): 8 give a hex, 6 a prism, 4 a
        tet, put in the order with positive scaled Jacobian that best fits the patches and the
        other blocks. Returns its 0-based index."""
        vertices = list(self.selection if vertices is None else vertices)
        block_type, ordered = order_block(self.points, vertices, self.known_faces())
        key = face_key(ordered)
        for i, (_, b) in enumerate(self.blocks):
            if face_key(b) == key:
                raise ValueError("block {} already uses these vertices".format(i + 1))
        self._push()
        self.blocks = self.blocks + [(block_type, tuple(ordered))]
        self.selection = []
        self._changed()
        return len(self.blocks) - 1

    def edit_block(self, block, vertices=None):
        """Replaces the vertices of block ``block`` (0-based) by ``vertices`` (default: the
        selection), ordered as in add_block."""
        block = self._block_index(block)
        vertices = list(self.selection if vertices is None else vertices)
        block_type, ordered = order_block(self.points, vertices, self.known_faces(block))
        self._push()
        blocks = list(self.blocks)
        blocks[block] = (block_type, tuple(ordered))
        self.blocks = blocks
        self.selection = []
        self._changed()
        return block

    def delete_block(self, block):
        """Deletes block ``block`` (0-based); later blocks shift down by one."""
        block = self._block_index(block)
        self._push()
        self.blocks = self.blocks[:block] + self.blocks[block + 1:]
        self._changed()

    def _block_index(self, block):
        block = int(block)
        if not 0 <= block < len(self.blocks):
            raise ValueError("there is no block {} (blocks 1..{})".format(block + 1,
                                                                         len(self.blocks)))
        return block

    def clear_blocks(self):
        self._push()
        self.blocks = []
        self._changed()

    def load_structure(self, structure, undoable=True):
        """Replaces the blocks by those of ``structure`` (core.Mesh of hex, prism and tet
        blocks): vertices within ``snap`` x the surface size of a corner become that corner, the
        others interior vertices. Returns the number of interior vertices."""
        V = np.asarray(structure.V, float).reshape(-1, 3)
        cells = np.asarray(structure.cells, np.int64).reshape(-1, 8)
        types = np.asarray(structure.types, np.int64).reshape(-1)
        bad = sorted(set(types.tolist()) - set(NODE_COUNT))
        if bad:
            raise ValueError("a polycube structure holds hex, prism and tet blocks only; found "
                             "VTK type {}".format(bad[0]))
        scale = self.scale if self.boundary is not None else float(
            np.linalg.norm(V.max(axis=0) - V.min(axis=0)) if len(V) else 1.0) or 1.0
        corners = self.points[:self.corner_count]
        mapping = np.empty(len(V), np.int64)
        interior = []
        for i, p in enumerate(V):
            if len(corners):
                d = np.linalg.norm(corners - p[None, :], axis=1)
                j = int(np.argmin(d))
                if d[j] <= self.snap * scale:
                    mapping[i] = j
                    continue
            mapping[i] = self.corner_count + len(interior)
            interior.append(p)
        blocks = []
        for r, t in enumerate(types.tolist()):
            ids = cells[r, :NODE_COUNT[t]]
            if np.any(ids < 0) or np.any(ids >= len(V)):
                raise ValueError("block {} has corner indices outside 0..{}".format(
                    r + 1, len(V) - 1))
            blocks.append((int(t), tuple(int(v) for v in mapping[ids])))
        if undoable:
            self._push()
        self.points = np.vstack([corners, np.asarray(interior, float).reshape(-1, 3)])
        self.blocks = blocks
        self.selection = []
        self._changed()
        return len(interior)

    def import_structure(self, path):
        """Reads a structure file (.k as the original program's, or .vtk/.vtu) into the builder."""
        return self.load_structure(read_structure(path))

    def export_structure(self, path):
        """Writes the blocks as a structure file (.k, .vtk, .vtu; chosen by extension)."""
        core.write_mesh(path, self.structure())

    def _state(self):
        return (self.points, self.blocks)

    def _restore(self, state):
        if state is None:
            return False
        self.points, self.blocks = state
        self.selection = []
        self._changed()
        return True

    # --------------------------------------------------------------------------------------------
    # Problems

    def block_jacobians(self):
        """Scaled Jacobian per block."""
        if not self.blocks:
            return np.zeros(0)
        mesh = self.structure()
        return np.asarray(core.cell_metrics(mesh)[0], float)

    def problems(self):
        """Everything that keeps the blocks from filling the boundary exactly once: patches
        covered by no block face or by several, block faces on no patch and in no other block,
        faces in more than two blocks, inverted and overlapping blocks, unused interior
        vertices (cached until the next edit)."""
        if self._problems is None:
            self._problems = self._find_problems()
        return list(self._problems)

    def _find_problems(self):
        problems = []
        if self.boundary is None:
            problems.append(Problem("no_boundary", "no polycube boundary to fill{}".format(
                ": " + self.boundary_error if self.boundary_error else " (no segmentation)")))
        faces = [(i, list(f)) for i, (t, b) in enumerate(self.blocks) for f in block_faces(t, b)]
        seen = {}
        for i, (t, b) in enumerate(self.blocks):
            key = face_key(b)
            if len(set(b)) != len(b):
                problems.append(Problem("inverted", "block {} ({}) uses a vertex twice".format(
                    i + 1, TYPE_NAMES[t]), blocks=[i], vertices=list(b)))
            if key in seen:
                problems.append(Problem(
                    "duplicate_block", "blocks {} and {} have the same vertices".format(
                        seen[key] + 1, i + 1), blocks=[seen[key], i], vertices=list(b)))
            seen.setdefault(key, i)
        problems += self._match_problems(faces)
        if self.blocks:
            sj = self.block_jacobians()
            for i, value in enumerate(sj.tolist()):
                t, b = self.blocks[i]
                if len(set(b)) == len(b) and not (np.isfinite(value) and 0 < value <= 1 + 1e-9):
                    problems.append(Problem(
                        "inverted", "block {} ({}) is inverted: scaled Jacobian {:.3g}".format(
                            i + 1, TYPE_NAMES[t], value), blocks=[i], vertices=list(b)))
            problems += self._overlaps()
        used = set(self.used_vertices())
        for v in range(self.corner_count, self.vertex_count):
            if v not in used:
                problems.append(Problem(
                    "unused_vertex", "interior vertex {} is used by no block (OK drops it)"
                    .format(v), vertices=[v]))
        return problems

    def _match_problems(self, faces):
        """The core's matching of the block faces ``faces`` ((block, vertices) pairs) to the
        patches (core.match_faces_to_patches) as Problems: the patches' problems in patch
        order, then the faces' in the order of their first block face."""
        patches = list(self.boundary.faces) if self.boundary is not None else []
        found, _, _ = core.match_faces_to_patches(faces, [p["corners"] for p in patches])

        def name(p):
            return "patch {} (part {})".format(patches[p]["patch"], patches[p]["id"])

        on_patches, on_faces = [], []
        for m in found:
            uses = m["faces"]
            blocks = [faces[i][0] for i in uses]
            if m["patches"]:
                p = m["patches"][-1]
                corners = [int(c) for c in patches[p]["corners"]]
                patch = [patches[q]["patch"] for q in m["patches"]]
                if m["kind"] == "patches_share_corners":
                    problem = Problem(
                        "patches_share_corners", "{} and {} have the same corners ({})".format(
                            name(m["patches"][0]), name(p), " ".join(str(c) for c in corners)),
                        patches=patch, vertices=corners, faces=[corners])
                elif m["kind"] == "patch_on_no_face":
                    problem = Problem(
                        "uncovered_patch", "{} is covered by no block face (corners {})".format(
                            name(p), " ".join(str(c) for c in corners)),
                        patches=patch, vertices=corners, faces=[corners])
                else:
                    problem = Problem(
                        "patch_covered_twice", "{} is covered by {} block faces (blocks {})".format(
                            name(p), len(uses), ", ".join(str(i + 1) for i in blocks)),
                        blocks=blocks, patches=patch, vertices=corners, faces=[corners])
                on_patches.append((p, problem))
                continue
            face = faces[uses[0]][1]
            text = " ".join(str(v) for v in face)
            if m["kind"] == "face_on_no_patch":
                if self.boundary is None:
                    continue
                problem = Problem(
                    "open_face", "face ({}) of block {} is on no patch and in no other block"
                    .format(text, blocks[0] + 1), blocks=blocks, vertices=list(face), faces=[face])
            else:
                problem = Problem(
                    "face_shared", "face ({}) is shared by {} blocks ({})".format(
                        text, len(uses), ", ".join(str(i + 1) for i in blocks)),
                    blocks=blocks, vertices=list(face), faces=[face])
            on_faces.append((uses[0], problem))
        return ([p for _, p in sorted(on_patches, key=lambda x: x[0])]
                + [p for _, p in sorted(on_faces, key=lambda x: x[0])])

    def _overlaps(self):
        """Pairs of blocks whose insides meet, shared faces or not: points spread through each
        block (block_samples: a lattice in its parameter space, pulled OVERLAP_MARGIN towards
        its middle) that lie inside another block (inside_block: inside its parameter domain,
        so curved faces count as the block's trilinear map draws them), testing only the
        samples inside the other's bounding box. A block poking into another by more than about
        OVERLAP_MARGIN / 2 of its size is found; neighbours that share a face, an edge or a
        vertex are not flagged."""
        n = len(self.blocks)
        if n < 2:
            return []
        P = self.points
        boxes, samples = [], []
        for t, b in self.blocks:
            pts = P[list(b)]
            samples.append(block_samples(t, pts))
            boxes.append((pts.min(axis=0), pts.max(axis=0)))
        lo = np.array([b[0] for b in boxes])
        hi = np.array([b[1] for b in boxes])
        tol = 1e-9 * self.scale
        # (sample, block it may lie in) pairs: samples of each block inside the bounding box of
        # another, then one Newton solve per block type.
        pairs = {}
        for a in range(n):
            others = np.flatnonzero(np.all(lo <= hi[a] + tol, axis=1)
                                    & np.all(hi >= lo[a] - tol, axis=1))
            others = others[others != a]
            if len(others) == 0:
                continue
            queries = np.vstack([samples[o] for o in others])
            owner = np.repeat(others, [len(samples[o]) for o in others])
            near = np.all((queries >= lo[a] - tol) & (queries <= hi[a] + tol), axis=1)
            if near.any():
                pairs.setdefault(self.blocks[a][0], []).append(
                    (queries[near], owner[near], np.full(int(near.sum()), a)))
        found = set()
        for t, parts in pairs.items():
            queries = np.vstack([q for q, _, _ in parts])
            owner = np.concatenate([o for _, o, _ in parts])
            container = np.concatenate([c for _, _, c in parts])
            corners = np.array([self.blocks[a][1] for a in container.tolist()], np.int64)
            inside = inside_block(t, P[corners], queries)
            for o, a in zip(owner[inside].tolist(), container[inside].tolist()):
                found.add((min(a, o), max(a, o)))
        return [Problem("overlap", "blocks {} and {} overlap".format(i + 1, j + 1),
                        blocks=[i, j], vertices=sorted(set(self.blocks[i][1])
                                                       | set(self.blocks[j][1])))
                for i, j in sorted(found)]
