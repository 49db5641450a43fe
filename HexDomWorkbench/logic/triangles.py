"""Triangle-surface helpers (numpy only): normals, the triangle adjacency, edges, connected
regions and point merging. The one place the workbench pairs triangles across their edges."""

import numpy as np


def triangle_normals(V, F):
    """Unit normals (#F x 3) and areas (#F) of the triangles F of V."""
    V = np.asarray(V, float)
    F = np.asarray(F, np.int64).reshape(-1, 3)
    n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    length = np.linalg.norm(n, axis=1)
    safe = np.where(length > 0, length, 1.0)
    return n / safe[:, None], 0.5 * length


def sorted_edges(F):
    """(edges, triangle): the three edges of every triangle (#3F x 2, each edge's vertices in
    ascending order) sorted so that equal edges are consecutive, and the triangle of each."""
    F = np.asarray(F, np.int64).reshape(-1, 3)
    edges = np.sort(F[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    tri = np.repeat(np.arange(len(F)), 3)
    order = np.lexsort((edges[:, 1], edges[:, 0]))
    return edges[order], tri[order]


def triangle_adjacency(F):
    """Pairs (#P x 2) of triangles sharing an edge (on an edge with k > 2 triangles, consecutive
    ones are paired)."""
    if len(np.asarray(F).reshape(-1, 3)) == 0:
        return np.zeros((0, 2), np.int64)
    edges, tri = sorted_edges(F)
    same = np.all(edges[1:] == edges[:-1], axis=1)
    return np.stack([tri[:-1][same], tri[1:][same]], axis=1)


def all_edges(F):
    """The distinct edges (#E x 2, vertices ascending) of the triangles F, sorted."""
    if len(np.asarray(F).reshape(-1, 3)) == 0:
        return np.zeros((0, 2), np.int64)
    edges, _ = sorted_edges(F)
    return edges[np.r_[True, np.any(edges[1:] != edges[:-1], axis=1)]]


def edge_uses(F):
    """(edges, uses): the distinct edges of F and how many triangles use each (2 everywhere on a
    closed conforming surface)."""
    edges, _ = sorted_edges(F)
    if len(edges) == 0:
        return edges, np.zeros(0, np.int64)
    start = np.r_[True, np.any(edges[1:] != edges[:-1], axis=1)]
    return edges[start], np.bincount(np.cumsum(start) - 1)


def boundary_edges(F, ids):
    """Edges (#E x 2) between triangles of different ``ids``, and edges of one triangle only."""
    if len(np.asarray(F).reshape(-1, 3)) == 0:
        return np.zeros((0, 2), np.int64)
    ids = np.asarray(ids)
    edges, tri = sorted_edges(F)
    start = np.r_[True, np.any(edges[1:] != edges[:-1], axis=1)]
    group = np.cumsum(start) - 1
    ngroups = group[-1] + 1
    lo = np.full(ngroups, np.iinfo(np.int64).max)
    hi = np.full(ngroups, np.iinfo(np.int64).min)
    np.minimum.at(lo, group, ids[tri])
    np.maximum.at(hi, group, ids[tri])
    count = np.bincount(group)
    keep = (lo != hi) | (count == 1)
    return edges[start][keep]


def union_find(n, pairs):
    """Root (the smallest member) of the set of each of 0..n-1, the ``pairs`` joined."""
    parent = list(range(n))

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a, b in pairs:
        ra, rb = find(a), find(b)
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)
    return np.array([find(a) for a in range(n)], np.int64)


def connected_regions(F, key, adjacency=None):
    """Region number (0..R-1, in order of first triangle) per triangle: triangles sharing an edge
    and the same ``key`` value belong to one region."""
    key = np.asarray(key)
    pairs = triangle_adjacency(F) if adjacency is None else adjacency
    pairs = pairs[key[pairs[:, 0]] == key[pairs[:, 1]]] if len(pairs) else pairs
    roots = union_find(len(key), pairs.tolist())
    _, first, inverse = np.unique(roots, return_index=True, return_inverse=True)
    rank = np.argsort(np.argsort(first))
    return rank[inverse].astype(np.int32)


def merge_points(V, tol):
    """Index of the representative point per row of V, merging points closer than ``tol``."""
    V = np.asarray(V, float).reshape(-1, 3)
    try:
        from scipy.spatial import cKDTree
        pairs = np.array(sorted(cKDTree(V).query_pairs(tol)), np.int64).reshape(-1, 2)
    except ImportError:
        key = np.round(V / tol).astype(np.int64)
        _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
        return first[inverse]
    return union_find(len(V), pairs.tolist())


def nearest_rows(source, target):
    """Index of the nearest row of ``source`` (#S x 3 points) for each row of ``target``."""
    source = np.asarray(source, float)
    target = np.asarray(target, float)
    try:
        from scipy.spatial import cKDTree
        return cKDTree(source).query(target)[1]
    except ImportError:
        nearest = np.empty(len(target), np.int64)
        s2 = np.einsum("ij,ij->i", source, source)
        for start in range(0, len(target), 512):
            block = target[start:start + 512]
            d = s2[None, :] - 2.0 * block @ source.T
            nearest[start:start + 512] = np.argmin(d, axis=1)
        return nearest
