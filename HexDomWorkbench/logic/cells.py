"""The faces of hex, prism and tet blocks (VTK node order, right-hand normals pointing out of the
block), as the core's one face table gives them, and the boundary of a block structure."""

import numpy as np

from .. import core

HEX, WEDGE, TET = 12, 13, 10  # VTK cell types, as core.HEX, core.WEDGE, core.TET
NODE_COUNT = {HEX: 8, WEDGE: 6, TET: 4}
# The core's face table (mesh::cell_faces), read once.
BLOCK_FACES = {t: core.cell_faces(t) for t in (HEX, WEDGE, TET)}


def face_key(vertices):
    """A face's vertices as a sorted tuple: equal for the same face seen from either block."""
    return tuple(sorted(int(v) for v in vertices))


def block_faces(block_type, vertices):
    """Faces (vertex lists, outward) of a block."""
    return [[int(vertices[i]) for i in f] for f in BLOCK_FACES[block_type]]


def structure_boundary(blocks, types):
    """(boundary faces as index lists, block type of each, all block edges #E x 2) of the blocks
    (rows of corner indices, VTK order) of ``types``: the faces in one block only."""
    count, owner = {}, {}
    edges = set()
    for cell, t in zip(blocks, types):
        for face in BLOCK_FACES.get(t, ()):
            ids = [int(cell[i]) for i in face]
            key = tuple(sorted(ids))
            count[key] = count.get(key, 0) + 1
            owner.setdefault(key, (ids, t))
            for a, b in zip(ids, ids[1:] + ids[:1]):
                edges.add((min(a, b), max(a, b)))
    boundary = [owner[k] for k, c in count.items() if c == 1]
    faces = [ids for ids, _ in boundary]
    face_types = [t for _, t in boundary]
    return faces, face_types, np.array(sorted(edges), np.int64).reshape(-1, 2)
