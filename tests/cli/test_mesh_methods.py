"""`hexdom mesh --method auto|polycube|overlay` on the shipped bracket (examples/data/bracket.step,
made by examples/make_bracket_step.py): each path gives a valid mesh of the part (VTK's Verdict), the
log says which path made it, and `auto` keeps the polycube mesh where it meets every target. A method
that does not exist is refused before anything is read or written. The polycube path's time budget
(--polycube-seconds): under auto a tiny one gives the overlay mesh and says why; with --method
polycube it is an error (exit 5) and nothing is written. The file written is the same on one
and on three threads (--threads)."""

import subprocess
from pathlib import Path

import meshio
import numpy as np
import pytest

import hexdom_oracles as oracles

REPO = Path(__file__).resolve().parents[2]
STEP = REPO / "examples" / "data" / "bracket.step"
VTK_TYPE = {"hexahedron": oracles.HEX, "wedge": oracles.WEDGE, "tetra": oracles.TET}


def _mesh(hexdom_bin, tmp_path, method, *extra, name=None):
    out = tmp_path / f"bracket_{name or method}.vtu"
    run = subprocess.run([str(hexdom_bin), "mesh", str(STEP), "-o", str(out), "--method", method, *extra],
                         capture_output=True, text=True)
    return run, out


def _verdict(path):
    m = meshio.read(path)
    cells, types = [], []
    for block in m.cells:
        for row in block.data:
            cells.append(list(row) + [-1] * (8 - len(row)))
            types.append(VTK_TYPE[block.type])
    g = oracles.vtk_grid(m.points, np.array(cells, np.int64), np.array(types))
    sj, _ = oracles.verdict_metrics(g)
    return sj, float(np.sum(oracles.signed_volumes(g)))


@pytest.fixture(scope="module")
def runs(hexdom_bin, tmp_path_factory):
    tmp = tmp_path_factory.mktemp("methods")
    return {m: _mesh(hexdom_bin, tmp, m) for m in ("auto", "polycube", "overlay")}


@pytest.mark.parametrize("method", ["polycube", "overlay"])
def test_each_path_meshes_the_bracket(runs, method):
    run, out = runs[method]
    assert run.returncode == 0, run.stderr
    assert f"kept: {method} path" in run.stderr
    sj, volume = _verdict(out)
    assert np.all(sj > 0), f"{int(np.sum(sj <= 0))} inverted cells"
    assert "B-rep volume" in run.stdout
    brep = float(run.stdout.split("B-rep volume")[1].split()[0])
    assert volume == pytest.approx(brep, rel=0.01), (volume, brep)


def test_auto_keeps_the_polycube_on_the_bracket(runs):
    auto, out = runs["auto"]
    polycube, polycube_out = runs["polycube"]
    assert auto.returncode == 0, auto.stderr
    assert "kept: polycube path" in auto.stderr
    assert "overlay" not in auto.stderr  # the polycube met every target: the grid was not tried
    assert meshio.read(out).points.shape == meshio.read(polycube_out).points.shape


def test_an_unknown_method_is_refused_with_nothing_written(hexdom_bin, tmp_path):
    run, out = _mesh(hexdom_bin, tmp_path, "octree")
    assert run.returncode != 0
    assert "--method" in run.stderr and "octree" in run.stderr
    assert not out.exists()


def test_the_polycube_time_budget_is_an_option_next_to_the_method(hexdom_bin):
    run = subprocess.run([str(hexdom_bin), "mesh", "--help"], capture_output=True, text=True)
    assert run.returncode == 0
    assert "--polycube-seconds" in run.stdout
    assert run.stdout.index("--polycube-seconds") > run.stdout.index("--method")


def test_auto_with_a_tiny_polycube_budget_keeps_the_overlay_mesh(hexdom_bin, tmp_path):
    # Without a budget auto keeps the bracket's polycube mesh (test above); with a microsecond the
    # polycube path stops at once and the overlay grid's mesh is written.
    out = tmp_path / "bracket_budget.vtu"
    run = subprocess.run([str(hexdom_bin), "mesh", str(STEP), "-o", str(out), "--polycube-seconds", "0.000001"],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "the polycube path stopped after its time budget of 1e-06 s" in run.stderr
    assert "kept: overlay path" in run.stderr
    sj, _ = _verdict(out)
    assert np.all(sj > 0), f"{int(np.sum(sj <= 0))} inverted cells"


def test_polycube_with_a_tiny_budget_fails_with_nothing_written(hexdom_bin, tmp_path):
    out = tmp_path / "bracket_polycube_budget.vtu"
    run = subprocess.run([str(hexdom_bin), "mesh", str(STEP), "-o", str(out), "--method", "polycube",
                          "--polycube-seconds", "0.000001"], capture_output=True, text=True)
    assert run.returncode == 5, (run.returncode, run.stderr)
    assert "hexdom: error:" in run.stderr and "stopped after the time budget of 1e-06 s" in run.stderr
    assert not out.exists()
    assert not list(tmp_path.iterdir()), "files were written"


def test_a_negative_polycube_budget_is_a_usage_error(hexdom_bin, tmp_path):
    out = tmp_path / "x.vtu"
    run = subprocess.run([str(hexdom_bin), "mesh", str(STEP), "-o", str(out), "--polycube-seconds", "-1"],
                         capture_output=True, text=True)
    assert run.returncode == 2, run.stderr
    assert not out.exists()


def _box_triangles(lo, hi, inward):
    c = np.array([[lo[0], lo[1], lo[2]], [hi[0], lo[1], lo[2]], [hi[0], hi[1], lo[2]], [lo[0], hi[1], lo[2]],
                  [lo[0], lo[1], hi[2]], [hi[0], lo[1], hi[2]], [hi[0], hi[1], hi[2]], [lo[0], hi[1], hi[2]]], float)
    tris = []
    for q in [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]:
        for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3])):
            tris.append(c[list(t[::-1] if inward else t)])
    return tris


def test_octree_levels_refine_the_overlay_grid_at_thin_walls(hexdom_bin, tmp_path):
    """A hollow cube 40 wide with walls of 2 (the default cells are 2.35): --octree-levels 1 splits the
    cells at the walls in 27 (the log says so), and the mesh is valid with the solid's volume."""
    stl = tmp_path / "hollow.stl"
    with open(stl, "w") as f:
        f.write("solid hollow\n")
        for t in _box_triangles((0, 0, 0), (40, 40, 40), False) + _box_triangles((2, 2, 2), (38, 38, 38), True):
            n = np.cross(t[1] - t[0], t[2] - t[0])
            n /= np.linalg.norm(n)
            f.write(f"facet normal {n[0]} {n[1]} {n[2]}\n outer loop\n")
            f.write("".join(f"  vertex {p[0]} {p[1]} {p[2]}\n" for p in t) + " endloop\nendfacet\n")
        f.write("endsolid hollow\n")
    out = tmp_path / "hollow.vtu"
    run = subprocess.run([str(hexdom_bin), "mesh", str(stl), "-o", str(out), "--method", "overlay",
                          "--octree-levels", "1"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "1 octree levels" in run.stderr
    sj, volume = _verdict(out)
    assert np.all(sj > 0), f"{int(np.sum(sj <= 0))} inverted cells"
    assert volume == pytest.approx(40.0 ** 3 - 36.0 ** 3, rel=0.01)


def test_octree_levels_out_of_range_is_refused(hexdom_bin, tmp_path):
    out = tmp_path / "x.vtu"
    run = subprocess.run([str(hexdom_bin), "mesh", str(STEP), "-o", str(out), "--octree-levels", "4"],
                         capture_output=True, text=True)
    assert run.returncode != 0
    assert "--octree-levels" in run.stderr
    assert not out.exists()


@pytest.mark.parametrize("method", ["polycube", "overlay"])
def test_the_mesh_is_the_same_file_on_one_and_three_threads(hexdom_bin, tmp_path, method):
    # The optimisers move nodes colour by colour and the snap's projections start from each node's
    # own last point (optimize/improver.h, cad/snap.cpp): the threads change the time, never the mesh.
    outs = []
    for threads in (1, 3):
        run, out = _mesh(hexdom_bin, tmp_path, method, "--threads", str(threads), name=f"{method}_{threads}")
        assert run.returncode == 0, run.stderr
        outs.append(out.read_bytes())
    assert len(outs[0]) > 10000
    assert outs[0] == outs[1], "the mesh written depends on the number of threads"


def test_a_negative_thread_count_is_a_usage_error(hexdom_bin, tmp_path):
    out = tmp_path / "x.vtu"
    run = subprocess.run([str(hexdom_bin), "mesh", str(STEP), "-o", str(out), "--threads", "-2"],
                         capture_output=True, text=True)
    assert run.returncode == 2, run.stderr
    assert "--threads" in run.stderr
    assert not out.exists()
