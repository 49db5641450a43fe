"""Tessellation time and triangle counts for each shared STEP part at size = bounding-box diagonal / 30.

Run: HEXDOM_BUILD_DIR=build /usr/bin/python3 bench/bench_tessellate.py [part.step ...]
Reads HEXDOM_DATA/cad/*.step|*.stp (default ../shared/data). Prints, never asserts. Times are the
best of --repeat runs (default 3) of _hexdom.tessellate_file, which includes reading the file;
the read alone (cad_volume) is timed separately.
"""

import argparse
import glob
import os
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.environ.get("HEXDOM_DATA", os.path.join(ROOT, "..", "shared", "data"))


def load_hexdom():
    sys.path.insert(0, ROOT)
    from HexDomWorkbench import core
    return core._hexdom


def min_angles(V, F):
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]

    def ang(u, v):
        return np.degrees(np.arctan2(np.linalg.norm(np.cross(u, v), axis=1), (u * v).sum(1)))
    return np.minimum(np.minimum(ang(b - a, c - a), ang(a - b, c - b)), ang(a - c, b - c))


def best_time(f, repeat):
    best, result = float("inf"), None
    for _ in range(repeat):
        t = time.perf_counter()
        result = f()
        best = min(best, time.perf_counter() - t)
    return best, result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("parts", nargs="*", help="STEP files (default: every one under HEXDOM_DATA/cad)")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--divisions", type=float, default=30.0, help="size = diagonal / this")
    args = parser.parse_args()
    parts = args.parts or sorted(glob.glob(os.path.join(DATA, "cad", "*.st*p")))
    if not parts:
        print(f"no STEP parts under {os.path.join(DATA, 'cad')} (set HEXDOM_DATA)")
        return
    hx = load_hexdom()
    if not hx.has_opencascade():
        print("_hexdom was built without OpenCASCADE: nothing to measure")
        return
    print(f"{'part':34s} {'faces':>5s} {'size':>8s} {'triangles':>9s} {'tri/s':>8s} {'read s':>7s} "
          f"{'total s':>7s} {'min planar':>10s} {'min all':>7s} {'vol err %':>9s} {'edge/size':>9s}")
    total = 0.0
    for path in parts:
        info = hx.cad_info(path)
        size = np.linalg.norm(np.subtract(info["bbox_max"], info["bbox_min"])) / args.divisions
        t_read, _ = best_time(lambda: hx.cad_volume(path), args.repeat)
        t, (V, F, face_id) = best_time(lambda: hx.tessellate_file(path, size=size), args.repeat)
        total += t
        ang = min_angles(V, F)
        planar = np.array([info["face_types"][f - 1] == "plane" for f in face_id])
        a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
        vol = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6
        err = 100 * (vol - info["volume"]) / info["volume"]
        edges = np.linalg.norm(V[F] - V[np.roll(F, -1, axis=1)], axis=2)
        planar_min = f"{ang[planar].min():10.2f}" if planar.any() else f"{'-':>10s}"
        print(f"{os.path.basename(path):34s} {info['faces']:5d} {size:8.4g} {len(F):9d} {len(F) / t:8.0f} "
              f"{t_read:7.3f} {t:7.3f} {planar_min} {ang.min():7.2f} {err:+9.3f} {edges.mean() / size:9.2f}")
    print(f"total {total:.2f} s")


if __name__ == "__main__":
    main()
