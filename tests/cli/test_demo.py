"""`make demo`: examples/run_demo.sh meshes the shipped STEP bracket end to end with `hexdom mesh`
and writes the mesh, its quality report and the intermediate files.

Oracles: meshio reads the mesh; VTK's Verdict measures it; the bracket's volume is known in closed
form (examples/make_bracket_step.py: 60x40x10 base, 10x40x50 upright, a 12 mm hole through the
10 mm base, a 6 mm fillet along the 40 mm inside corner).
"""

import json
import math
import os
import subprocess
from pathlib import Path

import meshio
import numpy as np
import pytest

import hexdom_oracles as oracles
import hexdom_test_support as support

REPO = Path(__file__).resolve().parents[2]
STEP = REPO / "examples" / "data" / "bracket.step"
VOLUME = 60 * 40 * 10 + 10 * 40 * 40 - math.pi * 6 ** 2 * 10 + (6 ** 2 - math.pi * 6 ** 2 / 4) * 40
VTK_TYPE = {"hexahedron": oracles.HEX, "wedge": oracles.WEDGE, "tetra": oracles.TET}


def _has_cad(hexdom_bin, tmp):
    probe = subprocess.run([str(hexdom_bin), "tessellate", str(STEP), "-o", str(tmp / "probe.k")],
                           capture_output=True, text=True)
    return "without OpenCASCADE" not in probe.stderr


@pytest.fixture(scope="module")
def demo(hexdom_bin, tmp_path_factory):
    out = tmp_path_factory.mktemp("demo")
    if not _has_cad(hexdom_bin, out):
        pytest.skip("hexdom built without OpenCASCADE: the demo meshes a STEP part")
    env = dict(os.environ, HEXDOM_DEMO_OUT=str(out))
    run = subprocess.run(["bash", str(REPO / "examples" / "run_demo.sh"),
                          str(support.BUILD_DIR)], capture_output=True, text=True, env=env,
                         timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    return out, run


def test_demo_writes_the_mesh_report_and_intermediates(demo):
    out, run = demo
    for name in ("bracket.vtu", "bracket_quality.json", "bracket_quality.txt",
                 "bracket_labels.k", "bracket_structure.k", "bracket_patches.k",
                 "bracket_polycube.vtk", "lbracket.vtu"):
        assert (out / name).is_file() and (out / name).stat().st_size > 0, name
    assert "meshed end to end in" in run.stdout
    for stage in ("tessellate:", "segment:", "autopolycube:", "generate:", "improve:"):
        assert stage in run.stderr, stage  # one progress line per stage


def test_demo_mesh_is_valid_by_verdict_and_has_the_part_volume(demo):
    out, _ = demo
    m = meshio.read(out / "bracket.vtu")
    cells, types = [], []
    for block in m.cells:
        assert block.type in VTK_TYPE, block.type  # volume cells only
        for row in block.data:
            cells.append(list(row) + [-1] * (8 - len(row)))
            types.append(VTK_TYPE[block.type])
    types = np.array(types)
    g = oracles.vtk_grid(m.points, np.array(cells, np.int64), types)
    sj, _ = oracles.verdict_metrics(g)
    hexes = types == oracles.HEX
    assert hexes.sum() > 1000
    assert np.all(sj > 0), f"{int(np.sum(sj <= 0))} inverted cells"
    assert sj[hexes].min() >= 0.3, f"worst hex SJ {sj[hexes].min():.3f}"
    volume = float(np.sum(oracles.signed_volumes(g)))
    assert volume == pytest.approx(VOLUME, rel=0.01), (volume, VOLUME)

    report = json.loads((out / "bracket_quality.json").read_text())
    counts = {name: int(np.sum(types == t)) for name, t in
              (("hex", oracles.HEX), ("prism", oracles.WEDGE), ("tet", oracles.TET))}
    for name, count in counts.items():
        assert report[name]["count"] == count, name
    assert report["hex"]["sj_min"] == pytest.approx(sj[hexes].min(), abs=1e-6)
    print(f"demo bracket: {counts}, worst hex SJ {sj[hexes].min():.3f}, mean "
          f"{sj[hexes].mean():.3f}, volume {100 * (volume - VOLUME) / VOLUME:+.3f}%")


def test_shipped_step_is_what_the_script_describes():
    """The STEP file is the script's part: one solid, ten faces (a hole and a fillet)."""
    text = STEP.read_text()
    assert text.startswith("ISO-10303-21;")
    assert text.count("CYLINDRICAL_SURFACE") == 2  # the hole and the fillet
    assert text.count("ADVANCED_FACE") == 10
