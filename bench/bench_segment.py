"""Segmentation time and figures on the paper's raw surfaces, the largest shared surface and
refined copies of rockerarm (target: rockerarm, 23k triangles, in at most 1 s).

Run: HEXDOM_BUILD_DIR=build /usr/bin/python3 bench/bench_segment.py
Per model: triangles, best-of-3 time of core.segment (no file IO) and of `hexdom segment` (with IO),
then the figures of the segmentation: area share within 55 degrees of the label's axis, patches,
zig-zag triangles and boundary length against the classical CVT's, and the area on which the labels
agree with the axis of the paper's patch at the same place (nearest centroid), next to the
nearest-axis labelling of the same triangles (the paper's patches taken as connected regions, and
as part ids as REFERENCE.md did). Prints, never asserts.
"""

import glob
import os
import subprocess
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.environ.get("HEXDOM_DATA", os.path.join(ROOT, "..", "shared", "data"))
BUILD = os.environ.get("HEXDOM_BUILD_DIR", os.path.join(ROOT, "build"))
sys.path.insert(0, ROOT)
from HexDomWorkbench import core  # noqa: E402

MODELS = {"rockerarm": "rockerarm_indexPatch_hexdom.k", "mount1": "mount1_patch_hexdom.k",
          "hepta": "hepta_patch_hexdom.k", "fertility": "fertility_indexPatch_hexdom.k",
          "ant": "ant_indexPatch_hexdom.k", "mountwithhole": "mountwithhole_patch_hexdom.k"}
AXES = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float)


def best_of(n, f):
    times = []
    for _ in range(n):
        t0 = time.perf_counter()
        r = f()
        times.append(time.perf_counter() - t0)
    return min(times), r


def geometry(s):
    V, F = np.asarray(s.V), np.asarray(s.F)
    n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    a = np.linalg.norm(n, axis=1) / 2
    return n / (2 * a[:, None]), a, V[F].mean(axis=1)


def paper_labels(path):
    """Centroids and per-triangle axis labels of the paper's patches, by region and by part id."""
    from scipy.spatial import cKDTree  # noqa: F401  (checked by the caller)
    s = core.read_surface(path)
    n, a, c = geometry(s)
    out = []
    for groups in (core.number_patches(s), np.asarray(s.patch)):
        _, inv = np.unique(groups, return_inverse=True)
        mean = np.zeros((inv.max() + 1, 3))
        np.add.at(mean, inv, n * a[:, None])
        out.append((np.argmax(mean @ AXES.T, axis=1) + 1)[inv])
    return c, out[0], out[1]


def refine(s):
    """1-to-4 subdivision of every triangle (labels/patch ids copied)."""
    V, F = np.asarray(s.V), np.asarray(s.F)
    e = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    uniq, inv = np.unique(e, axis=0, return_inverse=True)
    mid = len(V) + inv.reshape(3, -1).T
    V2 = np.vstack([V, (V[uniq[:, 0]] + V[uniq[:, 1]]) / 2])
    a, b, c = F.T
    ab, bc, ca = mid.T
    F2 = np.concatenate([np.stack(t, 1) for t in ((a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca))])
    return core.Surface(V2, F2.astype(np.int32), np.tile(np.asarray(s.patch), 4))


def cli_time(path):
    out = os.path.join("/tmp", "bench_segment_out.k")
    exe = os.path.join(BUILD, "bin", "hexdom")

    def go():
        subprocess.run([exe, "segment", "-i", path, "-o", out], check=True, capture_output=True)
    t, _ = best_of(3, go)
    os.remove(out)
    return t


def main():
    if not os.path.isdir(os.path.join(DATA, "hexdom")):
        print(f"skipped: shared data missing: {os.path.join(DATA, 'hexdom')}")
        return
    try:
        from scipy.spatial import cKDTree
    except ImportError:
        cKDTree = None
    print("model          triangles  segment   CLI+IO | within55  patches(classical)  zig-zags(classical)"
          "  boundary/classical | agree  nearest-axis  (by part id: agree, nearest-axis)")
    agree_all, base_all, agree_id_all, base_id_all = [], [], [], []
    for model, patch_file in MODELS.items():
        path = os.path.join(DATA, "hexdom", model, model + ".k")
        if not os.path.exists(path):
            print(f"{model}: skipped, {path} missing")
            continue
        s = core.read_surface(path)
        t, seg = best_of(3, lambda: core.segment(s))
        st = core.segmentation_stats(seg)
        st0 = core.segmentation_stats(core.Surface(s.V, s.F, seg.classical))
        line = (f"{model:14s} {len(s.F):9d} {t * 1000:7.1f} ms {cli_time(path) * 1000:6.0f} ms | "
                f"{100 * st['axis_fraction']:6.2f}%  {st['patches']:4d} ({st0['patches']:4d})"
                f"          {st['teeth']:4d} ({st0['teeth']:4d})       "
                f"      {st['boundary_length'] / st0['boundary_length']:.3f}      |")
        ppath = os.path.join(DATA, "hexdom", model, patch_file)
        if cKDTree is not None and os.path.exists(ppath):
            n, a, c = geometry(s)
            pc, by_region, by_id = paper_labels(ppath)
            idx = cKDTree(pc).query(c)[1]
            near = np.argmax(n @ AXES.T, axis=1) + 1
            agree = a[seg.patch == by_region[idx]].sum() / a.sum()
            base = a[near == by_region[idx]].sum() / a.sum()
            agree_id = a[seg.patch == by_id[idx]].sum() / a.sum()
            base_id = a[near == by_id[idx]].sum() / a.sum()
            agree_all.append(agree)
            base_all.append(base)
            agree_id_all.append(agree_id)
            base_id_all.append(base_id)
            line += f" {100 * agree:5.1f}%   {100 * base:5.1f}%        ({100 * agree_id:5.1f}%, {100 * base_id:5.1f}%)"
        print(line)
    if agree_all:
        print(f"{'mean':>14s} {'':>60s} {'':>44s} {100 * np.mean(agree_all):5.1f}%   "
              f"{100 * np.mean(base_all):5.1f}%        ({100 * np.mean(agree_id_all):5.1f}%, "
              f"{100 * np.mean(base_id_all):5.1f}%)")

    # The largest shared surface, and rockerarm refined.
    sizes = []
    for p in glob.glob(os.path.join(DATA, "hexdom", "*", "*.k")):
        try:
            sizes.append((len(core.read_surface(p).F), p))
        except core.Error:
            pass  # solids, not surfaces
    n, largest = max(sizes)
    s = core.read_surface(largest)
    t, seg = best_of(3, lambda: core.segment(s))
    t_off, _ = best_of(3, lambda: core.segment(s, respect_faces=False))
    print(f"\nlargest shared surface: {os.path.relpath(largest, DATA)} ({n} triangles, {len(np.unique(s.patch))} "
          f"part ids taken as CAD faces): segment {t * 1000:.1f} ms ({t_off * 1000:.1f} ms ignoring the ids), "
          f"CLI with IO {cli_time(largest) * 1000:.0f} ms")
    s = core.read_surface(os.path.join(DATA, "hexdom", "rockerarm", "rockerarm.k"))
    for _ in range(2):
        s = refine(s)
        t, seg = best_of(1, lambda: core.segment(s))
        print(f"rockerarm refined: {len(s.F):8d} triangles: segment {t * 1000:8.1f} ms "
              f"({len(s.F) / t / 1e6:.2f} M triangles/s), {seg.info['classical_sweeps']} + "
              f"{seg.info['edge_sweeps']} sweeps")


if __name__ == "__main__":
    main()
