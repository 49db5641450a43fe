"""Stopping a core call from another thread through _hexdom (core.Interrupt, the workbench's Cancel):
a call made inside ``with interrupt:`` raises core.Interrupted (not a core.Error: no fallback
catches it) soon after another thread calls interrupt.cancel() (the bound is generous; the latency
itself is bench/bench_cancel.py's); calls outside the ``with`` and on other threads are not
affected; after clear() the same interrupt lets the next call run to its end. The part: the
shipped bracket (examples/data/bracket.step) on the overlay grid at a fine size, several seconds
of work."""

import threading
import time

import pytest

import hexdom_test_support as support

STEP = support.REPO / "examples" / "data" / "bracket.step"
# About 4.6 s of work on the CI machine (2 cores, 2026-12): well past the cancel at 1.5 s. At 0.8 the
# call took 1.55 s once the optimiser got faster, and ended before the cancel.
WORK_SIZE = 0.5


@pytest.fixture(scope="module")
def cad(core):
    if not core._hexdom.has_opencascade():
        pytest.skip("_hexdom was built without OpenCASCADE (HEXDOM_WITH_CAD=OFF)")
    return core


def _run_and_cancel(core, interrupt, after):
    outcome = {}

    def work():
        try:
            with interrupt:
                outcome["run"] = core.mesh_part(str(STEP), size=WORK_SIZE, method="overlay", snap=False)
        except BaseException as e:  # noqa: B902 (what the thread ended with)
            outcome["error"] = e
        outcome["end"] = time.monotonic()

    worker = threading.Thread(target=work)
    worker.start()
    time.sleep(after)
    sent = time.monotonic()
    interrupt.cancel()
    worker.join(60)
    return outcome, outcome.get("end", float("inf")) - sent


def test_cancel_stops_a_running_call_soon(cad):
    core = cad
    interrupt = core.Interrupt()
    outcome, latency = _run_and_cancel(core, interrupt, after=1.5)
    assert isinstance(outcome.get("error"), core.Interrupted), outcome
    assert not isinstance(outcome["error"], core.Error)
    assert "interrupted" in str(outcome["error"])
    assert latency < 3.0, f"{latency:.2f} s from cancel() to the end of the call"
    assert interrupt.cancelled


def test_only_calls_inside_the_with_stop(cad):
    core = cad
    interrupt = core.Interrupt()
    interrupt.cancel()
    run = core.mesh_part(str(STEP), size=12.0, method="overlay", snap=False)  # not inside `with`
    assert run.mesh.cells.shape[0] > 0
    with interrupt:
        with pytest.raises(core.Interrupted):
            core.mesh_part(str(STEP), size=12.0, method="overlay", snap=False)
    interrupt.clear()
    with interrupt:
        again = core.mesh_part(str(STEP), size=12.0, method="overlay", snap=False)
    assert again.mesh.cells.shape[0] == run.mesh.cells.shape[0]
