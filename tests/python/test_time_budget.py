"""The polycube path's time budget through _hexdom (polycube_seconds=): under method "auto" a budget
too small for anything gives the overlay mesh, and polycube_note names the budget; under "polycube"
the same budget raises _hexdom.TimeoutError (an _hexdom.Error), and without it the polycube path has
no limit. The part: the shipped bracket (examples/data/bracket.step), whose polycube mesh auto keeps
without a budget (tests/cli/test_mesh_methods.py)."""

import numpy as np
import pytest

import hexdom_test_support as support

STEP = support.REPO / "examples" / "data" / "bracket.step"


@pytest.fixture(scope="module")
def hx(core):
    if not core._hexdom.has_opencascade():
        pytest.skip("_hexdom was built without OpenCASCADE (HEXDOM_WITH_CAD=OFF)")
    return core._hexdom


@pytest.fixture(scope="module")
def budget_run(hx):
    return hx.mesh_cad(str(STEP), polycube_seconds=1e-6)


def _inverted(quality):
    return sum(quality[t]["inverted"] for t in ("hex", "prism", "tet"))


def test_auto_with_a_tiny_budget_keeps_the_overlay_mesh(budget_run):
    run = budget_run["run"]
    assert run["method"] == "overlay"
    assert "the polycube path stopped after its time budget of 1e-06 s at stage" in run["polycube_note"]
    assert _inverted(run["quality"]) == 0
    assert budget_run["tessellations"] == 1


def test_polycube_with_a_tiny_budget_raises_timeout_error(hx):
    assert issubclass(hx.TimeoutError, hx.Error)
    with pytest.raises(hx.TimeoutError, match="stopped after the time budget of 1e-06 s"):
        hx.mesh_cad(str(STEP), method="polycube", polycube_seconds=1e-6)


def test_mesh_surface_takes_the_budget_too(hx, budget_run):
    V, F, face = budget_run["surface"]
    auto = hx.mesh_surface(V, F, face, polycube_seconds=1e-6)
    assert auto["method"] == "overlay"
    assert "time budget of 1e-06 s" in auto["polycube_note"]
    with pytest.raises(hx.TimeoutError):
        hx.mesh_surface(V, F, face, method="polycube", polycube_seconds=1e-6)
    # No budget given: the polycube method runs to its end.
    polycube = hx.mesh_surface(V, F, face, method="polycube")
    assert polycube["method"] == "polycube"
    assert not polycube["budget_passed"]
    assert np.asarray(polycube["mesh"][1]).shape[0] > 0


def test_a_negative_budget_is_refused(hx):
    with pytest.raises(hx.InputError, match="polycube_seconds"):
        hx.mesh_cad(str(STEP), polycube_seconds=-1.0)


def test_the_keyword_is_documented(hx):
    for f in (hx.mesh_surface, hx.mesh_cad):
        assert "polycube_seconds" in f.__doc__


# time_limit=: the whole call's limit (`hexdom mesh --time-limit`), through _hexdom and core.


def test_the_time_limit_stops_mesh_cad_and_mesh_surface_naming_the_step(hx, core, budget_run):
    import time
    assert hx.mesh_options()["time_limit"] == 1800  # the default, as `hexdom mesh --help` shows
    start = time.monotonic()
    with pytest.raises(hx.TimeoutError, match=r"\(time limit of the run\): stopped after the time budget of 0.5 s"):
        hx.mesh_cad(str(STEP), method="overlay", size=0.8, time_limit=0.5)
    assert time.monotonic() - start < 3.0
    V, F, face = budget_run["surface"]
    with pytest.raises(hx.TimeoutError, match="time limit of the run"):
        hx.mesh_surface(V, F, face, method="overlay", size=0.4, time_limit=0.3)
    with pytest.raises(hx.InputError, match="time_limit"):
        hx.mesh_cad(str(STEP), time_limit=-1.0)
    # core passes it on; the error is an Error carrying the stage, as any stage failure.
    with pytest.raises(core.Error, match="time limit of the run") as e:
        core.mesh_part(STEP, method="overlay", size=0.8, time_limit=0.5)
    assert hasattr(e.value, "stage")
    for f in (hx.mesh_surface, hx.mesh_cad):
        assert "time_limit" in f.__doc__
