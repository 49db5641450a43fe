"""Prism blocks along knife edges (issue 9): `hexdom mesh` with hex blocks only (--sliver-ratio 0)
and with the default, on the thin wedge of the tests (remeshed), the wedges made with FreeCAD Part
(when FreeCAD imports), the shared CAD parts and the paper's raw surfaces. Per run: cells per type,
worst / mean scaled Jacobian per type by Verdict (VTK; wedges through libvtkverdict), inverted
cells, volume against the B-rep's (CAD) or the surface's, and seconds.

Run: HEXDOM_BUILD_DIR=build HEXDOM_DATA=/work/shared/data /usr/bin/python3 bench/bench_prisms.py [names...]
Names: thin_wedge, fc_wedge, fc_chamfer, CAD part stems (s09o_bridge, ...), paper models (hepta, ...);
default: all. Prints, never asserts.
"""

import glob
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.environ.get("HEXDOM_DATA", os.path.join(ROOT, "..", "shared", "data"))
BUILD = os.environ.get("HEXDOM_BUILD_DIR", os.path.join(ROOT, "build"))
sys.path.insert(0, os.path.join(ROOT, "tests", "python"))
import hexdom_oracles as oracle  # noqa: E402
import hexdom_test_support as support  # noqa: E402

HEXDOM = os.path.join(BUILD, "bin", "hexdom")
CAD = ["s09o_bridge", "s11o_cube_cyl", "s15o_cylinder", "s12o_cube_rounded_1", "s14o_cube_corner_sub_sphere",
       "n11o_limit_cycle", "i10o_simp", "i11o_s1"]
PAPER = ["hepta", "mount1", "rockerarm", "mountwithhole"]
NAMES = {oracle.HEX: "hex", oracle.WEDGE: "prism", oracle.TET: "tet"}


def thin_wedge(d):
    """The tests' thin wedge (15 degree knife edge), remeshed to triangles of 0.15 (its own
    triangles are 5 long: no band along the edge could be narrow)."""
    V, F, P = support.thin_wedge()
    raw = os.path.join(d, "thin_wedge_raw.k")
    support.write_k_surface(raw, V, F, P)
    out = os.path.join(d, "thin_wedge.k")
    subprocess.run([HEXDOM, "remesh", "-i", raw, "-o", out, "--size", "0.15"], check=True, capture_output=True)
    return out


def freecad_part(d, which):
    sys.path += ["/usr/lib/freecad-python3/lib", "/usr/share/freecad/Mod", "/usr/share/freecad/Ext"]
    try:
        import FreeCAD  # noqa: F401
        import Part
    except ImportError:
        return None
    V = FreeCAD.Vector
    if which == "fc_wedge":  # tests/freecad/app/test_mesh_part.py::_wedge
        shape = Part.Face(Part.makePolygon([V(0, 0, 0), V(40, 0, 0), V(0, 0, 20), V(0, 0, 0)])).extrude(V(0, 30, 0))
    else:  # _chamfered_box
        box = Part.makeBox(40, 30, 20)
        shape = box.makeChamfer(6, [e for e in box.Edges if abs(e.Length - 30) < 1e-6][:2])
    path = os.path.join(d, which + ".step")
    shape.exportStep(path)
    return path


def measure(name, path, d, ratio):
    out = os.path.join(d, f"{name}_{ratio}.vtu")
    args = [HEXDOM, "mesh", path, "-o", out, "--allow-inverted"] + ([] if ratio is None else ["--sliver-ratio", str(ratio)])
    t = time.time()
    r = subprocess.run(args, capture_output=True, text=True)
    secs = time.time() - t
    label = "default" if ratio is None else f"ratio {ratio}"
    if r.returncode != 0:
        print(f"{name:28s} {label:10s} failed: {r.stderr.strip().splitlines()[-1][:160]}", flush=True)
        return
    g = oracle.read_vtu(out)
    sj, _ = oracle.verdict_metrics(g)
    types = np.array([g.GetCellType(i) for i in range(g.GetNumberOfCells())])
    volume = float(oracle.signed_volumes(g).sum())
    ref = [ln for ln in r.stdout.splitlines() if " volume " in ln and "%" in ln]
    ref_err = ref[-1].split("(")[-1].rstrip(")") if ref else "?"
    parts = []
    for t, n in NAMES.items():
        m = types == t
        if m.any():
            parts.append(f"{n} {int(m.sum()):6d} SJ {sj[m].min():6.3f}/{sj[m].mean():5.3f}")
    blocks = [ln for ln in r.stderr.splitlines() if ln.strip().startswith("autopolycube:") or "autopolycube:" in ln]
    prism_blocks = ""
    for ln in blocks:
        if "prism," in ln:
            prism_blocks = ln[ln.index("("):ln.index(")") + 1] if "(" in ln else ""
    print(f"{name:28s} {label:10s} | {' | '.join(parts)} | inverted {int(np.sum(~(sj > 0)))} | volume {volume:.6g} "
          f"({ref_err}) | {secs:5.1f} s {prism_blocks}", flush=True)


def main():
    names = sys.argv[1:] or ["thin_wedge", "fc_wedge", "fc_chamfer"] + CAD + PAPER
    with tempfile.TemporaryDirectory() as d:
        for name in names:
            if name == "thin_wedge":
                path = thin_wedge(d)
            elif name.startswith("fc_"):
                path = freecad_part(d, name)
                if path is None:
                    print(f"{name}: skipped, FreeCAD does not import")
                    continue
            elif name in PAPER:
                path = os.path.join(DATA, "hexdom", name, name + ".k")
            else:
                paths = glob.glob(os.path.join(DATA, "cad", name + ".*"))
                path = paths[0] if paths else None
            if not path or not os.path.exists(path):
                print(f"{name}: skipped, data missing")
                continue
            for ratio in (0, None):
                measure(name, path, d, ratio)


if __name__ == "__main__":
    main()
