"""Ctrl-C stops `hexdom mesh` cleanly: SIGINT (or SIGTERM) in the middle of a run that takes seconds
makes the program stop within a fraction of a second (the bound here is generous; the latency itself
is bench/bench_cancel.py's), exit 130 with a message saying it was interrupted, and write nothing:
no mesh, no report, no temporary file."""

import signal
import subprocess
import time
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
STEP = REPO / "examples" / "data" / "bracket.step"


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_stops_the_run_and_nothing_is_written(hexdom_bin, tmp_path, sig):
    out, report = tmp_path / "bracket.vtu", tmp_path / "bracket.json"
    # The overlay grid at a fine size: several seconds of work (about 5 s on a 2-core machine).
    logs = tmp_path.parent / f"{tmp_path.name}.log"
    with open(logs, "w") as err:
        proc = subprocess.Popen([str(hexdom_bin), "mesh", str(STEP), "-o", str(out), "--report", str(report),
                                 "--method", "overlay", "--size", "0.8", "-v"],
                                stderr=err, stdout=subprocess.PIPE, text=True)
        # Signal once the part is read and tessellated (the grid is then being meshed).
        start = time.monotonic()
        while "tessellate:" not in logs.read_text() and proc.poll() is None and time.monotonic() - start < 60:
            time.sleep(0.05)
        time.sleep(0.5)
        sent = time.monotonic()
        proc.send_signal(sig)
        stdout, _ = proc.communicate(timeout=60)
        stopped = time.monotonic() - sent
    log = logs.read_text()
    assert proc.returncode == 130, log
    assert "interrupted); nothing written" in log, log
    assert stopped < 5.0, f"{stopped:.2f} s from the signal to the exit"
    assert not out.exists() and not report.exists()
    assert list(tmp_path.iterdir()) == [], sorted(p.name for p in tmp_path.iterdir())
    assert "wrote" not in log and stdout == ""


@pytest.mark.parametrize("method", ["overlay", "auto"])
def test_the_time_limit_stops_the_run_naming_its_step(hexdom_bin, tmp_path, method):
    """--time-limit: the same several-second run given 1.5 s ends with exit 5, the step it was in and
    the limit named, within a fraction of a second of the limit, and nothing written."""
    out, report = tmp_path / "bracket.vtu", tmp_path / "bracket.json"
    start = time.monotonic()
    r = subprocess.run([str(hexdom_bin), "mesh", str(STEP), "-o", str(out), "--report", str(report),
                        "--method", method, "--size", "0.8", "--time-limit", "1.5"],
                       capture_output=True, text=True, timeout=120)
    took = time.monotonic() - start
    assert r.returncode == 5, r.stderr
    line = r.stderr.strip().splitlines()[-1]
    assert "(time limit of the run): stopped after the time budget of 1.5 s" in line, line
    assert line.split(": ")[1] not in ("", "time limit of the run"), line  # a step is named
    assert 1.5 <= took < 4.0, f"{took:.2f} s for a 1.5 s limit"
    assert list(tmp_path.iterdir()) == [], sorted(p.name for p in tmp_path.iterdir())  # no inspection files either


def test_the_time_limit_is_an_option_with_a_generous_default(hexdom_bin):
    r = subprocess.run([str(hexdom_bin), "mesh", "--help"], capture_output=True, text=True)
    assert "--time-limit FLOAT:NONNEGATIVE=1800" in r.stdout, r.stdout
