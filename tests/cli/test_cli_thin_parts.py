"""Thin parts (issue "element size that FEM users can steer"): a 100 x 100 x 0.5 plate and a
1000 x 1 x 1 rod, written here as STL boxes, mesh with at least two cells across each thin axis and
no needles: Verdict's edge ratio at most 5 on every cell (cubic cells of the default size gave 18
and 66), every scaled Jacobian above 0.99, VTK's volume the box's."""

import numpy as np
import pytest

import hexdom_oracles as oracles
from test_cli_input_checks import _box, _mesh_default, _write_stl


@pytest.mark.parametrize("dims, cells", [((100.0, 100.0, 0.5), 80 * 80 * 2), ((1000.0, 1.0, 1.0), 400 * 2 * 2)])
def test_a_plate_and_a_rod_get_two_cells_across_without_needles(hexdom_bin, tmp_path, dims, cells):
    src = _write_stl(tmp_path / "part.stl", _box((0, 0, 0), dims))
    out = tmp_path / "part.vtu"
    run = _mesh_default(hexdom_bin, src, out)
    assert run.returncode == 0, run.stderr
    assert "thin part: cells of" in run.stderr, run.stderr
    g = oracles.read_vtu(str(out))
    sj, er = oracles.verdict_metrics(g)
    assert g.GetNumberOfCells() == cells
    assert sj.min() > 0.99 and er.max() <= 5.0 + 1e-9, (sj.min(), er.max())
    assert float(np.sum(oracles.signed_volumes(g))) == pytest.approx(float(np.prod(dims)), rel=1e-9)
    P, _, _ = oracles.grid_arrays(g)
    for a in range(3):
        if dims[a] <= 1.0:  # a thin axis: three node levels or more, so two cells or more across
            assert len(np.unique(np.round(P[:, a], 9))) >= 3
