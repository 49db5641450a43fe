"""core.Mesh <-> Fem.FemMesh.

core.Mesh keeps VTK node order; Fem.FemMesh (SMESH's SMDS) orders hexahedra and tetrahedra
differently (see /work/shared/REFERENCE.md, "FreeCAD 0.20.2 facts"):

- hexahedron: smds = vtk[0, 3, 2, 1, 4, 7, 6, 5]
- tetrahedron: smds = vtk[0, 2, 1, 3]
- pentahedron (wedge), triangle, quadrangle: the same order.

Second order (FreeCAD's own .inp import, femmesh/importInpMesh.py, gives SMDS's order from
CalculiX's, which is VTK's for C3D20 and C3D10): the corners as above, the mid-edge nodes on the
edges between them in the same pattern, so that

- hexahedron 20: smds = vtk[0, 3, 2, 1, 4, 7, 6, 5, 11, 10, 9, 8, 15, 14, 13, 12, 16, 19, 18, 17]
- tetrahedron 10: smds = vtk[0, 2, 1, 3, 6, 5, 4, 7, 9, 8]
- pentahedron 15: the same order.

Each permutation is its own inverse, so one table serves both directions. Nodes get ids 1..#V in
row order and cells ids 1..#C in row order, so cell id ``c + 1`` is row ``c`` (ElementColor and
the region list rely on it).
"""

import numpy as np

from .. import core

# VTK type -> (node count, permutation between VTK and SMDS order; an involution).
_SMDS_ORDER = {
    core.HEX: (8, (0, 3, 2, 1, 4, 7, 6, 5)),
    core.TET: (4, (0, 2, 1, 3)),
    core.WEDGE: (6, (0, 1, 2, 3, 4, 5)),
    core.TRIANGLE: (3, (0, 1, 2)),
    core.QUAD: (4, (0, 1, 2, 3)),
    core.HEX20: (20, (0, 3, 2, 1, 4, 7, 6, 5, 11, 10, 9, 8, 15, 14, 13, 12, 16, 19, 18, 17)),
    core.TET10: (10, (0, 2, 1, 3, 6, 5, 4, 7, 9, 8)),
    core.WEDGE15: (15, tuple(range(15))),
}
_VOLUME_TYPES = (core.HEX, core.TET, core.WEDGE, core.HEX20, core.TET10, core.WEDGE15)
_SECOND_ORDER = {10: core.TET10, 15: core.WEDGE15, 20: core.HEX20}

# Linear corner count of an SMDS element (quadratic elements list their corners first) -> VTK type.
_VOLUME_BY_NODE_COUNT = {4: core.TET, 10: core.TET, 6: core.WEDGE, 15: core.WEDGE,
                         8: core.HEX, 20: core.HEX}
_FACE_BY_NODE_COUNT = {3: core.TRIANGLE, 6: core.TRIANGLE, 4: core.QUAD, 8: core.QUAD}


def to_femmesh(mesh):
    """Returns a new Fem.FemMesh holding ``mesh`` (nodes 1..#V, cells 1..#C in row order).

    Volumes go through addVolume and triangles / quads through addFace; any other cell type raises
    ValueError naming the row.
    """
    import Fem

    fem = Fem.FemMesh()
    V = np.asarray(mesh.V, dtype=float)
    for i, (x, y, z) in enumerate(V.tolist()):
        fem.addNode(x, y, z, i + 1)
    cells = np.asarray(mesh.cells)
    types = np.asarray(mesh.types)
    for t in np.unique(types).tolist():
        if t not in _SMDS_ORDER:
            row = int(np.flatnonzero(types == t)[0])
            raise ValueError("cell {}: VTK cell type {} has no Fem.FemMesh element".format(row, t))
    # Reorder per type in bulk, then add row by row so that ids follow rows.
    smds = np.full(cells.shape, -1, dtype=np.int64)
    for t, (n, perm) in _SMDS_ORDER.items():
        rows = types == t
        if np.any(rows):
            smds[rows, :n] = cells[rows][:, list(perm)] + 1
    for c, (t, ids) in enumerate(zip(types.tolist(), smds.tolist())):
        n = _SMDS_ORDER[t][0]
        if t in _VOLUME_TYPES:
            fem.addVolume(ids[:n], c + 1)
        else:
            fem.addFace(ids[:n], c + 1)
    return fem


def set_node_groups(fem, groups):
    """Replaces the node groups of Fem.FemMesh ``fem`` named in ``groups`` ({name: 0-based node
    indices}; node k is FemMesh node k + 1, as to_femmesh numbers them) with those nodes."""
    names = {fem.getGroupName(g): g for g in fem.Groups}
    for name, nodes in groups.items():
        if name in names:
            fem.removeGroup(names[name])
        g = fem.addGroup(name, "Node")
        fem.addGroupElements(g, [int(i) + 1 for i in nodes])
    return fem


def node_groups(fem, prefix=""):
    """{name: sorted FemMesh node ids} of the node groups of ``fem`` whose name starts with ``prefix``."""
    return {fem.getGroupName(g): sorted(fem.getGroupElements(g)) for g in fem.Groups
            if fem.getGroupName(g).startswith(prefix) and fem.getGroupElementType(g) == "Node"}


def from_femmesh(fem, with_ids=False, corners_only=False):
    """Returns the core.Mesh held by a Fem.FemMesh (VTK order): second order (hex20 / wedge15 /
    tet10, cells #C x 20) when every volume is second order and not ``corners_only``, else the
    first-order cells of the volumes' corners.

    Cells come in increasing element id, nodes in increasing node id. A mesh without volumes gives
    its faces instead. Region ids are 0 (FemMesh has no place for them; HexDom Mesh objects keep
    them in their Region property). With ``with_ids`` returns ``(mesh, node_ids, cell_ids)``.
    Raises ValueError for elements core cannot hold (pyramids, polyhedra).
    """
    nodes = fem.Nodes  # {id: Vector}
    node_ids = np.array(sorted(nodes), dtype=np.int64)
    V = np.array([tuple(nodes[i]) for i in node_ids.tolist()], dtype=float).reshape(-1, 3)
    index = {nid: k for k, nid in enumerate(node_ids.tolist())}

    cell_ids = sorted(fem.Volumes)
    by_count = _VOLUME_BY_NODE_COUNT
    if not cell_ids:
        cell_ids = sorted(fem.Faces)
        by_count = _FACE_BY_NODE_COUNT
    elements = [fem.getElementNodes(eid) for eid in cell_ids]
    second = (not corners_only and by_count is _VOLUME_BY_NODE_COUNT and elements
              and all(len(e) in _SECOND_ORDER for e in elements))
    cells = np.full((len(cell_ids), 20 if second else 8), -1, dtype=np.int32)
    types = np.zeros(len(cell_ids), dtype=np.int32)
    for row, (eid, smds) in enumerate(zip(cell_ids, elements)):
        t = _SECOND_ORDER[len(smds)] if second else by_count.get(len(smds))
        if t is None:
            raise ValueError("element {} has {} nodes: HexDom meshes hold tetrahedra, wedges and "
                             "hexahedra (and triangles, quads) only".format(eid, len(smds)))
        n, perm = _SMDS_ORDER[t]
        corners = smds[:n]
        cells[row, :n] = [index[corners[p]] for p in perm]
        types[row] = t
    region = np.zeros(len(cell_ids), dtype=np.int32)
    mesh = core.Mesh(V, cells, types, region)
    if with_ids:
        return mesh, node_ids, np.array(cell_ids, dtype=np.int64)
    return mesh
