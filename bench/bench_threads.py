"""The optimisers' threads: `hexdom mesh` on 1 and on N threads, time and whether the output files are
the same byte for byte (they must be: the nodes move colour by colour, optimize/improver.h).

Per part and method (overlay, polycube, auto), the runs alternate (1 thread, N threads, 1, N, ...)
--repeat times; prints the median wall time of each, the ratio, and "same" when every output file
of the part is identical to the first one, else "DIFFERENT" (a defect). Then the median ratio and
the totals. Under auto the two paths already run beside each other on two threads, so the gain of
the optimiser's threads is smaller there than for one path alone.

Run:  /usr/bin/python3 bench/bench_threads.py PART.step [PART ...] [--hexdom PATH] [--threads 2]
          [--methods overlay,polycube,auto] [--repeat 1] [--timeout 300]
e.g.  bench/bench_threads.py /tmp/corpus/sweep_002.step ../shared/data/cad/*.step
(corpus parts: /usr/bin/python3 bench/make_corpus.py /tmp/corpus). Prints, never asserts.
"""

import argparse
import filecmp
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def default_hexdom():
    build = os.environ.get("HEXDOM_BUILD_DIR", os.path.join(ROOT, "build"))
    return os.path.join(build, "bin", "hexdom")


def run(hexdom, part, method, threads, out, timeout):
    cmd = [hexdom, "mesh", part, "-o", out, "--allow-inverted", "--method", method, "--threads", str(threads)]
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, f"timeout after {timeout:g} s"
    dt = time.perf_counter() - t0
    if p.returncode != 0 or not os.path.exists(out):
        lines = [l for l in p.stderr.splitlines() if l.strip()]
        return None, lines[-1] if lines else f"exit {p.returncode}"
    return dt, None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("parts", nargs="+", help="CAD parts or closed surfaces")
    ap.add_argument("--hexdom", default=default_hexdom())
    ap.add_argument("--threads", type=int, default=2, help="the thread count compared with 1")
    ap.add_argument("--methods", default="overlay,polycube,auto")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=300)
    args = ap.parse_args()
    if not os.access(args.hexdom, os.X_OK):
        sys.exit(f"bench_threads: no hexdom program at {args.hexdom}")
    methods = [m for m in args.methods.split(",") if m]
    print(f"{'part':28s} {'method':8s} {'1 thread s':>10s} {f'{args.threads} threads s':>11s} {'ratio':>6s}  output")
    ratios, totals = [], [0.0, 0.0]
    for part in args.parts:
        name = os.path.splitext(os.path.basename(part))[0]
        for method in methods:
            with tempfile.TemporaryDirectory(prefix="bench_threads_") as tmp:
                times = {1: [], args.threads: []}
                outs, error = [], None
                for k in range(args.repeat):
                    for n in (1, args.threads):
                        out = os.path.join(tmp, f"m_{n}_{k}.vtu")
                        dt, error = run(args.hexdom, part, method, n, out, args.timeout)
                        if error:
                            break
                        times[n].append(dt)
                        outs.append(out)
                    if error:
                        break
                if error:
                    print(f"{name:28s} {method:8s} no mesh: {error}")
                    continue
                same = all(filecmp.cmp(outs[0], o, shallow=False) for o in outs[1:])
                t1, tn = statistics.median(times[1]), statistics.median(times[args.threads])
                ratios.append(tn / t1)
                totals[0] += t1
                totals[1] += tn
                print(f"{name:28s} {method:8s} {t1:10.2f} {tn:11.2f} {tn / t1:6.2f}  {'same' if same else 'DIFFERENT'}",
                      flush=True)
    if ratios:
        print(f"\n{len(ratios)} runs: median ratio {statistics.median(ratios):.2f}, "
              f"total {totals[0]:.1f} s on 1 thread, {totals[1]:.1f} s on {args.threads}")


if __name__ == "__main__":
    main()
