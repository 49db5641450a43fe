"""Cancel latency: how soon `hexdom mesh` stops after Ctrl-C, wherever it is.

Per part, `hexdom mesh PART -o OUT --allow-inverted [--method M]` is started --repeat times per
delay; SIGINT is sent after each delay (seconds from the start), and the time from the signal to the
program's exit is measured. A run that ends before its signal is counted as "finished". Prints per
part and delay the stage named in the message ("stopped (overlay: interrupted)") and the latency;
then the median and the largest latency over all runs, and whether every interrupted run exited 130
with no output file (the contract: common/interrupt.h, src/cli/main.cpp). The workbench's Cancel
goes through the same checks (HexDomWorkbench/progress.py); the target there is 0.2 s.

Run:  /usr/bin/python3 bench/bench_cancel.py PART [PART ...] [--hexdom PATH] [--method auto]
          [--delays 0.5,1,2,4,8] [--repeat 1]
e.g.  bench/bench_cancel.py examples/data/bracket.step /tmp/corpus/shell_revolved_001.step
Prints, never asserts.
"""

import argparse
import os
import re
import signal
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def default_hexdom():
    build = os.environ.get("HEXDOM_BUILD_DIR", os.path.join(ROOT, "build"))
    return os.path.join(build, "bin", "hexdom")


def one(hexdom, part, method, delay, tmp):
    out = os.path.join(tmp, "out.vtu")
    if os.path.exists(out):
        os.remove(out)
    err_path = os.path.join(tmp, "err.txt")
    with open(err_path, "w") as err:
        p = subprocess.Popen([hexdom, "mesh", part, "-o", out, "--allow-inverted", "--method", method],
                             stdout=subprocess.DEVNULL, stderr=err)
        start = time.perf_counter()
        while p.poll() is None and time.perf_counter() - start < delay:
            time.sleep(0.002)
        if p.poll() is not None:
            return {"finished": True, "seconds": time.perf_counter() - start}
        sent = time.perf_counter()
        p.send_signal(signal.SIGINT)
        p.wait()
        latency = time.perf_counter() - sent
    text = open(err_path).read()
    m = re.search(r"stopped \((.*?): interrupted\)", text)
    clean = p.returncode == 130 and not os.path.exists(out) and not [f for f in os.listdir(tmp) if ".tmp-" in f]
    return {"finished": False, "latency": latency, "stage": m.group(1) if m else "?", "clean": clean,
            "exit": p.returncode}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("parts", nargs="+")
    ap.add_argument("--hexdom", default=default_hexdom())
    ap.add_argument("--method", default="auto")
    ap.add_argument("--delays", default="0.5,1,2,4,8")
    ap.add_argument("--repeat", type=int, default=1)
    a = ap.parse_args()
    delays = [float(x) for x in a.delays.split(",")]
    latencies, unclean = [], 0
    with tempfile.TemporaryDirectory() as tmp:
        for part in a.parts:
            name = os.path.splitext(os.path.basename(part))[0]
            for delay in delays:
                for _ in range(a.repeat):
                    r = one(a.hexdom, part, a.method, delay, tmp)
                    if r["finished"]:
                        print(f"{name:28s} signal at {delay:5.2f} s: finished before it ({r['seconds']:.2f} s)")
                        continue
                    latencies.append(r["latency"])
                    unclean += not r["clean"]
                    print(f"{name:28s} signal at {delay:5.2f} s: stopped in {r['stage']:32s} "
                          f"{1000 * r['latency']:7.1f} ms  exit {r['exit']}{'' if r['clean'] else '  NOT CLEAN'}")
    if latencies:
        print(f"\n{len(latencies)} interrupted runs: latency median {1000 * statistics.median(latencies):.1f} ms, "
              f"max {1000 * max(latencies):.1f} ms; {unclean} not clean (exit other than 130, or a file left)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
