#!/usr/bin/env python3
"""Timings of what the Build Polycube and Edit Patches panels recompute after each edit, on the
paper's rocker arm: the live problem list of the polycube (and its overlap check alone), and the
lasso's point-in-polygon test over every facet centroid. The panels must stay interactive, so
the figures should be well under a second. Prints figures; never asserts on time.

Run:  HEXDOM_BUILD_DIR=build /usr/bin/python3 bench/bench_dialogs.py [--repeat N]
Data: HEXDOM_DATA (default ../shared/data beside the repository); missing files are reported and
skipped.
"""

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))
BUILD = Path(os.environ.get("HEXDOM_BUILD_DIR") or REPO / "build").resolve()
os.environ["HEXDOM_BUILD_DIR"] = str(BUILD)
DATA = Path(os.environ.get("HEXDOM_DATA") or REPO.parent / "shared" / "data").resolve() / "hexdom"

from HexDomWorkbench import core  # noqa: E402
from HexDomWorkbench.logic import polycube_building  # noqa: E402
from HexDomWorkbench.logic.patch_editing import points_in_polygon  # noqa: E402
from HexDomWorkbench.logic.polycube_building import PolycubeBuilder  # noqa: E402

MODELS = [  # (segmented surface, structure)
    ("rockerarm/rockerarm_indexPatch_hexdom.k", "rockerarm/rockerarm_polycube_withtet.k"),
]


def timed(fn, repeat):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - start)
    return result, statistics.median(times), min(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    print("HexDom dialog bench ({} runs, median / best)".format(args.repeat))
    for surface_file, structure_file in MODELS:
        paths = [DATA / surface_file, DATA / structure_file]
        missing = [str(p) for p in paths if not p.is_file()]
        if missing:
            print("  {}: skipped, missing {}".format(surface_file, ", ".join(missing)))
            continue
        surface = core.read_surface(str(paths[0]))
        builder = PolycubeBuilder(surface)
        builder.import_structure(str(paths[1]))
        counts = builder.counts()
        samples = sum(len(polycube_building.sample_weights(t)) for t, _ in builder.blocks)

        def problems():
            builder._problems = None
            return builder.problems()

        found, median, best = timed(problems, args.repeat)
        print("  {}: {} hex, {} prism, {} tet, {} overlap samples".format(
            structure_file, counts["hex"], counts["prism"], counts["tet"], samples))
        print("    problem list after an edit: {:.0f} ms / {:.0f} ms ({} problems)".format(
            1e3 * median, 1e3 * best, len(found)))
        overlaps, median, best = timed(builder._overlaps, args.repeat)
        print("    overlap check alone:        {:.0f} ms / {:.0f} ms ({} overlaps)".format(
            1e3 * median, 1e3 * best, len(overlaps)))
        # A lasso of 400 points (a hand-drawn circle) over the facet centroids, projected on xy.
        centroids = np.asarray(surface.V)[np.asarray(surface.F)].mean(axis=1)[:, :2]
        lo, hi = centroids.min(axis=0), centroids.max(axis=0)
        t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
        lasso = 0.5 * (lo + hi) + 0.3 * (hi - lo) * np.c_[np.cos(t), np.sin(t)]
        inside, median, best = timed(lambda: points_in_polygon(centroids, lasso), args.repeat)
        print("    lasso of 400 points over {} facets: {:.0f} ms / {:.0f} ms ({} inside)".format(
            len(centroids), 1e3 * median, 1e3 * best, int(inside.sum())))


if __name__ == "__main__":
    main()
