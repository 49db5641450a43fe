"""Mesh Part in FreeCAD against `hexdom mesh` on the same parts: time (whole call each, median of
--repeat, alternating) and whether the meshes are the same (cell counts, node coordinates).

Mesh Part runs `hexdom mesh`'s pipeline once inside FreeCAD (the HexDom Mesh object's Pipeline)
and fills the document objects from it; the program reads the BREP text FreeCAD holds
(shape.exportBrepToString() written to a file), so both mesh the same shape. Mesh Part is timed in
a warm FreeCAD session (its FEM module loaded by a first run on a small box, as in a session where
a FEM analysis is open): mesh_part() from the call to the checked objects, document objects
included. The program is timed as a whole process.

Target (issue "One pipeline behind every front end"): Mesh Part within 1.2 x `hexdom mesh`.

Run: /usr/bin/python3 bench/bench_mesh_part.py [--cad DIR] [--corpus DIR --limit N] [--repeat 3] [--repeat-short 7]
     [--hexdom build/bin/hexdom] [--polycube-seconds S]
(the bundled bracket always; HEXDOM_BUILD_DIR or build/ gives _hexdom.)
"""

import argparse
import glob
import os
import statistics
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
for p in ("/usr/lib/freecad-python3/lib", "/usr/share/freecad/Mod", "/usr/share/freecad/Ext", REPO):
    if p not in sys.path:
        sys.path.append(p)
os.environ.setdefault("HEXDOM_BUILD_DIR", os.path.join(REPO, "build"))

import FreeCAD  # noqa: E402
import Part  # noqa: E402
import numpy as np  # noqa: E402

import HexDomWorkbench as hexdom  # noqa: E402
from HexDomWorkbench.objects import hex_mesh  # noqa: E402


def read_vtu_points(path):
    import meshio
    m = meshio.read(path)
    return m.points, sum(len(c.data) for c in m.cells)


def run_cli(binary, brep, out, seconds):
    t0 = time.perf_counter()
    r = subprocess.run([binary, "mesh", brep, "-o", out, "--allow-inverted"]
                       + (["--polycube-seconds", str(seconds)] if seconds is not None else []),
                       capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if r.returncode != 0:
        raise RuntimeError(r.stderr.strip().splitlines()[-1] if r.stderr.strip() else "exit %d" % r.returncode)
    return dt


def run_mesh_part(shape, name, seconds):
    doc = FreeCAD.newDocument("bench_" + name)
    try:
        part = doc.addObject("Part::Feature", name)
        part.Shape = shape
        doc.recompute()
        t0 = time.perf_counter()
        objs = hexdom.mesh_part(doc, part, allow_inverted=True, polycube_seconds=seconds)
        dt = time.perf_counter() - t0
        mesh = hex_mesh.get_mesh(objs["mesh"])
        return dt, np.asarray(mesh.V), len(mesh.types), objs["mesh"].MeshingPath
    finally:
        FreeCAD.closeDocument(doc.Name)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cad", help="directory of STEP parts (../shared/data/cad)")
    ap.add_argument("--corpus", help="directory of bench/make_corpus.py parts")
    ap.add_argument("--limit", type=int, default=10, help="corpus parts taken (sorted by name, spread)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--repeat-short", type=int, default=7,
                    help="repeats for a part whose first `hexdom mesh` takes under 2 s (their run-to-run "
                         "spread, about 0.15 s, is a large part of them)")
    ap.add_argument("--hexdom", default=os.path.join(REPO, "build", "bin", "hexdom"))
    ap.add_argument("--polycube-seconds", type=float, default=None,
                    help="the polycube path's budget for both (default: the default's 20 s; 0: none)")
    args = ap.parse_args()
    parts = [os.path.join(REPO, "examples", "data", "bracket.step")]
    if args.cad:
        parts += sorted(glob.glob(os.path.join(args.cad, "*.st*p")))
    if args.corpus:
        found = sorted(glob.glob(os.path.join(args.corpus, "*.step")))
        step = max(1, len(found) // max(1, args.limit))
        parts += found[::step][:args.limit]
    tmp = tempfile.mkdtemp(prefix="hexdom-bench-mesh-part-")
    run_mesh_part(Part.makeBox(10, 10, 10), "warmup", args.polycube_seconds)  # loads Fem
    print(f"{'part':28s} {'path':8s} {'cells':>7s} {'hexdom s':>9s} {'MeshPart s':>10s} {'ratio':>6s} same")
    ratios, rows = [], 0
    for path in parts:
        name = os.path.basename(path).rsplit(".", 1)[0]
        shape = Part.read(path)
        brep = os.path.join(tmp, name + ".brep")
        with open(brep, "w") as f:
            f.write(shape.exportBrepToString())
        out = os.path.join(tmp, name + ".vtu")
        cli_t, fc_t = [], []
        try:
            repeat = args.repeat
            while len(cli_t) < repeat:
                cli_t.append(run_cli(args.hexdom, brep, out, args.polycube_seconds))
                t, V, cells, method = run_mesh_part(shape, name, args.polycube_seconds)
                fc_t.append(t)
                if len(cli_t) == 1 and cli_t[0] < 2.0:
                    repeat = max(repeat, args.repeat_short)
        except Exception as e:  # noqa: BLE001 - a bench reports and goes on
            print(f"{name:28s} failed: {e}")
            continue
        P, cli_cells = read_vtu_points(out)
        same = P.shape == V.shape and cli_cells == cells and float(np.abs(P - V).max(initial=0)) <= 1e-12 * max(
            1.0, float(np.abs(P).max(initial=0)))
        a, b = statistics.median(cli_t), statistics.median(fc_t)
        ratios.append(b / a)
        rows += 1
        print(f"{name:28s} {method:8s} {cells:7d} {a:9.2f} {b:10.2f} {b / a:6.2f} {'yes' if same else 'NO'}",
              flush=True)
    if ratios:
        print(f"\n{rows} parts, median of {args.repeat} ({args.repeat_short} under 2 s): Mesh Part / hexdom mesh median {statistics.median(ratios):.2f}, "
              f"max {max(ratios):.2f}; within 1.2 x: {sum(r <= 1.2 for r in ratios)}/{len(ratios)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
