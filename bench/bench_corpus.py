"""Every closed solid meshes: runs `hexdom mesh` on every part of a corpus (bench/make_corpus.py) and
of extra STEP folders, per method, and prints per run and in total how many parts meet the targets.

Per run (one part, one method): `hexdom mesh PART.step -o OUT.vtu --report R.json --allow-inverted
[--method M]`, killed after --timeout seconds (counted as "timeout"). From the report and the
reference volume (the manifest's B-rep volume; for the parts of an --extra folder, FreeCAD's
Solids[0].Volume of the STEP file; for a --surface, the volume the surface encloses, as `hexdom mesh`
prints it):
  meshed    the report was written
  inv       no inverted cell (hex, prism, tet)
  SJ        worst hex scaled Jacobian >= 0.3 (no hex: not met)
  vol       |mesh volume - B-rep volume| <= 1% of the B-rep volume
  ER        largest edge ratio over the cell types <= 10 (a target of its own, on 90% of the parts;
            not part of "all")
  time      wall time < 10 s
  all       meshed, inv, SJ, vol and time together
Totals per method, for the corpus, for the extra parts (folders and surfaces), and for both together: the percentage of
parts meeting each target, median and maximum time, parts over 10 s; then the runs that miss a
target, each with its first reason (the error's first line when it did not mesh).

Methods: --methods auto,polycube,overlay (default) passes `--method M`. When the binary's `hexdom
mesh --help` lists no --method, the part runs once without it and the column is labelled
"polycube" (a note says so).

Run:  /usr/bin/python3 bench/bench_corpus.py CORPUS_DIR [--extra ../shared/data/cad] [--hexdom PATH]
          [--methods auto,polycube,overlay] [--timeout 60] [--jobs 1] [--parts GLOB] [--limit N]
          [--json OUT.json] [--surface SURFACE.k ...]
The issue's sets, the corpus, the shared CAD parts and the paper's six raw surfaces, in one run:
  bench_corpus.py CORPUS_DIR --extra ../shared/data/cad --methods auto --jobs 1 \
      $(for m in rockerarm mount1 hepta fertility ant mountwithhole; do echo --surface ../shared/data/hexdom/$m/$m.k; done)
--json is rewritten after every run (an interrupted bench keeps its runs; "complete" says whether
it finished). CORPUS_DIR holds manifest.json and the STEP files (/usr/bin/python3 bench/make_corpus.py CORPUS_DIR).
The binary: --hexdom, else $HEXDOM_BUILD_DIR/bin/hexdom, else build/bin/hexdom of the repository.
--limit N keeps N corpus parts spread evenly over the sorted names (every family appears once N >= 20
or so); the extra folders' parts are always run. /usr/bin/python3 (FreeCAD's Python) is needed
only for the reference volume of the extra folders' parts. With --jobs > 1 the runs share the
cores, so their times are longer than alone: a run under auto uses both cores of this machine (the
overlay beside the polycube), and the issue's times are those of --jobs 1. Prints, never asserts.
"""

import argparse
import concurrent.futures
import fnmatch
import glob
import json
import os
import re
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FREECAD_PATHS = ("/usr/lib/freecad-python3/lib", "/usr/share/freecad/Mod", "/usr/share/freecad/Ext")

SJ_MIN = 0.3
VOLUME_TOL = 0.01
EDGE_RATIO_MAX = 10.0
TIME_MAX = 10.0
TARGETS = ("meshed", "inv", "SJ", "vol", "ER", "time", "all")


def default_hexdom():
    build = os.environ.get("HEXDOM_BUILD_DIR") or os.path.join(ROOT, "build")
    return os.path.join(build, "bin", "hexdom")


def has_method_option(hexdom):
    p = subprocess.run([hexdom, "mesh", "--help"], capture_output=True, text=True)
    return "--method" in p.stdout + p.stderr


def freecad_volume(path):
    """B-rep volume of the first solid of a STEP file (FreeCAD / OpenCASCADE), or None."""
    for p in FREECAD_PATHS:
        if p not in sys.path:
            sys.path.append(p)
    try:
        import FreeCAD  # noqa: F401  (Part needs FreeCAD imported first, else it crashes)
        import Part
    except ImportError:
        return None
    shape = Part.read(path)
    return shape.Solids[0].Volume if shape.Solids else None


def spread(items, n):
    """n of items, evenly spaced (all when n >= len(items))."""
    if n is None or n >= len(items):
        return list(items)
    if n <= 0:
        return []
    return [items[int(k * len(items) / n)] for k in range(n)]


def collect(corpus, extras, pattern, limit, surfaces=()):
    """[{name, path, family, group, ref_volume, ref_source}] of the corpus and the extra folders."""
    parts = []
    if corpus:
        with open(os.path.join(corpus, "manifest.json")) as f:
            manifest = json.load(f)
        names = sorted(n for n in manifest["parts"] if not pattern or fnmatch.fnmatch(n, pattern))
        for name in spread(names, limit):
            info = manifest["parts"][name]
            parts.append({"name": name, "path": os.path.join(corpus, name + ".step"), "family": info["family"],
                          "group": "corpus", "ref_volume": info["volume"], "ref_source": "manifest"})
    for folder in extras:
        paths = sorted(p for ext in ("*.step", "*.stp", "*.STEP", "*.STP") for p in glob.glob(os.path.join(folder, ext)))
        for path in dict.fromkeys(paths):
            name = os.path.splitext(os.path.basename(path))[0]
            if pattern and not fnmatch.fnmatch(name, pattern):
                continue
            vol = freecad_volume(path)
            parts.append({"name": name, "path": path, "family": "extra:" + os.path.basename(os.path.normpath(folder)),
                          "group": "extra", "ref_volume": vol, "ref_source": "FreeCAD" if vol else "hexdom"})
    for path in surfaces:
        name = os.path.splitext(os.path.basename(path))[0]
        if pattern and not fnmatch.fnmatch(name, pattern):
            continue
        parts.append({"name": name, "path": path, "family": "surface", "group": "extra", "ref_volume": None,
                      "ref_source": "hexdom"})
    return parts


def first_error(stderr, returncode):
    lines = [ln.strip() for ln in stderr.splitlines() if ln.strip()]
    for ln in lines:
        if ln.startswith("hexdom: error:"):
            return ln[len("hexdom: error:"):].strip()
    if returncode < 0:
        return f"killed by signal {-returncode}"
    return lines[-1] if lines else f"exit {returncode}"


def brep_volume_from_stdout(stdout):
    for ln in stdout.splitlines():
        if ln.startswith("B-rep volume ") or ln.startswith("surface volume "):
            try:
                return float(ln.split()[2])
            except (IndexError, ValueError):
                return None
    return None


def run_one(hexdom, part, method, use_method, timeout, extra_args=()):
    r = {"part": part["name"], "family": part["family"], "group": part["group"], "method": method}
    with tempfile.TemporaryDirectory(prefix="bench_corpus_") as tmp:
        out, rep = os.path.join(tmp, "m.vtu"), os.path.join(tmp, "m.json")
        cmd = [hexdom, "mesh", part["path"], "-o", out, "--report", rep, "--allow-inverted"]
        if use_method:
            cmd += ["--method", method]
        cmd += list(extra_args)
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
        try:
            stdout, stderr = p.communicate(timeout=timeout)
            r["time"] = time.perf_counter() - t0
            r["exit"] = p.returncode
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)  # its own session: the run and nothing else
            p.communicate()
            r["time"] = time.perf_counter() - t0
            r["exit"] = None
            r["status"] = "timeout"
            r["error"] = f"timeout after {timeout:g} s"
            return finish(r, part, None)
        report = None
        if os.path.exists(rep):
            try:
                with open(rep) as f:
                    report = json.load(f)
            except (OSError, ValueError) as e:
                r["error"] = f"unreadable report: {e}"
        if report is not None:
            r["status"] = "ok"
        else:
            r["status"] = "failed"
            r.setdefault("error", first_error(stderr, p.returncode))
        if part["ref_volume"] is None:
            part["ref_volume"] = brep_volume_from_stdout(stdout)
        kept = re.search(r"kept: (\w+) path", stderr)
        r["path"] = kept.group(1) if kept else None
        # Share of the boundary's area in faces that cross a CAD edge (CAD parts, after the snap;
        # the program says nothing when there are none).
        crossing = re.search(r"faces: \d+ of \d+ boundary faces \(([0-9.]+)% of the area\) cross", stderr)
        snapped = re.search(r"snap: \d+ boundary nodes", stderr)
        r["crossing"] = float(crossing.group(1)) / 100 if crossing else (0.0 if snapped else None)
        return finish(r, part, report)


def finish(r, part, report):
    ref = part["ref_volume"]
    r["ref_volume"] = ref
    t = {k: False for k in TARGETS}
    t["meshed"] = report is not None
    if report is not None:
        types = ("hex", "prism", "tet")
        r["cells"] = {k: report[k]["count"] for k in types}
        r["inverted"] = sum(report[k]["inverted"] for k in types)
        r["hex_sj_min"] = report["hex"]["sj_min"] if report["hex"]["count"] else None
        ers = [report[k]["edge_ratio_max"] for k in types if report[k]["count"] and report[k]["edge_ratio_max"] is not None]
        r["edge_ratio_max"] = max(ers) if ers else None
        r["volume"] = report["total_volume"]
        r["volume_error"] = (r["volume"] - ref) / ref if ref and r["volume"] is not None else None
        t["inv"] = r["inverted"] == 0
        t["SJ"] = r["hex_sj_min"] is not None and r["hex_sj_min"] >= SJ_MIN
        t["vol"] = r["volume_error"] is not None and abs(r["volume_error"]) <= VOLUME_TOL
        t["ER"] = r["edge_ratio_max"] is not None and r["edge_ratio_max"] <= EDGE_RATIO_MAX
    t["time"] = r["time"] < TIME_MAX
    t["all"] = all(t[k] for k in ("meshed", "inv", "SJ", "vol", "time"))
    r["targets"] = t
    return r


def reason(r):
    """The first target a run misses, as text."""
    t = r["targets"]
    if not t["meshed"]:
        return r.get("error", r["status"])
    if not t["inv"]:
        return f"{r['inverted']} inverted cells"
    if not t["SJ"]:
        return "no hex" if r["hex_sj_min"] is None else f"worst hex SJ {r['hex_sj_min']:.3f}"
    if not t["vol"]:
        return "no reference volume" if r["volume_error"] is None else f"volume {100 * r['volume_error']:+.2f}%"
    if not t["time"]:
        return f"{r['time']:.1f} s"
    return ""


HEADER = (f"{'part':28s} {'method':8s} {'status':7s} {'kept':8s} {'hex':>7s} {'prism':>6s} {'tet':>6s} {'inv':>4s} "
          f"{'SJ min':>7s} {'vol %':>8s} {'ER max':>7s} {'time s':>7s}  targets")


def row(r):
    def f(v, spec):
        width = int(spec.lstrip("+").split(".")[0].rstrip("df"))
        if v is None:
            return "-".rjust(width)
        if isinstance(v, float) and abs(v) >= 10 ** (width - 4):  # a degenerate cell's edge ratio
            return format(v, f"{width}.1e")
        return format(v, spec)
    c = r.get("cells", {})
    flags = " ".join(k if r["targets"][k] else "-" * len(k) for k in TARGETS[:-1])
    miss = "" if r["targets"]["all"] else "  <- " + reason(r)[:120]
    return (f"{r['part'][:28]:28s} {r['method']:8s} {r['status']:7s} {r.get('path') or '-':8s} {f(c.get('hex'), '7d')} {f(c.get('prism'), '6d')} "
            f"{f(c.get('tet'), '6d')} {f(r.get('inverted'), '4d')} {f(r.get('hex_sj_min'), '7.3f')} "
            f"{f(None if r.get('volume_error') is None else 100 * r['volume_error'], '+8.2f')} "
            f"{f(r.get('edge_ratio_max'), '7.2f')} {r['time']:7.2f}  {flags}{miss}")


def totals(runs):
    n = len(runs)
    if not n:
        return None
    times = [r["time"] for r in runs]
    slow = max(runs, key=lambda r: r["time"])
    out = {"parts": n}
    for k in TARGETS:
        m = sum(r["targets"][k] for r in runs)
        out[k] = m
        out[k + "_pct"] = 100.0 * m / n
    out.update({"time_median": statistics.median(times), "time_max": slow["time"], "time_max_part": slow["part"],
                "over_10s": sum(t >= TIME_MAX for t in times), "timeouts": sum(r["status"] == "timeout" for r in runs)})
    return out


def print_totals(all_totals, methods):
    names = {"meshed": "meshed", "inv": "0 inverted", "SJ": "SJ>=0.3", "vol": "vol 1%", "ER": "ER<=10",
             "time": "<10 s", "all": "all"}
    print()
    print(f"{'group':14s} {'method':8s} {'parts':>5s} " + " ".join(f"{names[k]:>10s}" for k in TARGETS)
          + f" {'median s':>9s} {'max s':>7s} {'>10 s':>5s}  slowest")
    for group, per_method in all_totals.items():
        for m in methods:
            t = per_method.get(m)
            if not t:
                continue
            print(f"{group:14s} {m:8s} {t['parts']:5d} "
                  + " ".join(f"{t[k + '_pct']:9.1f}%" for k in TARGETS)
                  + f" {t['time_median']:9.2f} {t['time_max']:7.2f} {t['over_10s']:5d}  {t['time_max_part']}")


ER_BUCKETS = (2, 5, 10, 20, 50, 100)


def print_edge_ratios(runs, methods):
    """The distribution of the largest edge ratio per part (issue "element size that FEM users can
    steer": <= 10 on >= 95% of the parts at default settings)."""
    heads = [f"<={b}" for b in ER_BUCKETS] + [f">{ER_BUCKETS[-1]}", "no mesh"]
    print("\nlargest edge ratio per part: " + " ".join(f"{h:>7s}" for h in heads))
    for m in methods:
        ers = [r.get("edge_ratio_max") for r in runs if r["method"] == m]
        counts, lo = [], 0
        for b in ER_BUCKETS:
            counts.append(sum(e is not None and lo < e <= b for e in ers))
            lo = b
        counts += [sum(e is not None and e > ER_BUCKETS[-1] for e in ers), sum(e is None for e in ers)]
        print(f"{m:28s} " + " ".join(f"{c:7d}" for c in counts) + f"   ({len(ers)} parts)")


def print_crossing(runs, methods):
    """How much of the boundary crosses a CAD edge (faces FreeCAD's face loads leave out), per part."""
    heads = ["0", "<=1%", "<=5%", "<=10%", ">10%"]
    print("\nboundary area crossing a CAD edge per part: " + " ".join(f"{h:>6s}" for h in heads))
    for m in methods:
        xs = [r.get("crossing") for r in runs if r["method"] == m and r.get("crossing") is not None]
        counts = [sum(x == 0 for x in xs), sum(0 < x <= 0.01 for x in xs), sum(0.01 < x <= 0.05 for x in xs),
                  sum(0.05 < x <= 0.1 for x in xs), sum(x > 0.1 for x in xs)]
        mean = sum(xs) / len(xs) if xs else 0.0
        print(f"{m:28s} " + " ".join(f"{c:6d}" for c in counts) + f"   ({len(xs)} snapped parts, mean {mean:.2%})")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("corpus", nargs="?", help="folder with manifest.json and the STEP files (make_corpus.py)")
    ap.add_argument("--extra", action="append", default=[], help="also every .step/.stp of this folder (repeatable)")
    ap.add_argument("--surface", action="append", default=[],
                    help="also this closed triangle surface (.k, .stl, .obj, .vtk; repeatable), e.g. a paper raw model")
    ap.add_argument("--hexdom", help="the hexdom program (default $HEXDOM_BUILD_DIR/bin/hexdom)")
    ap.add_argument("--methods", default="auto,polycube,overlay")
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds per run (default 60)")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--parts", help="only the parts whose name matches this glob (e.g. 'flange_*')")
    ap.add_argument("--limit", type=int, help="N corpus parts spread evenly over the sorted names")
    ap.add_argument("--json", help="write every run and the totals to this file")
    ap.add_argument("--arg", action="append", default=[],
                    help="one more argument for every `hexdom mesh` run (repeatable), e.g. --arg=--polycube-seconds --arg=5")
    args = ap.parse_args(argv)
    if not args.corpus and not args.extra and not args.surface:
        ap.error("give a corpus folder, --extra folders or --surface files")
    for path in args.surface:
        if not os.path.isfile(path):
            ap.error(f"--surface {path}: no such file")
    hexdom = os.path.abspath(args.hexdom or default_hexdom())
    if not (os.path.isfile(hexdom) and os.access(hexdom, os.X_OK)):
        sys.exit(f"bench_corpus: no hexdom program at {hexdom} (--hexdom or HEXDOM_BUILD_DIR)")
    methods = [m.strip() for m in args.methods.split(",") if m.strip()]
    use_method = has_method_option(hexdom)
    note = None
    if not use_method:
        note = (f"{hexdom} mesh has no --method option: each part runs once without it, "
                f"labelled 'polycube' (asked for: {', '.join(methods)})")
        methods = ["polycube"]
        print("note: " + note)
    parts = collect(args.corpus, args.extra, args.parts, args.limit, args.surface)
    jobs = [(p, m) for p in parts for m in methods]
    print(f"{len(parts)} parts x {len(methods)} method(s) = {len(jobs)} runs, timeout {args.timeout:g} s, "
          f"{args.jobs} at a time, {hexdom}")
    print(HEADER, flush=True)
    lock = threading.Lock()
    runs = []
    t_all = time.perf_counter()

    def save(totals_=None):
        if not args.json:
            return
        tmp = args.json + ".tmp"
        with open(tmp, "w") as f:
            json.dump({"hexdom": hexdom, "methods": methods, "method_option": use_method, "note": note,
                       "timeout": args.timeout, "jobs": args.jobs, "complete": totals_ is not None,
                       "targets": {"sj_min": SJ_MIN, "volume_tolerance": VOLUME_TOL,
                                   "edge_ratio_max": EDGE_RATIO_MAX, "time_max": TIME_MAX},
                       "parts": parts, "runs": runs, "totals": totals_}, f, indent=1)
        os.replace(tmp, args.json)

    def one(job):
        r = run_one(hexdom, job[0], job[1], use_method, args.timeout, args.arg)
        with lock:
            runs.append(r)
            print(row(r), flush=True)
            save()  # so far: an interrupted bench keeps its runs
        return r

    if args.jobs > 1:
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            list(pool.map(one, jobs))
    else:
        for job in jobs:
            one(job)
    order = {(p["name"], p["group"]): i for i, p in enumerate(parts)}
    runs.sort(key=lambda r: (order[(r["part"], r["group"])], methods.index(r["method"])))

    groups = {"corpus": [r for r in runs if r["group"] == "corpus"],
              "extra": [r for r in runs if r["group"] == "extra"]}
    if groups["corpus"] and groups["extra"]:
        groups["corpus+extra"] = runs
    all_totals = {g: {m: totals([r for r in rs if r["method"] == m]) for m in methods}
                  for g, rs in groups.items() if rs}
    save(all_totals)
    print_totals(all_totals, methods)
    print_edge_ratios(runs, methods)
    print_crossing(runs, methods)
    misses = [r for r in runs if not r["targets"]["all"]]
    print(f"\n{len(misses)} of {len(runs)} runs miss a target:")
    for r in misses:
        print(f"  {r['part']:28s} {r['method']:8s} {reason(r)[:160]}")
    slowest = sorted(runs, key=lambda r: -r["time"])[:10]
    print("\nslowest runs: " + ", ".join(f"{r['part']} ({r['method']}) {r['time']:.1f} s" for r in slowest))
    print(f"total wall time {time.perf_counter() - t_all:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
