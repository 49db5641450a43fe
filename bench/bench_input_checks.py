"""Cost of the input checks every meshing path makes first (mesh::check_solid_surface: closed,
oriented, facing out, not crossing itself, one solid with its cavities) against the whole of
`hexdom mesh`, on CAD parts: each part's tessellation at the default size is checked (median of
--repeat) and the program is timed once on the part. Also counts, over a corpus directory, the parts
whose tessellation the checks refuse or turn around (expected: none; a B-rep's tessellation is
closed, outward and free of crossings), and with --surfaces every .k / .stl / .obj / .off under a
directory that reads as a triangle surface (the paper's inputs: what each check says of them).

Target (issue "Surfaces as other tools export them"): the checks under 10% of `hexdom mesh`'s time.

Run: /usr/bin/python3 bench/bench_input_checks.py --cad ../shared/data/cad [--corpus DIR]
     [--surfaces ../shared/data/hexdom] [--repeat 5] [--hexdom build/bin/hexdom]
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
sys.path.insert(0, os.path.join(os.environ.get("HEXDOM_BUILD_DIR", os.path.join(REPO, "build")), "python"))
import _hexdom  # noqa: E402


def check_seconds(V, F, patch, repeat):
    times, result = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        result = _hexdom.check_surface(V, F, patch)
        times.append(time.perf_counter() - t0)
    return statistics.median(times), result


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cad", required=True)
    ap.add_argument("--corpus")
    ap.add_argument("--surfaces")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--hexdom", default=os.path.join(REPO, "build", "bin", "hexdom"))
    args = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="hexdom-bench-checks-")
    print(f"{'part':28s} {'triangles':>9s} {'check s':>8s} {'mesh s':>7s} {'share':>6s}")
    shares = []
    for path in sorted(glob.glob(os.path.join(args.cad, "*.st*p"))):
        name = os.path.basename(path).rsplit(".", 1)[0]
        V, F, patch = _hexdom.tessellate_file(path, size=0.0, solid=0)
        t_check, r = check_seconds(V, F, patch, args.repeat)
        t0 = time.perf_counter()
        subprocess.run([args.hexdom, "mesh", path, "-o", os.path.join(tmp, name + ".vtu"), "--allow-inverted"],
                       capture_output=True, text=True)
        t_mesh = time.perf_counter() - t0
        shares.append(t_check / t_mesh)
        print(f"{name:28s} {len(F):9d} {t_check:8.4f} {t_mesh:7.2f} {100 * t_check / t_mesh:5.2f}%"
              + (f"  {r['warnings']}" if r["warnings"] else ""), flush=True)
    print(f"\nchecks / hexdom mesh: median {100 * statistics.median(shares):.2f}%, max {100 * max(shares):.2f}%")
    if args.corpus:
        refused, turned, n = [], [], 0
        for path in sorted(glob.glob(os.path.join(args.corpus, "*.step"))):
            n += 1
            V, F, patch = _hexdom.tessellate_file(path, size=0.0, solid=0)
            try:
                r = _hexdom.check_surface(V, F, patch, os.path.basename(path))
                if r["flipped_shells"]:
                    turned.append(os.path.basename(path))
            except _hexdom.Error as e:
                refused.append(f"{os.path.basename(path)}: {e}")
        print(f"corpus: {n} tessellations checked, {len(refused)} refused, {len(turned)} turned around")
        for line in refused + turned:
            print("  " + line)
    if args.surfaces:
        check_surfaces(args.surfaces)
    return 0


def check_surfaces(root):
    """Checks every file under ``root`` that reads as a triangle surface; prints what the checks say."""
    counts = {"surfaces": 0, "refused": 0, "warned": 0}
    for path in sorted(glob.glob(os.path.join(root, "**", "*"), recursive=True)):
        if not path.lower().endswith((".k", ".stl", ".obj", ".off")):
            continue
        try:
            V, F, patch = _hexdom.read_surface(path)
        except _hexdom.Error:
            continue  # a volume mesh or a structure, not a surface
        counts["surfaces"] += 1
        name = os.path.relpath(path, root)
        try:
            r = _hexdom.check_surface(V, F, patch, name, several_solids=True)
            if r["warnings"]:
                counts["warned"] += 1
                print(f"  warned: {' / '.join(r['warnings'])}")
        except _hexdom.Error as e:
            counts["refused"] += 1
            print(f"  refused: {e}")
    print("surfaces under {}: {surfaces} read, {refused} refused, {warned} warned".format(root, **counts))


if __name__ == "__main__":
    sys.exit(main())
