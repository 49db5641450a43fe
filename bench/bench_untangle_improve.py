"""Inverted cells straight out of `hexdom generate` and quality after `hexdom improve`, per paper
model, for several generate modes (issue 3: may the untangling be the default?).

Run: HEXDOM_BUILD_DIR=build /usr/bin/python3 bench/bench_untangle_improve.py [--level S] [mode...]
A mode is a comma-separated list of extra `hexdom generate` arguments ("" is the default run), e.g.
  bench/bench_untangle_improve.py "" "--no-untangle"
For each model and mode it prints, by VTK's Verdict (tests/python/hexdom_oracles.py): the inverted
cells per type and the worst / mean scaled Jacobian per type after generation, then the same after
`hexdom improve --surface` (the run tests/python/test_improve.py checks: worst hex >= 0.3, mean
>= 0.85), and how many nodes the mode moved against the first mode. Prints, never asserts.
"""

import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "python"))
import hexdom_oracles as O  # noqa: E402
import hexdom_test_support as support  # noqa: E402

DATA = os.environ.get("HEXDOM_DATA", os.path.join(ROOT, "..", "shared", "data"))
BUILD = os.environ.get("HEXDOM_BUILD_DIR", os.path.join(ROOT, "build"))
HEXDOM = os.path.join(BUILD, "bin", "hexdom")
MODELS = support.PAPER_MODELS
NAMES = {O.HEX: "hex", O.WEDGE: "prism", O.TET: "tet"}


def figures(path):
    g, _ = O.read_legacy_vtk(path)
    sj, _ = O.verdict_metrics(g)
    types = np.array([g.GetCellType(i) for i in range(g.GetNumberOfCells())])
    X = O.grid_arrays(g)[0]
    out = []
    for t, name in NAMES.items():
        s = sj[types == t]
        if len(s):
            bad = ~((s > 0) & (s <= 1))
            out.append(f"{name} {int(bad.sum())} inv, min {np.min(np.where(s > 1, -1, s)):+.3f} mean {s[~bad].mean():.3f}")
    return "; ".join(out), X


def main(argv):
    level = 2
    if argv[:1] == ["--level"]:
        level, argv = int(argv[1]), argv[2:]
    modes = argv or [""]
    models = [m for m in MODELS if os.environ.get("MODELS") is None or m in os.environ["MODELS"].split(",")]
    with tempfile.TemporaryDirectory() as d:
        for model in models:
            pf, sf = (os.path.join(DATA, "hexdom", model, f) for f in MODELS[model])
            if not os.path.exists(pf):
                print(f"{model}: skipped, shared data missing")
                continue
            first = None
            for mode in modes:
                extra = [a for a in mode.split(",") if a]
                raw, imp = os.path.join(d, "raw.vtk"), os.path.join(d, "imp.vtk")
                subprocess.run([HEXDOM, "generate", "-i", pf, "-p", sf, "-s", str(level), "-o", raw, *extra],
                               check=True, capture_output=True)
                subprocess.run([HEXDOM, "improve", "-i", raw, "-o", imp, "--surface", pf], check=True, capture_output=True)
                g, X = figures(raw)
                moved = "" if first is None else f" ({int((np.linalg.norm(X - first, axis=1) > 0).sum())} nodes moved)"
                first = X if first is None else first
                print(f"{model:13s} {mode or 'default':22s} generated: {g}{moved}")
                print(f"{'':13s} {'':22s} improved:  {figures(imp)[0]}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
