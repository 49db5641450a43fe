"""Surfaces as other tools export them (issue "inside-out and self-intersecting input"): `hexdom mesh`
checks its input before any stage. An inside-out box (every triangle reversed) meshes with a
warning and the same cells as the box; two overlapping boxes written as one triangle soup exit 1
naming two crossing triangles and a point, and write nothing; a cube with a cubic cavity (two
nested shells) meshes with the cavity empty; an inconsistently oriented surface is refused naming
an edge; separate solids in one file (and a solid inside another's cavity) mesh as one region each;
solids touching along a face mesh with a warning; bodies whose faces lie on each other are
refused. The STL files are written here; meshio reads them back as an independent check that they
say what the test means, VTK's Verdict measures the meshes."""

import subprocess

import meshio
import numpy as np
import pytest

import hexdom_oracles as oracles

# A box's 12 triangles, counter-clockwise seen from outside, over corners i = x + 2y + 4z.
BOX_TRIANGLES = [(0, 2, 1), (1, 2, 3), (4, 5, 6), (5, 7, 6), (0, 1, 4), (1, 5, 4),
                 (2, 6, 3), (3, 6, 7), (0, 4, 2), (2, 4, 6), (1, 3, 5), (3, 7, 5)]


def _box(lo, hi):
    corners = [(hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2])
               for i in range(8)]
    return [tuple(corners[k] for k in t) for t in BOX_TRIANGLES]


def _reversed(tris):
    return [(a, c, b) for a, b, c in tris]


def _write_stl(path, tris):
    lines = ["solid test"]
    for tri in tris:
        lines += ["  facet normal 0 0 0", "    outer loop"]
        lines += ["      vertex {:.17g} {:.17g} {:.17g}".format(*p) for p in tri]
        lines += ["    endloop", "  endfacet"]
    lines.append("endsolid test")
    path.write_text("\n".join(lines) + "\n")
    return path


def _signed_volume(path):
    m = meshio.read(path)
    P = m.points
    T = np.concatenate([b.data for b in m.cells if b.type == "triangle"])
    a, b, c = P[T[:, 0]], P[T[:, 1]], P[T[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def _mesh(hexdom_bin, src, out, *extra):
    return _mesh_default(hexdom_bin, src, out, "--size", "2.5", *extra)


def _mesh_default(hexdom_bin, src, out, *extra):
    return subprocess.run([str(hexdom_bin), "mesh", str(src), "-o", str(out), *extra], capture_output=True, text=True)


def _cells(path):
    """(points, VTK type per cell, Verdict SJ per cell, total signed volume) of a .vtu, read by VTK."""
    g, sj, types = oracles.vtu_sj_types(str(path))
    points, _, _ = oracles.grid_arrays(g)
    return points, types, sj, float(np.sum(oracles.signed_volumes(g)))


def test_an_inside_out_box_meshes_with_a_warning_and_the_box_s_cells(hexdom_bin, tmp_path):
    box = _write_stl(tmp_path / "box.stl", _box((0, 0, 0), (10, 10, 10)))
    inside_out = _write_stl(tmp_path / "inside_out.stl", _reversed(_box((0, 0, 0), (10, 10, 10))))
    assert _signed_volume(box) == pytest.approx(1000.0)
    assert _signed_volume(inside_out) == pytest.approx(-1000.0)  # meshio agrees it is inside out
    ok = _mesh(hexdom_bin, box, tmp_path / "box.vtu")
    run = _mesh(hexdom_bin, inside_out, tmp_path / "inside_out.vtu")
    assert ok.returncode == 0, ok.stderr
    assert run.returncode == 0, run.stderr
    assert "inside out" in run.stderr and "turned around" in run.stderr, run.stderr
    assert "surface volume 1000 (+0.000%)" in run.stdout, run.stdout
    assert "inside out" not in ok.stderr
    pa, types_a, sj_a, vol_a = _cells(tmp_path / "box.vtu")
    pb, types_b, sj_b, vol_b = _cells(tmp_path / "inside_out.vtu")
    assert sorted(types_a.tolist()) == sorted(types_b.tolist())
    np.testing.assert_allclose(np.sort(pa, axis=0), np.sort(pb, axis=0), atol=1e-9)
    assert np.all(sj_b > 0) and vol_b == pytest.approx(1000.0, rel=1e-6) and vol_a == pytest.approx(vol_b)


def test_overlapping_boxes_exit_1_naming_two_triangles_and_a_point(hexdom_bin, tmp_path):
    soup = _write_stl(tmp_path / "soup.stl", _box((0, 0, 0), (10, 10, 10)) + _box((5, 5, 5), (15, 15, 15)))
    out = tmp_path / "soup.vtu"
    run = _mesh(hexdom_bin, soup, out)
    assert run.returncode == 1, run.stderr
    assert "crosses itself: triangles" in run.stderr and " cross at (" in run.stderr, run.stderr
    assert not out.exists()
    assert "polycube" not in run.stderr  # refused before any meshing stage ran


def test_a_cube_with_a_cubic_cavity_meshes_with_the_cavity_empty(hexdom_bin, tmp_path):
    # The inner shell facing into the cavity, as a correct export writes it; and facing out of it.
    for name, inner in (("cavity", _reversed(_box((3, 3, 3), (7, 7, 7)))),
                        ("cavity_wrong", _box((3, 3, 3), (7, 7, 7)))):
        src = _write_stl(tmp_path / f"{name}.stl", _box((0, 0, 0), (10, 10, 10)) + inner)
        out = tmp_path / f"{name}.vtu"
        run = _mesh(hexdom_bin, src, out, "--allow-inverted")
        assert run.returncode == 0, run.stderr
        assert ("cavity's shell" in run.stderr) == (name == "cavity_wrong"), run.stderr
        _, _, sj, volume = _cells(out)
        assert np.sum(sj <= 0) == 0
        assert volume == pytest.approx(1000.0 - 64.0, rel=0.01)


def test_an_inconsistently_oriented_surface_is_refused_naming_an_edge(hexdom_bin, tmp_path):
    tris = _box((0, 0, 0), (10, 10, 10))
    tris[0] = (tris[0][0], tris[0][2], tris[0][1])
    src = _write_stl(tmp_path / "mixed.stl", tris)
    out = tmp_path / "mixed.vtu"
    run = _mesh(hexdom_bin, src, out)
    assert run.returncode == 1
    assert "inconsistently oriented" in run.stderr and "edge (" in run.stderr, run.stderr
    assert not out.exists()


def _regions(path):
    """Region id, VTK type and signed volume per cell, and the points per cell, of a .vtu read by VTK."""
    from vtk.util.numpy_support import vtk_to_numpy
    g = oracles.read_vtu(str(path))
    region = vtk_to_numpy(g.GetCellData().GetArray("region"))
    return region, np.asarray(oracles.signed_volumes(g)), g


def test_separate_solids_mesh_as_one_region_each(hexdom_bin, tmp_path):
    # The second box inside out: turned around, and the volume compared with the solids' 1500.
    src = _write_stl(tmp_path / "two.stl", _box((0, 0, 0), (10, 10, 10)) + _reversed(_box((20, 0, 0), (30, 10, 5))))
    out = tmp_path / "two.vtu"
    run = _mesh(hexdom_bin, src, out)
    assert run.returncode == 0, run.stderr
    assert "solid 1 of 2" in run.stderr and "solid 2 of 2" in run.stderr, run.stderr
    assert "the outer shell of solid 2 of 12 triangles faced inward" in run.stderr, run.stderr
    assert "surface volume 1500 (+0.000%)" in run.stdout, run.stdout
    region, volume, g = _regions(out)
    assert sorted(set(region.tolist())) == [1, 2]
    assert volume[region == 1].sum() == pytest.approx(1000.0, rel=1e-6)
    assert volume[region == 2].sum() == pytest.approx(500.0, rel=1e-6)
    _, _, sj, _ = _cells(out)
    assert np.all(sj > 0)
    for c in range(g.GetNumberOfCells()):  # each region's cells lie in its own box
        x = [g.GetCell(c).GetPoints().GetPoint(i)[0] for i in range(g.GetCell(c).GetNumberOfPoints())]
        assert (max(x) <= 10 + 1e-9) if region[c] == 1 else (min(x) >= 20 - 1e-9)


def test_a_solid_inside_another_s_cavity_is_its_own_region(hexdom_bin, tmp_path):
    shells = (_box((0, 0, 0), (12, 12, 12)) + _reversed(_box((2, 2, 2), (10, 10, 10)))
              + _box((4, 4, 4), (8, 8, 8)))
    src = _write_stl(tmp_path / "nested.stl", shells)
    out = tmp_path / "nested.vtu"
    run = _mesh(hexdom_bin, src, out)
    assert run.returncode == 0, run.stderr
    region, volume, _ = _regions(out)
    assert sorted(set(region.tolist())) == [1, 2]
    assert volume[region == 1].sum() == pytest.approx(12.0 ** 3 - 8.0 ** 3, rel=1e-3)
    assert volume[region == 2].sum() == pytest.approx(64.0, rel=1e-6)


def test_solids_touching_along_a_face_mesh_as_two_regions_with_a_warning(hexdom_bin, tmp_path):
    # A smaller box against the face x = 10 of a larger one: the two surfaces lie on each other
    # there, facing opposite ways (the larger face's diagonal meets the smaller box's edges: a
    # contact, not a crossing).
    src = _write_stl(tmp_path / "touching.stl", _box((0, 0, 0), (10, 10, 10)) + _box((10, 2, 2), (20, 8, 8)))
    out = tmp_path / "touching.vtu"
    run = _mesh(hexdom_bin, src, out)
    assert run.returncode == 0, run.stderr
    assert "solids 1 and 2 touch" in run.stderr and "do not conform" in run.stderr, run.stderr
    region, volume, _ = _regions(out)
    assert sorted(set(region.tolist())) == [1, 2]
    assert volume[region == 1].sum() == pytest.approx(1000.0, rel=1e-6)
    assert volume[region == 2].sum() == pytest.approx(360.0, rel=1e-6)
    _, _, sj, _ = _cells(out)
    assert np.all(sj > 0)


def test_boxes_overlapping_along_coplanar_faces_are_refused_naming_two_triangles(hexdom_bin, tmp_path):
    # Two boxes overlapping whose faces y = 0, 10 and z = 0, 10 lie on each other (where an edge of
    # one meets a face of the other, the two surfaces touch: no edge passes through a face).
    src = _write_stl(tmp_path / "overlap.stl", _box((0, 0, 0), (10, 10, 10)) + _box((5, 0, 0), (15, 10, 10)))
    out = tmp_path / "overlap.vtu"
    run = _mesh(hexdom_bin, src, out)
    assert run.returncode == 1, run.stderr
    assert "lies on itself: triangles" in run.stderr and "facing the same way at (" in run.stderr, run.stderr
    assert not out.exists()
