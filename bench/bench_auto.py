"""The automatic path, stage by stage: time per stage (tessellate, segment, autopolycube, generate,
improve, and snap for CAD parts, with the boundary nodes' B-rep distance before / after it), blocks, cells and quality for the paper's raw surfaces and the shared CAD parts, next to
the hand-built structures of the paper models (generate at level 2 + improve).

Run: HEXDOM_BUILD_DIR=build /usr/bin/python3 bench/bench_auto.py [names...]
Names are paper models (rockerarm, mount1, hepta, fertility, ant, mountwithhole) or CAD part stems
(s09o_bridge, ...); default: all. Prints, never asserts.
"""

import glob
import os
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.environ.get("HEXDOM_DATA", os.path.join(ROOT, "..", "shared", "data"))
sys.path.insert(0, ROOT)
from HexDomWorkbench import core  # noqa: E402

PAPER = ["hepta", "mount1", "rockerarm", "fertility", "ant", "mountwithhole"]
HAND = {  # model: (patch file, structure)
    "rockerarm": ("rockerarm_indexPatch_hexdom.k", "rockerarm_polycube_withtet.k"),
    "mount1": ("mount1_patch_hexdom.k", "mount1_polycube_hexdom_withtet.k"),
    "hepta": ("hepta_patch_hexdom.k", "hepta_polycube_withtet.k"),
}
CAD = ["s09o_bridge", "s11o_cube_cyl", "s15o_cylinder", "s12o_cube_rounded_1", "s14o_cube_corner_sub_sphere",
       "n11o_limit_cycle", "i10o_simp", "i11o_s1", "i01o_m1"]


def enclosed_volume(s):
    a, b, c = s.V[s.F[:, 0]], s.V[s.F[:, 1]], s.V[s.F[:, 2]]
    import numpy as np
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def line(name, run, reference):
    q, info = run.quality, run.polycube.info
    counts = "/".join(str(q[t]["count"]) for t in ("hex", "prism", "tet"))
    stages = " ".join(f"{k} {v:6.2f}s" for k, v in run.seconds.items())
    err = 100.0 * (q["total_volume"] - reference) / reference
    print(f"{name:28s} {stages} | {info['charts']:3d} charts ({info['relabelled']:3d} relabelled) "
          f"{info['blocks']:5d} blocks (level {run.level}, lambda {run.edge_weight:g}) | cells {counts:>14s} "
          f"| hex SJ min {q['hex']['sj_min']:6.3f} mean {q['hex']['sj_mean']:5.3f} | inverted {run.inverted} "
          f"| volume {err:+6.2f}%"
          + (f" | B-rep distance {run.snap['max_before'] / run.snap['diagonal']:.1e} -> "
             f"{run.snap['max_after'] / run.snap['diagonal']:.1e} x diagonal" if run.snap else ""), flush=True)


def paper(model):
    path = os.path.join(DATA, "hexdom", model, model + ".k")
    if not os.path.exists(path):
        print(f"{model}: skipped, shared data missing: {path}")
        return
    s = core.read_surface(path)
    try:
        line(model, core.mesh_surface(s, allow_inverted=True), enclosed_volume(s))
    except core.Error as e:
        print(f"{model:28s} failed: {str(e).splitlines()[0][:160]}", flush=True)
    if model in HAND:
        d = os.path.join(DATA, "hexdom", model)
        ps = core.read_surface(os.path.join(d, HAND[model][0]))
        t0 = time.perf_counter()
        m = core.improve(core.generate(ps, core.read_mesh(os.path.join(d, HAND[model][1])), level=2), surface=ps)
        q = core.quality_report(m)
        counts = "/".join(str(q[t]["count"]) for t in ("hex", "prism", "tet"))
        print(f"{model + ' (hand-built, level 2)':28s} generate+improve {time.perf_counter() - t0:6.2f}s | "
              f"cells {counts:>14s} | hex SJ min {q['hex']['sj_min']:6.3f} mean {q['hex']['sj_mean']:5.3f}", flush=True)


def cad(stem):
    paths = glob.glob(os.path.join(DATA, "cad", stem + ".*"))
    if not paths:
        print(f"{stem}: skipped, shared data missing: {os.path.join(DATA, 'cad', stem)}.*")
        return
    if not getattr(core._hexdom, "has_opencascade", lambda: False)():
        print(f"{stem}: skipped, _hexdom built without OpenCASCADE")
        return
    try:
        run = core.mesh_part(paths[0], allow_inverted=True)
        line(stem, run, core._hexdom.cad_volume(paths[0]))
    except core.Error as e:
        print(f"{stem:28s} failed: {str(e).splitlines()[0][:160]}", flush=True)


if __name__ == "__main__":
    for name in sys.argv[1:] or PAPER + CAD:
        (paper if name in PAPER else cad)(name)
