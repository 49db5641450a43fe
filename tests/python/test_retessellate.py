"""A tessellation whose labelling defeats the automatic polycube is not the end (issue 9, "mesh a CAD
part with no manual step"): `hexdom mesh` tessellates the B-rep again with triangles of 0.97, 1.03,
0.94, 1.06 x the size, the polycube grid kept at the asked element size, when the first one gives
no polycube or cells stay inverted after the snap (cad::mesh_cad_part).

Measured (bench/bench_size_sweep.py, before): i10o_simp at 0.9 x the default size had no mesh (the
label repair cycles: "3 problems of the labelling remain after relabelling 3 charts"), now 2,192 hexes,
worst 0.427, +0.52% from the tessellation at 0.97; i01o_m1 at 1.1 x kept 3 inverted cells after the
snap, now 2,784 hexes, none inverted (worst 0.060), from 0.97. Parts that mesh on the first
tessellation are meshed once, as before.

Oracles nobody here wrote: FreeCAD's Part (B-rep distance, volume), VTK's Verdict."""

import glob
import subprocess

import numpy as np
import pytest

import hexdom_oracles as oracle
import hexdom_test_support as support


def _shared(stem):
    paths = glob.glob(str(support.DATA_ROOT / "cad" / f"{stem}.*"))
    if not paths:
        pytest.skip(support.missing(support.DATA_ROOT / "cad" / f"{stem}.*"))
    return paths[0]


def _default_size(core, path):
    V = core._hexdom.tessellate_file(path, size=0.0, solid=0)[0]
    return float(np.linalg.norm(V.max(axis=0) - V.min(axis=0))) / 30.0


@pytest.fixture
def cad(core):
    if not core._hexdom.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")
    return core


def test_a_labelling_the_repair_cannot_use_gets_another_tessellation(cad, tmp_path, freecad):
    FreeCAD, Part = freecad
    path = _shared("i10o_simp")
    # 0.9 x the default size (6.884), as bench_size_sweep.py printed it. The outcome of a tessellation
    # hinges on the last digits (6.19577 meshes at once): the size is given as the sweep gave it.
    size = 6.1958
    assert size == pytest.approx(0.9 * _default_size(cad, path), rel=1e-4)
    out = tmp_path / "m.vtu"
    # The polycube path: under auto the overlay grid would mesh the first tessellation instead.
    r = subprocess.run([str(support.hexdom_bin()), "mesh", path, "-o", str(out), "--size", str(size), "--method", "polycube"],
                       capture_output=True, text=True)
    log = r.stdout + r.stderr
    assert r.returncode == 0, log[-800:]
    assert "the automatic polycube failed at stage autopolycube: tessellating again with triangles of 0.97" in log
    assert "kept the tessellation at 0.97 x the size" in log
    g, sj, types = oracle.vtu_sj_types(out)
    assert np.all(sj > 0)
    assert sj[types == oracle.HEX].min() >= 0.3
    shape = Part.read(path)
    shape = shape.Solids[0] if shape.Solids else shape
    assert float(oracle.signed_volumes(g).sum()) == pytest.approx(shape.Volume, rel=0.01)
    assert oracle.max_brep_distance(FreeCAD, Part, shape, g) <= 1e-7 * shape.BoundBox.DiagonalLength
    assert f"the polycube grid kept at {size:g}" in log


def test_cells_the_snap_leaves_inverted_get_another_tessellation(cad):
    """i01o_m1 at 1.1 x the default size keeps inverted cells after the snap on its first
    tessellation (so it did before the optimiser lowered edge ratios, and again since its nodes move
    colour by colour, optimize/improver.h); the tessellation at 0.97 x the size gives none and is
    kept. Without the retessellation for inverted cells (cad::MeshCadOptions) the run would end
    with them."""
    path = _shared("i01o_m1")
    size = 6.3930  # 1.1 x the default size, as the sweep printed it
    assert size == pytest.approx(1.1 * _default_size(cad, path), rel=1e-4)
    run = cad.mesh_part(path, size=size, allow_inverted=True, polycube_seconds=0, method="polycube")
    assert run.inverted == 0
    assert run.tessellations == 2 and run.tessellation_factor == 0.97


def test_a_part_that_meshes_at_once_is_tessellated_once(cad):
    run = cad.mesh_part(str(support.REPO / "examples" / "data" / "bracket.step"))
    assert run.tessellations == 1 and run.tessellation_factor == 1.0
    assert run.inverted == 0 and run.snap["max_after"] <= 1e-7 * run.snap["diagonal"]


def test_under_auto_a_kept_overlay_mesh_is_not_tessellated_again(cad, tmp_path):
    """Auto keeps the overlay's mesh of the first tessellation even when it misses a target: another
    tessellation's polycube beat it on none of 23 corpus parts (cad::MeshCadOptions::retessellate).
    The part is our corpus's cone_006 (bench/make_corpus.py, cone family, 7th draw of the default
    seed), made here by FreeCAD: its polycube's labelling defeats the repair for every edge weight,
    and the overlay's mesh is valid but 3% short of the volume, so the old rule tessellated it four
    times more (about 4 s) for nothing."""
    import sys
    p = subprocess.run([sys.executable, str(support.REPO / "bench" / "make_corpus.py"), str(tmp_path), "--families",
                        "cone", "--count", "7", "--no-fixed"], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
    part = str(tmp_path / "cone_006.step")
    run = cad.mesh_part(part, allow_inverted=True)
    assert run.method == "overlay" and run.inverted == 0
    reference = cad.cad_volume(part)
    volume = sum(run.quality[t]["volume"] for t in ("hex", "prism", "tet"))
    assert abs(volume - reference) > 0.01 * abs(reference)  # a target missed: the case the rule is for
    assert run.tessellations == 1 and run.tessellation_factor == 1.0
