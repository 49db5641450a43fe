#!/usr/bin/env python3
"""Timings of reading, writing and quality computation on the largest shared data files and on a
synthetic hex grid. Prints figures (ms, elements/s); never asserts on time.

Run:  HEXDOM_BUILD_DIR=build /usr/bin/python3 bench/bench_io_quality.py [--repeat N]
Data: HEXDOM_DATA (default ../shared/data beside the repository); missing files are reported and
skipped.
"""

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))
BUILD = Path(os.environ.get("HEXDOM_BUILD_DIR") or REPO / "build").resolve()
os.environ["HEXDOM_BUILD_DIR"] = str(BUILD)
DATA = Path(os.environ.get("HEXDOM_DATA") or REPO.parent / "shared" / "data").resolve() / "hexdom"

from HexDomWorkbench import core  # noqa: E402

READ_FILES = [
    "rockerarm/rockerarm.k",                  # raw surface, 23,312 triangles
    "rockerarm/rockerarm_indexPatch_hexdom.k",  # segmented surface, 23,410 triangles
    "ant/ant_indexPatch_hexdom.k",            # 14,618 triangles
    "joint/joint_hex_initial.vtk",            # the largest hex mesh: 6,144 hexes
    "ant/ant_hex.vtk",                        # 4,480 hexes
    "rockerarm/rockerarm3_hex.vtk",           # 3,840 hexes
    "fertility/fertility_hex.vtk",            # a .k file named .vtk: 3,712 hexes
]
QUALITY_FILES = ["joint/joint_hex_initial.vtk", "ant/ant_hex.vtk", "rockerarm/rockerarm3_hex.vtk",
                 "rockerarm/rockerarm_polycube_withtet.k"]


def timeit(fn, repeat):
    """Median and best wall time of `repeat` calls, in seconds (one warm-up call first)."""
    fn()
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), min(times)


def row(what, n, unit, med, best):
    rate = f"{n / med:12,.0f} {unit}/s" if med > 0 else ""
    print(f"  {what:<48} {n:>9,} {unit:<6} {med * 1e3:9.2f} ms (best {best * 1e3:8.2f})  {rate}")


def grid_mesh(n, jitter=0.15, seed=1):
    """An n x n x n grid of hexes with jittered interior nodes (some inverted at this jitter)."""
    rng = np.random.default_rng(seed)
    g = np.stack(np.meshgrid(*[np.arange(n + 1.0)] * 3, indexing="ij"), axis=-1).reshape(-1, 3)
    interior = np.all((g > 0) & (g < n), axis=1)
    g[interior] += jitter * rng.standard_normal((interior.sum(), 3))
    idx = np.arange((n + 1) ** 3).reshape(n + 1, n + 1, n + 1)
    i, j, k = [a.ravel() for a in np.meshgrid(*[np.arange(n)] * 3, indexing="ij")]
    cells = np.stack([idx[i, j, k], idx[i + 1, j, k], idx[i + 1, j + 1, k], idx[i, j + 1, k],
                      idx[i, j, k + 1], idx[i + 1, j, k + 1], idx[i + 1, j + 1, k + 1], idx[i, j + 1, k + 1]],
                     axis=1).astype(np.int32)
    c = len(cells)
    return core.Mesh(g, cells, np.full(c, core.HEX, np.int32), np.zeros(c, np.int32))


def count_elements(mesh):
    return len(mesh.types)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--grid", type=int, default=48, help="synthetic grid: N^3 hexes (default 48)")
    args = ap.parse_args()
    print(f"HexDom {core._hexdom.__version__}: {core._hexdom.__file__}\ndata {DATA}")
    print(f"{os.cpu_count()} CPUs; median of {args.repeat} runs after one warm-up\n")

    print("Reading (HexDomWorkbench.core.read_mesh)")
    for rel in READ_FILES:
        path = DATA / rel
        if not path.exists():
            print(f"  {rel}: skipped, shared data missing: {path}")
            continue
        mesh = core.read_mesh(path)
        med, best = timeit(lambda: core.read_mesh(path), args.repeat)
        row(f"{rel} ({path.stat().st_size / 1e6:.1f} MB)", count_elements(mesh), "cells", med, best)

    print("\nQuality (core.cell_metrics: scaled Jacobian, edge ratio, volume per cell)")
    meshes = [(rel, core.read_mesh(DATA / rel)) for rel in QUALITY_FILES if (DATA / rel).exists()]
    for rel in QUALITY_FILES:
        if not (DATA / rel).exists():
            print(f"  {rel}: skipped, shared data missing: {DATA / rel}")
    big = grid_mesh(args.grid)
    meshes.append((f"synthetic {args.grid}^3 grid", big))
    for name, mesh in meshes:
        med, best = timeit(lambda: core.cell_metrics(mesh), args.repeat)
        row(name, count_elements(mesh), "cells", med, best)
        med, best = timeit(lambda: core.quality_report(mesh), args.repeat)
        row("  + quality_report", count_elements(mesh), "cells", med, best)

    try:
        import vtk  # reference figure: VTK's own Verdict filter on the same grid
        sys.path.insert(0, str(REPO / "tests" / "python"))
        import hexdom_oracles as O
        g = O.vtk_grid(big.V, big.cells, big.types)

        def verdict():
            q = vtk.vtkMeshQuality()
            q.SetInputData(g)
            q.SetHexQualityMeasureToScaledJacobian()
            q.Update()
        med, best = timeit(verdict, args.repeat)
        row("  VTK vtkMeshQuality (Verdict SJ only), same grid", count_elements(big), "cells", med, best)
    except ImportError as e:
        print(f"  (VTK reference skipped: {e})")

    print(f"\nWriting and reading back the synthetic grid ({len(big.V):,} nodes)")
    with tempfile.TemporaryDirectory() as tmp:
        for ext, binary in (("vtk", False), ("vtk", True), ("vtu", False), ("k", False), ("inp", False)):
            path = Path(tmp) / f"grid{'_bin' if binary else ''}.{ext}"
            med, best = timeit(lambda: core.write_mesh(path, big, binary=binary), args.repeat)
            label = f"write .{ext}{' binary' if binary else ''} ({path.stat().st_size / 1e6:.1f} MB)"
            row(label, count_elements(big), "cells", med, best)
            if ext in ("vtk", "k"):
                med, best = timeit(lambda: core.read_mesh(path), args.repeat)
                row("read it back", count_elements(big), "cells", med, best)

    print("\nThe program end to end (process start, read, report)")
    exe = BUILD / "bin" / "hexdom"
    for rel in ("joint/joint_hex_initial.vtk", "rockerarm/rockerarm3_hex.vtk"):
        path = DATA / rel
        if not exe.exists() or not path.exists():
            print(f"  {rel}: skipped ({exe if not exe.exists() else path} missing)")
            continue
        n = count_elements(core.read_mesh(path))
        med, best = timeit(lambda: subprocess.run([str(exe), "quality", "-i", str(path), "--json"],
                                                  check=True, capture_output=True), args.repeat)
        row(f"hexdom quality --json {rel}", n, "cells", med, best)


if __name__ == "__main__":
    main()
