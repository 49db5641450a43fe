"""`hexdom remesh`: a closed triangle surface remeshed onto itself.

Input: a 20 x 10 x 5 box as 12 needle-free but huge STL triangles (written here), and its copy
without one facet. Oracles: meshio reads the result; closedness, planes, angles and volume are
computed here in numpy.
"""

import subprocess

import meshio
import numpy as np

BOX = np.array([[x, y, z] for z in (0, 5) for y in (0, 10) for x in (0, 20)], float)
QUADS = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
TRIS = [t for a, b, c, d in QUADS for t in ([a, b, c], [a, c, d])]


def _stl(path, tris):
    with open(path, "w") as f:
        f.write("solid box\n")
        for t in tris:
            p = BOX[t]
            n = np.cross(p[1] - p[0], p[2] - p[0])
            f.write(" facet normal %g %g %g\n  outer loop\n" % tuple(n / np.linalg.norm(n)))
            for x in p:
                f.write("   vertex %g %g %g\n" % tuple(x))
            f.write("  endloop\n endfacet\n")
        f.write("endsolid box\n")


def _run(hexdom_bin, *args):
    return subprocess.run([str(hexdom_bin), *map(str, args)], capture_output=True, text=True)


def _read(path):
    m = meshio.read(path)
    F = np.vstack([c.data for c in m.cells if c.type == "triangle"])
    return np.asarray(m.points, float), F


def _volume(V, F):
    return float(np.einsum("ij,ij->i", V[F[:, 0]], np.cross(V[F[:, 1]], V[F[:, 2]])).sum() / 6)


def test_remesh_keeps_the_sharp_edges_and_makes_good_triangles(hexdom_bin, tmp_path):
    _stl(tmp_path / "box.stl", TRIS)
    out = tmp_path / "box.vtk"
    r = _run(hexdom_bin, "remesh", "-i", tmp_path / "box.stl", "-o", out, "--size", 1.0)
    assert r.returncode == 0, r.stderr
    assert "12 curves, 8 corners" in r.stderr
    V, F = _read(out)
    edges = np.sort(F[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    _, uses = np.unique(edges, axis=0, return_counts=True)
    assert set(uses.tolist()) == {2}  # closed and manifold
    # Every vertex on the box: one coordinate at a face of it, the others inside.
    on_face = (np.isclose(V, 0, atol=1e-12) | np.isclose(V, [20, 10, 5], atol=1e-12)).any(axis=1)
    assert on_face.all() and (V >= -1e-12).all() and (V <= [20 + 1e-12, 10 + 1e-12, 5 + 1e-12]).all()
    assert abs(_volume(V, F) - 1000.0) < 1e-9  # the edges stay sharp
    for corner in BOX:
        assert np.min(np.linalg.norm(V - corner, axis=1)) < 1e-12
    lengths = np.linalg.norm(V[edges[:, 0]] - V[edges[:, 1]], axis=1)
    assert 0.7 < np.median(lengths) < 1.4 and lengths.max() < 1.5
    P = [V[F[:, i]] for i in range(3)]
    ang = [np.degrees(np.arctan2(np.linalg.norm(np.cross(P[(i + 1) % 3] - P[i], P[(i + 2) % 3] - P[i]), axis=1),
                                 np.einsum("ij,ij->i", P[(i + 1) % 3] - P[i], P[(i + 2) % 3] - P[i])))
           for i in range(3)]
    assert np.min(ang) > 25.0


def test_remesh_without_feature_angle_rounds_the_edges(hexdom_bin, tmp_path):
    # One part and no feature angle: nothing holds the box's edges, chords cut them.
    _stl(tmp_path / "box.stl", TRIS)
    out = tmp_path / "box.vtk"
    r = _run(hexdom_bin, "remesh", "-i", tmp_path / "box.stl", "-o", out, "--size", 1.0, "--feature-angle", 0)
    assert r.returncode == 0, r.stderr
    assert "0 curves, 0 corners" in r.stderr
    V, F = _read(out)
    assert _volume(V, F) < 1000.0 - 1e-3


def test_remesh_of_an_open_surface_is_refused(hexdom_bin, tmp_path):
    _stl(tmp_path / "open.stl", TRIS[:-1])
    out = tmp_path / "open.vtk"
    r = _run(hexdom_bin, "remesh", "-i", tmp_path / "open.stl", "-o", out, "--size", 1.0)
    assert r.returncode == 1
    assert "open.stl" in r.stderr and "open: edge (" in r.stderr
    assert not out.exists()
