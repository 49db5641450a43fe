"""Element size bounds (issue "element size that FEM users can steer"): `hexdom mesh --max-size`,
`--min-size` and `--cells-across`, as FreeCAD's Gmsh mesher offers CharacteristicLengthMax / Min.

Oracles: VTK reads the meshes, Verdict measures edge ratios; node coordinates count the cells
across a thin axis; the bundled bracket's B-rep volume (OpenCASCADE, printed by the program) is
compared with VTK's volume of the cells."""

import re
from pathlib import Path

import numpy as np
import pytest

import hexdom_oracles as oracles
from test_cli_input_checks import _box, _mesh_default, _write_stl

BRACKET = Path(__file__).resolve().parents[2] / "examples" / "data" / "bracket.step"


def _levels(points, axis):
    """Distinct node coordinates along ``axis`` (to 1e-9): cells across + 1 on a box."""
    return len(np.unique(np.round(points[:, axis], 9)))


def _hex_edge_lengths(g):
    P, types, conn = oracles.grid_arrays(g)
    hexes = np.array([c for c, t in zip(conn, types) if t == 12])
    edges = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
    return np.concatenate([np.linalg.norm(P[hexes[:, a]] - P[hexes[:, b]], axis=1) for a, b in edges])


def test_a_min_size_above_the_max_size_is_refused_before_any_work(hexdom_bin, tmp_path):
    src = _write_stl(tmp_path / "box.stl", _box((0, 0, 0), (10, 10, 10)))
    out = tmp_path / "box.vtu"
    run = _mesh_default(hexdom_bin, src, out, "--max-size", "1", "--min-size", "2")
    assert run.returncode != 0
    assert "min size 2 is larger than the max size 1" in run.stderr, run.stderr
    assert not out.exists()


def test_a_min_size_gives_a_thin_plate_one_cell_across_without_needles(hexdom_bin, tmp_path):
    # 100 x 100 x 0.5: two cells of 0.25 across by default (80 x 80 x 2); with cells of at least
    # 0.5, one across and 40 x 40 of 2.5 beside it (at most 5 to 1).
    src = _write_stl(tmp_path / "plate.stl", _box((0, 0, 0), (100.0, 100.0, 0.5)))
    out = tmp_path / "plate.vtu"
    run = _mesh_default(hexdom_bin, src, out, "--min-size", "0.5")
    assert run.returncode == 0, run.stderr
    g = oracles.read_vtu(str(out))
    sj, er = oracles.verdict_metrics(g)
    assert g.GetNumberOfCells() == 40 * 40
    assert sj.min() > 0.99 and er.max() <= 5.0 + 1e-9, (sj.min(), er.max())
    P, _, _ = oracles.grid_arrays(g)
    assert _levels(P, 2) == 2
    assert float(np.sum(oracles.signed_volumes(g))) == pytest.approx(5000.0, rel=1e-9)


@pytest.mark.parametrize("method", ["polycube", "overlay"])
def test_cells_across_a_rod_as_asked_by_either_path(hexdom_bin, tmp_path, method):
    # 200 x 1 x 1: cells across 4, so no cell thicker than 0.25 across and none longer than 5 x that.
    src = _write_stl(tmp_path / "rod.stl", _box((0, 0, 0), (200.0, 1.0, 1.0)))
    out = tmp_path / "rod.vtu"
    run = _mesh_default(hexdom_bin, src, out, "--cells-across", "4", "--method", method)
    assert run.returncode == 0, run.stderr
    g = oracles.read_vtu(str(out))
    sj, er = oracles.verdict_metrics(g)
    P, _, _ = oracles.grid_arrays(g)
    assert _levels(P, 1) >= 5 and _levels(P, 2) >= 5, (_levels(P, 1), _levels(P, 2))
    assert float(np.sum(oracles.signed_volumes(g))) == pytest.approx(200.0, rel=1e-6 if method == "polycube" else 1e-3)
    if method == "polycube":  # cubes of 0.25 x 1.25: exactly 160 x 4 x 4
        assert g.GetNumberOfCells() == 160 * 4 * 4
        assert er.max() <= 5.0 + 1e-9 and sj.min() > 0.99
    else:
        assert sj.min() > 0


def test_the_overlay_grid_stops_at_the_min_size(hexdom_bin, tmp_path):
    # 30 x 30 x 0.6: the overlay's grid would take 0.2 across (3 cells); with a min size of 0.3 its
    # thinnest spacing (the program's overlay line) is at least that.
    src = _write_stl(tmp_path / "plate.stl", _box((0, 0, 0), (30.0, 30.0, 0.6)))
    out = tmp_path / "plate.vtu"
    run = _mesh_default(hexdom_bin, src, out, "--method", "overlay", "--min-size", "0.3")
    assert run.returncode == 0, run.stderr
    m = re.search(r"overlay: spacing ([\d.eE+-]+) \(thinnest ([\d.eE+-]+)", run.stderr)
    assert m, run.stderr
    assert 0.3 * (1 - 1e-9) <= float(m.group(2)) < 0.33, m.group(0)
    g = oracles.read_vtu(str(out))
    assert float(np.sum(oracles.signed_volumes(g))) == pytest.approx(540.0, rel=1e-3)


def test_a_max_size_on_a_cad_part_tessellates_and_meshes_with_it(hexdom_bin, tmp_path):
    # The bundled bracket: default size (its diagonal / 30) about 2.9; with --max-size 2 the
    # triangles and the cells take 2: more cells, edges about that long, on the B-rep.
    assert BRACKET.is_file(), BRACKET
    default, bounded = tmp_path / "default.vtu", tmp_path / "bounded.vtu"
    run0 = _mesh_default(hexdom_bin, BRACKET, default)
    run = _mesh_default(hexdom_bin, BRACKET, bounded, "--max-size", "2")
    assert run0.returncode == 0 and run.returncode == 0, (run0.stderr, run.stderr)
    m = re.search(r"tessellate: size ([\d.]+), within the min and max size: 2\b", run.stderr)
    assert m and float(m.group(1)) > 2, run.stderr
    g0, g = oracles.read_vtu(str(default)), oracles.read_vtu(str(bounded))
    assert g.GetNumberOfCells() > 2 * g0.GetNumberOfCells()
    assert np.median(_hex_edge_lengths(g)) <= 2.0 < np.median(_hex_edge_lengths(g0))
    sj, _ = oracles.verdict_metrics(g)
    assert sj.min() > 0
    brep = float(re.search(r"B-rep volume ([\d.eE+-]+)", run.stdout).group(1))
    assert float(np.sum(oracles.signed_volumes(g))) == pytest.approx(brep, rel=0.01)


def _quads_on_hole(g, centre=(40.0, 20.0), radius=6.0, depth=10.0):
    """Mean edge length of each boundary quad whose nodes lie on the bracket's hole (Face10)."""
    P, types, conn = oracles.grid_arrays(g)
    count = {}
    for c, t in zip(conn, types):
        if t != 12:
            continue
        for f in ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)):
            q = tuple(c[i] for i in f)
            key = tuple(sorted(q))
            count[key] = (count.get(key, (0, q))[0] + 1, q)
    sizes = []
    for n, q in count.values():
        x = P[list(q)]
        on = np.abs(np.hypot(x[:, 0] - centre[0], x[:, 1] - centre[1]) - radius) < 1e-6
        if n == 1 and on.all() and (x[:, 2] > -1e-6).all() and (x[:, 2] < depth + 1e-6).all():
            sizes.append(np.mean(np.linalg.norm(x - np.roll(x, 1, axis=0), axis=1)))
    return np.array(sizes)


def _cell_sizes_and_centres(g):
    P, types, conn = oracles.grid_arrays(g)
    return np.cbrt(np.abs(oracles.signed_volumes(g))), np.array([P[c].mean(axis=0) for c in conn])


def _valid_whole_and_as_before_far_away(g0, g, run):
    """Asserts the bracket's mesh g with a local size on its hole: worst SJ above 0.3 (Verdict),
    the B-rep's volume within 1%, and far from the hole (the upright, x < 10 and z > 20) the cell
    sizes of g0, its mesh without it. Returns g's cell sizes (cube roots of volumes)."""
    sj, _ = oracles.verdict_metrics(g)
    assert sj.min() > 0.3, sj.min()
    brep = float(re.search(r"B-rep volume ([\d.eE+-]+)", run.stdout).group(1))
    assert float(np.sum(oracles.signed_volumes(g))) == pytest.approx(brep, rel=0.01)
    s0, c0 = _cell_sizes_and_centres(g0)
    s, c = _cell_sizes_and_centres(g)
    far0, far = (c0[:, 0] < 10) & (c0[:, 2] > 20), (c[:, 0] < 10) & (c[:, 2] > 20)
    assert np.median(s[far]) == pytest.approx(np.median(s0[far0]), rel=0.2)
    return s


def test_a_local_size_on_the_bracket_hole_refines_there_and_grades_back(hexdom_bin, tmp_path):
    # Face10 of the bundled bracket is its hole (radius 6 through the 10 mm base at x 40, y 20).
    # Asked 1 there (the default size is about 2.9) of the overlay path: its grid refined by
    # thirds near the hole. The quads on the hole are about 1; neighbours grade; far from the hole
    # the cells are as in the overlay mesh without it.
    assert BRACKET.is_file(), BRACKET
    plain, local = tmp_path / "plain.vtu", tmp_path / "local.vtu"
    run0 = _mesh_default(hexdom_bin, BRACKET, plain, "--method", "overlay")
    run = _mesh_default(hexdom_bin, BRACKET, local, "--face-size", "10=1", "--method", "overlay")
    assert run0.returncode == 0 and run.returncode == 0, (run0.stderr, run.stderr)
    assert "spacing 2.94118 (thinnest 0.952381, 1 octree levels)" in run.stderr, run.stderr
    g0, g = oracles.read_vtu(str(plain)), oracles.read_vtu(str(local))
    q0, q = _quads_on_hole(g0), _quads_on_hole(g)
    assert len(q) > 5 * len(q0), (len(q), len(q0))
    assert abs(np.median(q) - 1.0) <= 0.2, np.median(q)
    assert 0.7 <= np.percentile(q, 10) and np.percentile(q, 90) <= 1.3, np.percentile(q, [10, 90])
    s = _valid_whole_and_as_before_far_away(g0, g, run)
    # Neighbours graded: the 3-refinement templates' pieces reach about 2.05 times the small cubes
    # beside them, 2.35 after smoothing here.
    ratios = _neighbour_ratios(g, s)
    assert np.percentile(ratios, 99) <= 2.0 and max(ratios) < 2.6, (np.percentile(ratios, 99), max(ratios))


def _neighbour_ratios(g, sizes):
    """Per pair of hexes sharing a face: the larger size over the smaller (sizes per cell)."""
    P, types, conn = oracles.grid_arrays(g)
    owner = {}
    ratios = []
    for i, cell in enumerate(conn):
        for f in ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)):
            key = tuple(sorted(cell[k] for k in f))
            if key in owner:
                a, b = sizes[owner[key]], sizes[i]
                ratios.append(max(a, b) / min(a, b))
            else:
                owner[key] = i
    return np.array(ratios)


def test_a_local_size_refines_the_polycube_mesh_by_thirds(hexdom_bin, tmp_path):
    # --method polycube, the hole (Face10) at 0.5: the polycube's cell made 1.8 (a third of it
    # within 1.2 of 0.5), its hexes near the hole split in 27 and their neighbours given the
    # transition templates; the quads on the hole about 0.5, the rest of the mesh as the polycube
    # path's mesh of that cell without the local size.
    assert BRACKET.is_file(), BRACKET
    plain, local = tmp_path / "plain.vtu", tmp_path / "local.vtu"
    run0 = _mesh_default(hexdom_bin, BRACKET, plain, "--method", "polycube", "--size", "1.8")
    run = _mesh_default(hexdom_bin, BRACKET, local, "--method", "polycube", "--face-size", "10=0.5")
    assert run0.returncode == 0 and run.returncode == 0, (run0.stderr, run.stderr)
    assert "local sizes: the polycube's cell 2.92499 made 1.8" in run.stderr, run.stderr
    assert re.search(r"local sizes: 1 levels by thirds \(\d+ cells split, \d+ transition templates\)", run.stderr), run.stderr
    assert "kept: polycube path" in run.stderr, run.stderr
    g0, g = oracles.read_vtu(str(plain)), oracles.read_vtu(str(local))
    q = _quads_on_hole(g)
    assert abs(np.median(q) - 0.5) <= 0.1, np.median(q)
    assert g.GetNumberOfCells() > 3 * g0.GetNumberOfCells()
    s = _valid_whole_and_as_before_far_away(g0, g, run)
    ratios = _neighbour_ratios(g, s)
    assert np.percentile(ratios, 99) <= 2.0 and max(ratios) < 2.6, (np.percentile(ratios, 99), max(ratios))


@pytest.mark.parametrize("size, path", [("1", "overlay"), ("1.5", "polycube")])
def test_auto_keeps_the_path_whose_cells_meet_the_local_size(hexdom_bin, tmp_path, size, path):
    # Auto with the hole (Face10) at 1 and at 1.5: both paths mesh and refine, and say how near the
    # size their cells on the hole are. At 1 the polycube's (its square hole of side 12 carries the
    # circle of 37.7) are about 0.8 of it, the overlay's 0.84 and of the higher worst SJ: the overlay
    # mesh is kept; at 1.5 both meet it (the polycube's cell made 1.8) and the polycube's, of the
    # higher worst SJ, is kept. The kept mesh's quads on the hole, measured here, within 20%.
    out = tmp_path / "bracket.vtu"
    run = _mesh_default(hexdom_bin, BRACKET, out, "--face-size", "10=" + size)
    assert run.returncode == 0, run.stderr
    fits = [float(x) for x in re.findall(r"local sizes: cells ([\d.]+) of the size on Face10", run.stderr)]
    assert len(fits) == 2, run.stderr  # the polycube's, then the overlay's
    assert "kept: {} path".format(path) in run.stderr, run.stderr
    assert 0.8 <= fits[1] <= 1.2 and (path == "overlay" or 0.8 <= fits[0] <= 1.2), fits
    g = oracles.read_vtu(str(out))
    assert abs(np.median(_quads_on_hole(g)) / float(size) - 1) <= 0.2, np.median(_quads_on_hole(g))
    sj, _ = oracles.verdict_metrics(g)
    assert sj.min() > 0.3, sj.min()


@pytest.mark.parametrize(
    "args, message",
    [
        (["--face-size", "11=1"], "local size on face 11: the part has no such face (its faces are numbered 1 to 10)"),
        (["--face-size", "10"], "--face-size 10: expected FACE=SIZE"),
        (["--face-size", "Face10=0"], "the face number must be at least 1 and the size positive"),
        (["--face-size", "10=1", "--growth-rate", "1"], "growth rate 1: it must be above 1 and at most 3"),
        (["--edge-size", "Edge99=1"], "Edge99 does not exist (the solid has 24 edges)"),
        (["--edge-size", "20"], "--edge-size 20: expected EDGE=SIZE"),
    ],
)
def test_a_local_size_the_part_cannot_take_is_refused_without_output(hexdom_bin, tmp_path, args, message):
    out = tmp_path / "bracket.vtu"
    run = _mesh_default(hexdom_bin, BRACKET, out, *args)
    assert run.returncode == 1, (run.returncode, run.stderr)
    assert message in run.stderr, run.stderr
    assert not out.exists()


def test_a_faster_growth_rate_gives_a_narrower_refined_band(hexdom_bin, tmp_path):
    # The bracket's hole at 1: growth 3 refines only the cells touching the hole, 1.15 a band
    # about seven small cells wide; the quads on the hole keep their size.
    runs = {}
    for growth in ("1.15", "3"):
        out = tmp_path / ("g" + growth + ".vtu")
        run = _mesh_default(hexdom_bin, BRACKET, out, "--face-size", "10=1", "--growth-rate", growth, "--method", "overlay")
        assert run.returncode == 0, run.stderr
        g = oracles.read_vtu(str(out))
        runs[growth] = (g.GetNumberOfCells(), np.median(_quads_on_hole(g)))
    assert runs["1.15"][0] > 1.5 * runs["3"][0], runs
    assert all(abs(q - 1.0) <= 0.2 for _, q in runs.values()), runs


def test_a_local_size_along_the_hole_s_rim(hexdom_bin, tmp_path):
    # Edge20 of the bracket is the hole's top rim (a circle of radius 6 at z = 10, 37.7 long): at
    # 1, 29 to 54 boundary nodes on it (node spacing within 30% of 1: the buffer puts curve nodes
    # where the grid's staircase meets the curve, 30 here); without it, the overlay mesh's 12.
    # A triangle surface has no edges: refused.
    counts = {}
    for name, extra in (("plain", ["--method", "overlay"]), ("rim", ["--edge-size", "Edge20=1", "--method", "overlay"])):
        out = tmp_path / (name + ".vtu")
        run = _mesh_default(hexdom_bin, BRACKET, out, *extra)
        assert run.returncode == 0, run.stderr
        P, _, _ = oracles.grid_arrays(oracles.read_vtu(str(out)))
        on = (np.abs(np.hypot(P[:, 0] - 40, P[:, 1] - 20) - 6) < 1e-6) & (np.abs(P[:, 2] - 10) < 1e-6)
        counts[name] = int(on.sum())
    assert 29 <= counts["rim"] <= 54 and counts["rim"] > 2 * counts["plain"], counts
    stl = tmp_path / "box.stl"
    from test_cli_input_checks import _box, _write_stl
    _write_stl(stl, _box((0, 0, 0), (10, 10, 10)))
    out = tmp_path / "box.vtu"
    run = _mesh_default(hexdom_bin, stl, out, "--edge-size", "1=1")
    assert run.returncode == 1 and "--edge-size needs a CAD part" in run.stderr, run.stderr
    assert not out.exists()
