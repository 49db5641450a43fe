"""`hexdom mesh` against Gmsh's all-hex subdivision, whole process each, on the same parts.

Per part, both programs are run --repeat times, alternating (hexdom, gmsh, hexdom, gmsh, ...), and
the median wall time of each is kept:
  hexdom  `hexdom mesh PART -o OUT.vtu --allow-inverted --size H --threads T` (the auto method)
  gmsh    `gmsh PART -3 -nt T -setnumber Mesh.SubdivisionAlgorithm 2 -setnumber Mesh.MeshSizeMax G
           -o OUT.msh` (tetrahedra of size G, each split into four hexahedra: the all-hex mesh
           FreeCAD users can make today)
H is the part's bounding-box diagonal / 30 (hexdom's default size, taken in the model's axes here so
that both get the same number); G = --gmsh-scale x H (1: the same size, as the speed issue asks; the
subdivided hexahedra are then about H / 2 across, so Gmsh makes more cells: both counts are printed,
and --gmsh-scale 2 compares meshes of about the same cell size). Prints per part both times, the
ratio hexdom / gmsh and both cell counts; then the median ratio, the parts above 3 and the parts
above 10 s. Gmsh's failures and timeouts are printed as such.

Run:  /usr/bin/python3 bench/bench_vs_gmsh.py [PART ...] [--corpus DIR --limit 20]
          [--cad ../shared/data/cad] [--repeat 3] [--threads 2] [--gmsh-scale 1] [--timeout 300]
e.g.  bench/bench_vs_gmsh.py --cad ../shared/data/cad --corpus /tmp/corpus --limit 20
(corpus parts: /usr/bin/python3 bench/make_corpus.py /tmp/corpus; Gmsh: apt-get install gmsh).
Prints, never asserts.
"""

import argparse
import glob
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def default_hexdom():
    build = os.environ.get("HEXDOM_BUILD_DIR", os.path.join(ROOT, "build"))
    return os.path.join(build, "bin", "hexdom")


def diagonal(part):
    """The bounding-box diagonal of the first solid, by OpenCASCADE through Gmsh's Python module when
    it is there, else by FreeCAD."""
    try:
        import gmsh
        gmsh.initialize(["-noenv"])
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.occ.importShapes(part)
        gmsh.model.occ.synchronize()
        x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(-1, -1)
        gmsh.finalize()
        return ((x1 - x0) ** 2 + (y1 - y0) ** 2 + (z1 - z0) ** 2) ** 0.5
    except ImportError:
        for p in ("/usr/lib/freecad-python3/lib", "/usr/lib/freecad/lib"):
            if p not in sys.path:
                sys.path.append(p)
        import Part  # noqa: E402 (FreeCAD)
        shape = Part.read(part)
        solid = shape.Solids[0] if shape.Solids else shape
        return solid.BoundBox.DiagonalLength


def timed(cmd, timeout):
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, f"timeout after {timeout:g} s", ""
    dt = time.perf_counter() - t0
    if p.returncode != 0:
        lines = [line for line in (p.stderr + p.stdout).splitlines() if line.strip()]
        return None, lines[-1][:120] if lines else f"exit {p.returncode}", ""
    return dt, None, p.stdout + p.stderr


def hexdom_cells(text):
    n = 0
    for kind in ("hex", "prism", "tet"):
        m = re.search(rf"^{kind}\s+(\d+)", text, re.M)
        n += int(m.group(1)) if m else 0
    return n


def gmsh_cells(path):
    try:
        import meshio
        return sum(len(b.data) for b in meshio.read(path).cells if b.type in ("hexahedron", "tetra", "wedge", "pyramid"))
    except Exception:  # noqa: BLE001 (a count only)
        return -1


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("parts", nargs="*")
    ap.add_argument("--cad", action="append", default=[], help="every .step/.stp of this folder")
    ap.add_argument("--corpus", help="a make_corpus.py folder")
    ap.add_argument("--limit", type=int, default=20, help="corpus parts, spread evenly over the sorted names")
    ap.add_argument("--hexdom", default=default_hexdom())
    ap.add_argument("--gmsh", default=shutil.which("gmsh") or "gmsh")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--gmsh-scale", type=float, default=1.0)
    ap.add_argument("--timeout", type=float, default=300)
    a = ap.parse_args()
    if not shutil.which(a.gmsh) and not os.access(a.gmsh, os.X_OK):
        sys.exit("bench_vs_gmsh: no gmsh program (apt-get install gmsh)")
    parts = list(a.parts)
    for folder in a.cad:
        parts += sorted(glob.glob(os.path.join(folder, "*.step")) + glob.glob(os.path.join(folder, "*.stp")))
    if a.corpus:
        names = sorted(glob.glob(os.path.join(a.corpus, "*.step")))
        if a.limit and len(names) > a.limit:
            names = [names[round(i * (len(names) - 1) / (a.limit - 1))] for i in range(a.limit)]
        parts += names
    if not parts:
        sys.exit("bench_vs_gmsh: no parts (give files, --cad or --corpus)")
    print(f"{'part':24s} {'size':>8s} {'hexdom s':>9s} {'gmsh s':>8s} {'ratio':>6s} {'hexdom cells':>12s} "
          f"{'gmsh cells':>10s}", flush=True)
    ratios, above3, slow = [], [], []
    with tempfile.TemporaryDirectory(prefix="bench_vs_gmsh_") as tmp:
        for part in parts:
            name = os.path.splitext(os.path.basename(part))[0]
            h = diagonal(part) / 30.0
            hx_out, gm_out = os.path.join(tmp, "h.vtu"), os.path.join(tmp, "g.msh")
            hx_cmd = [a.hexdom, "mesh", part, "-o", hx_out, "--allow-inverted", "--size", f"{h:.6g}",
                      "--threads", str(a.threads)]
            gm_cmd = [a.gmsh, part, "-3", "-nt", str(a.threads), "-setnumber", "Mesh.SubdivisionAlgorithm", "2",
                      "-setnumber", "Mesh.MeshSizeMax", f"{a.gmsh_scale * h:.6g}", "-o", gm_out]
            th, tg, errors, hx_n, gm_n = [], [], [], 0, 0
            for _ in range(a.repeat):
                dt, err, text = timed(hx_cmd, a.timeout)
                if err:
                    errors.append("hexdom: " + err)
                else:
                    th.append(dt)
                    hx_n = hexdom_cells(text)
                dt, err, _ = timed(gm_cmd, a.timeout)
                if err:
                    errors.append("gmsh: " + err)
                else:
                    tg.append(dt)
                    gm_n = gmsh_cells(gm_out)
            mh = statistics.median(th) if th else float("nan")
            mg = statistics.median(tg) if tg else float("nan")
            ratio = mh / mg if th and tg else float("nan")
            if th and tg:
                ratios.append(ratio)
                if ratio > 3:
                    above3.append(f"{name} {ratio:.1f}")
            if th and mh > 10:
                slow.append(f"{name} {mh:.1f} s")
            note = ("  " + "; ".join(sorted(set(errors)))) if errors else ""
            print(f"{name:24s} {h:8.3g} {mh:9.2f} {mg:8.2f} {ratio:6.2f} {hx_n:12d} {gm_n:10d}{note}", flush=True)
    if ratios:
        print(f"\n{len(ratios)} parts timed by both: median ratio hexdom / gmsh {statistics.median(ratios):.2f} "
              f"(target <= 1), above 3: {len(above3)} {above3}; hexdom above 10 s: {len(slow)} {slow}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
