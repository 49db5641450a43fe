"""Same results before and after a refactoring: the figures a behaviour-keeping change must not move.

For `hexdom mesh` on the shared CAD parts (../shared/data/cad), the bundled bracket, the six paper
models' raw surfaces and, with --corpus, our own parts (bench/make_corpus.py), and for `hexdom
generate` (level 2) + `hexdom improve` on the six paper models' hand-built structures, prints
per run: cells per type, worst and mean scaled Jacobian per type, the total volume, and two
fingerprints of the written mesh (sum of the node coordinates, and a hash of the connectivity) that
change when any node moves or any cell changes.

The 17 corpus parts compared so far are make_corpus.py's fixed ones: `make_corpus.py D --count 0`
writes only them (without --count 0, D also holds 200 seeded parts, and --corpus runs them all).

Run:   HEXDOM_BUILD_DIR=build /usr/bin/python3 bench/bench_same_results.py [--save F] [--compare F] [--corpus D] [names]
--save writes the figures as JSON; --compare reads such a file (e.g. made before the change) and prints
every figure that differs by more than 1e-9, per run. Prints, never asserts.
"""

import argparse
import glob
import hashlib
import json
import os
import subprocess
import sys
import tempfile
import time

import meshio

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.environ.get("HEXDOM_DATA", os.path.join(ROOT, "..", "shared", "data"))
BUILD = os.environ.get("HEXDOM_BUILD_DIR", os.path.join(ROOT, "build"))
HEXDOM = os.path.join(BUILD, "bin", "hexdom")

sys.path.insert(0, os.path.join(ROOT, "tests", "python"))
from hexdom_test_support import PAPER_MODELS as PAPER  # noqa: E402  (model: patch file, hand-built structure)


def fingerprint(path):
    m = meshio.read(path)
    h = hashlib.sha1()
    for block in m.cells:
        h.update(block.type.encode())
        h.update(block.data.astype("int64").tobytes())
    return {"coordinate_sum": float(abs(m.points).sum()), "connectivity": h.hexdigest()[:16]}


def figures(report_path, mesh_path):
    with open(report_path) as f:
        q = json.load(f)
    out = {}
    for t in ("hex", "prism", "tet"):
        out[t + "_count"] = q[t]["count"]
        if q[t]["count"]:
            out[t + "_sj_min"] = q[t]["sj_min"]
            out[t + "_sj_mean"] = q[t]["sj_mean"]
    out["inverted"] = sum(q[t]["inverted"] for t in ("hex", "prism", "tet"))
    out["volume"] = q["total_volume"]
    out.update(fingerprint(mesh_path))
    return out


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError((p.stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1])


def mesh_part(path, tmp):
    out, rep = os.path.join(tmp, "m.vtu"), os.path.join(tmp, "m.json")
    run([HEXDOM, "mesh", path, "-o", out, "--report", rep, "--allow-inverted"])
    return figures(rep, out)


def paper_model(model, tmp):
    d = os.path.join(DATA, "hexdom", model)
    gen, out, rep = os.path.join(tmp, "g.vtk"), os.path.join(tmp, "i.vtu"), os.path.join(tmp, "i.json")
    patches = os.path.join(d, PAPER[model][0])
    run([HEXDOM, "generate", "-i", patches, "-p", os.path.join(d, PAPER[model][1]), "-s", "2", "-o", gen])
    run([HEXDOM, "improve", "-i", gen, "--surface", patches, "-o", out, "--report", rep, "--allow-inverted"])
    return figures(rep, out)


def cases(names, corpus):
    bracket = os.path.join(ROOT, "examples", "data", "bracket.step")
    all_cases = [("bracket", lambda t: mesh_part(bracket, t))]
    for path in sorted(glob.glob(os.path.join(DATA, "cad", "*.st*p"))):
        all_cases.append((os.path.splitext(os.path.basename(path))[0], (lambda p: lambda t: mesh_part(p, t))(path)))
    for model in PAPER:
        ok = os.path.exists(os.path.join(DATA, "hexdom", model))
        all_cases.append((model + " (hand, level 2)", (lambda m: lambda t: paper_model(m, t))(model) if ok else None))
        raw = os.path.join(DATA, "hexdom", model, model + ".k")
        all_cases.append((model + " (raw surface)", (lambda p: lambda t: mesh_part(p, t))(raw) if ok else None))
    for path in sorted(glob.glob(os.path.join(corpus, "*.step"))) if corpus else []:
        all_cases.append(("corpus/" + os.path.splitext(os.path.basename(path))[0], (lambda p: lambda t: mesh_part(p, t))(path)))
    return [c for c in all_cases if not names or c[0].split()[0] in names]


def differences(before, after):
    keys = sorted(set(before) | set(after))
    out = []
    for k in keys:
        a, b = before.get(k), after.get(k)
        if isinstance(a, float) and isinstance(b, float):
            if abs(a - b) > 1e-9 * max(1.0, abs(a)):
                out.append(f"{k} {a!r} -> {b!r}")
        elif a != b:
            out.append(f"{k} {a!r} -> {b!r}")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--save")
    ap.add_argument("--compare")
    ap.add_argument("--corpus", help="also every .step in this folder (bench/make_corpus.py writes one)")
    ap.add_argument("names", nargs="*")
    args = ap.parse_args()
    before = json.load(open(args.compare)) if args.compare else None
    results, same = {}, 0
    for name, fn in cases(args.names, args.corpus):
        if fn is None:
            print(f"{name:30s} skipped: shared data missing under {DATA}")
            continue
        t0 = time.perf_counter()
        with tempfile.TemporaryDirectory() as tmp:
            try:
                r = fn(tmp)
            except RuntimeError as e:
                r = {"error": str(e).replace(tmp, "<tmp>")[:200]}
        results[name] = r
        sec = time.perf_counter() - t0
        if "error" in r:
            line = f"failed: {r['error']}"
        else:
            cells = "/".join(str(r[t + "_count"]) for t in ("hex", "prism", "tet"))
            line = (f"cells {cells:>16s} hex SJ min {r.get('hex_sj_min', float('nan')):.12f} "
                    f"mean {r.get('hex_sj_mean', float('nan')):.12f} inverted {r['inverted']} "
                    f"coords {r['coordinate_sum']:.9e} conn {r['connectivity']}")
        verdict = ""
        if before is not None:
            if name not in before:
                verdict = " | not in the compared file"
            else:
                d = differences(before[name], r)
                same += not d
                verdict = " | same" if not d else " | DIFFERS: " + "; ".join(d)
        print(f"{name:30s} {sec:6.1f}s {line}{verdict}", flush=True)
    if before is not None:
        print(f"{same} of {len(results)} runs give the same figures as {args.compare}")
    if args.save:
        with open(args.save, "w") as f:
            json.dump(results, f, indent=1, sort_keys=True)


if __name__ == "__main__":
    sys.exit(main())
