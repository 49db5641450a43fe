"""Meshes built in the tests (numpy only), shared by the App and GUI tests."""

import os

import numpy as np

HEX, WEDGE, TET = 12, 13, 10


def data_root():
    return os.environ.get("HEXDOM_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "..",
                                                      "shared", "data"))


def rockerarm_path():
    """Path of the paper's rockerarm polycube structure (hex, prism, tet), or None."""
    path = os.path.join(data_root(), "hexdom", "rockerarm", "rockerarm_polycube_withtet.k")
    return path if os.path.isfile(path) else None


def box_mesh(L, W, H, nx, ny, nz, wedge_layers=0):
    """Structured mesh of [0,L]x[0,W]x[0,H] in VTK order; node coordinates lie exactly on the
    box faces. The lowest ``wedge_layers`` layers (in z) are split into two wedges per hex by the
    diagonal of the y-z cross-section (wedges extruded along x, conforming with the hexes above).

    Returns (V, cells, types) as numpy arrays (#V x 3, #C x 8 with -1 padding, #C).
    """
    xs, ys, zs = np.linspace(0, L, nx + 1), np.linspace(0, W, ny + 1), np.linspace(0, H, nz + 1)
    X, Y, Z = np.meshgrid(xs, ys, zs, indexing="ij")
    V = np.c_[X.ravel(), Y.ravel(), Z.ravel()]

    def n(i, j, k):
        return (i * (ny + 1) + j) * (nz + 1) + k

    cells, types = [], []
    for i in range(nx):
        for j in range(ny):
            for k in range(nz):
                if k >= wedge_layers:
                    cells.append([n(i, j, k), n(i + 1, j, k), n(i + 1, j + 1, k), n(i, j + 1, k),
                                  n(i, j, k + 1), n(i + 1, j, k + 1), n(i + 1, j + 1, k + 1),
                                  n(i, j + 1, k + 1)])
                    types.append(HEX)
                    continue
                # Cross-section corners a (j,k), b (j+1,k), c (j+1,k+1), d (j,k+1) at x_i and
                # x_{i+1}. VTK wedge: the first triangle's right-hand normal points away from
                # the second one (here -x), so go a -> c -> b.
                for tri in ((0, 2, 1), (0, 3, 2)):
                    q0 = [n(i, j, k), n(i, j + 1, k), n(i, j + 1, k + 1), n(i, j, k + 1)]
                    q1 = [n(i + 1, j, k), n(i + 1, j + 1, k), n(i + 1, j + 1, k + 1),
                          n(i + 1, j, k + 1)]
                    cells.append([q0[t] for t in tri] + [q1[t] for t in tri] + [-1, -1])
                    types.append(WEDGE)
    return V, np.array(cells, dtype=np.int32), np.array(types, dtype=np.int32)


def mixed_sample():
    """Three unit cells along x: a hex, a hex cut into two wedges (extruded along z) and a hex
    cut into six tetrahedra; every cell type shows on the outside.

    Returns (V, cells, types, region) with region = 1, 2, 3 per original cell.
    """
    V, _, _ = box_mesh(3.0, 1.0, 1.0, 3, 1, 1)

    def n(i, j, k):
        return (i * 2 + j) * 2 + k

    cells, types, region = [], [], []
    cells.append([n(0, 0, 0), n(1, 0, 0), n(1, 1, 0), n(0, 1, 0),
                  n(0, 0, 1), n(1, 0, 1), n(1, 1, 1), n(0, 1, 1)])
    types.append(HEX)
    region.append(1)
    # Wedges extruded along +z: bottom triangles clockwise seen from above (normal -z).
    for a, b, c in (((1, 0), (2, 1), (2, 0)), ((1, 0), (1, 1), (2, 1))):
        bottom = [n(x, y, 0) for x, y in (a, b, c)]
        top = [n(x, y, 1) for x, y in (a, b, c)]
        cells.append(bottom + top + [-1, -1])
        types.append(WEDGE)
        region.append(2)
    # Six tetrahedra around the diagonal (2,0,0)-(3,1,1) (Kuhn subdivision), each oriented
    # positively by swapping two nodes when needed.
    corner = {(dx, dy, dz): n(2 + dx, dy, dz) for dx in (0, 1) for dy in (0, 1) for dz in (0, 1)}
    for perm in ((0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)):
        path = [(0, 0, 0)]
        for axis in perm:
            p = list(path[-1])
            p[axis] = 1
            path.append(tuple(p))
        tet = [corner[p] for p in path]
        a, b, c, d = (V[t] for t in tet)
        if np.dot(np.cross(b - a, c - a), d - a) < 0:
            tet[1], tet[2] = tet[2], tet[1]
        cells.append(tet + [-1] * 4)
        types.append(TET)
        region.append(3)
    return (V, np.array(cells, dtype=np.int32), np.array(types, dtype=np.int32),
            np.array(region, dtype=np.int32))


def example_path(name):
    """Path of a bundled example file (examples/data/<name>) of the repository under test."""
    here = os.environ.get("HEXDOM_FC_TEST_DIR") or os.path.dirname(os.path.abspath(__file__))
    return os.path.join(here, "..", "..", "examples", "data", name)


def box_structure(L, W, H, origin=(0.0, 0.0, 0.0)):
    """One hex block spanning the box [0,L]x[0,W]x[0,H] (+ origin): (V, cells, types)."""
    V, cells, types = box_mesh(L, W, H, 1, 1, 1)
    return V + np.asarray(origin, float), cells, types


def closed_surface_checks(V, F):
    """(edge use counts as a set, signed volume, area) of a triangle surface."""
    V = np.asarray(V, float)
    F = np.asarray(F, np.int64).reshape(-1, 3)
    edges = np.sort(F[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()
    return set(counts.tolist()), volume, area


def edge_lengths(V, F):
    V = np.asarray(V, float)
    F = np.asarray(F, np.int64).reshape(-1, 3)
    edges = np.unique(np.sort(F[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1), axis=0)
    return np.linalg.norm(V[edges[:, 0]] - V[edges[:, 1]], axis=1)


def island(editor, patch_id=5):
    """Triangles (an array) around a triangle in the middle of ``patch_id`` touching no other
    patch, for a PatchEditor (HexDomWorkbench.logic.patch_editing) to plant a patch inside another."""
    tris = np.flatnonzero(editor.patches == patch_id)
    inner = [t for t in tris.tolist()
             if all(set(editor.patches[editor.vertex_triangles(v)].tolist()) == {patch_id}
                    for v in editor.F[t])]
    centre = editor.V[editor.F[tris]].mean(axis=(0, 1))
    t0 = min(inner, key=lambda t: np.linalg.norm(editor.V[editor.F[t]].mean(axis=0) - centre))
    ring = np.unique(np.concatenate([editor.vertex_triangles(v) for v in editor.F[t0]]))
    return np.array([t for t in ring.tolist() if t in set(inner)])


# A box's 12 triangles, counter-clockwise seen from outside, over corners i = x + 2y + 4z.
BOX_TRIANGLES = [(0, 2, 1), (1, 2, 3), (4, 5, 6), (5, 7, 6), (0, 1, 4), (1, 5, 4),
                 (2, 6, 3), (3, 6, 7), (0, 4, 2), (2, 4, 6), (1, 3, 5), (3, 7, 5)]


def box_triangles(lo, hi, reverse=False):
    """The box [lo, hi] as 12 triangles of corner tuples, facing out (or in, ``reverse``)."""
    corners = [(hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2])
               for i in range(8)]
    tris = [(a, c, b) if reverse else (a, b, c) for a, b, c in BOX_TRIANGLES]
    return [tuple(corners[k] for k in t) for t in tris]


def write_stl(path, tris):
    """An ASCII STL of the triangles ``tris`` (corner tuples); returns the path as a string."""
    lines = ["solid t"]
    for tri in tris:
        lines += ["facet normal 0 0 0", "outer loop"]
        lines += ["vertex {!r} {!r} {!r}".format(*map(float, p)) for p in tri] + ["endloop", "endfacet"]
    with open(str(path), "w") as f:
        f.write("\n".join(lines + ["endsolid t"]) + "\n")
    return str(path)
