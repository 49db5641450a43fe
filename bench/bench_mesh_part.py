"""Mesh Part through the workbench's document objects: for the shipped STEP bracket and each shared
CAD part, the time each object takes to recompute (Surface = tessellate, Segmentation = segment,
Polycube = automatic polycube, Mesh = generate + improve [+ snap]), cells, worst / mean hex scaled
Jacobian, inverted cells and the volume against OpenCASCADE's. Prints, never asserts.

Run: HEXDOM_BUILD_DIR=build HEXDOM_BENCH_ARGS="[names...]" freecadcmd bench/bench_mesh_part.py
(freecadcmd passes no arguments to scripts). Names are part stems (bracket, s09o_bridge, ...);
default: all.
"""

import glob
import os
import sys
import time
import traceback

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.environ.get("HEXDOM_DATA", os.path.join(ROOT, "..", "shared", "data"))
sys.path.insert(0, ROOT)


def parts():
    found = {"bracket": os.path.join(ROOT, "examples", "data", "bracket.step")}
    for path in sorted(glob.glob(os.path.join(DATA, "cad", "*.st*p"))):
        found[os.path.splitext(os.path.basename(path))[0]] = path
    return found


def bench(name, path):
    import FreeCAD
    import Part

    from HexDomWorkbench import api
    doc = FreeCAD.newDocument("Bench")
    try:
        part = doc.addObject("Part::Feature", name)
        part.Shape = Part.read(path)
        doc.recompute()
        objs = api.make_mesh_part(doc, part, level=1)
        seconds = {}
        for key in ("surface", "segmentation", "polycube", "mesh"):
            t = time.perf_counter()
            objs[key].recompute()
            seconds[key] = time.perf_counter() - t
            state = objs[key].State
            if "Invalid" in state or "Error" in state:
                return "{:<28} failed at {}: {}".format(name, key, objs[key].getStatusString())
        m = objs["mesh"]
        volume = sum(s.Volume for s in part.Shape.Solids)  # a STEP compound may repeat it
        return ("{:<28} {:6.2f} {:6.2f} {:6.2f} {:7.2f}  {:6d} {:5d} {:5d}  {:6.3f} {:6.3f} {:4d}"
                "  {:+7.3f}%".format(
                    name, seconds["surface"], seconds["segmentation"], seconds["polycube"],
                    seconds["mesh"], m.HexCount, m.PrismCount, m.TetCount, m.MinHexSJ,
                    m.MeanHexSJ, m.InvertedCount, 100.0 * (m.MeshVolume - volume) / volume))
    except Exception as e:  # a bench reports and goes on
        traceback.print_exc()
        return "{:<28} error: {}".format(name, e)
    finally:
        FreeCAD.closeDocument(doc.Name)


def main(names):
    found = parts()
    names = names or list(found)
    print("{:<28} {:>6} {:>6} {:>6} {:>7}  {:>6} {:>5} {:>5}  {:>6} {:>6} {:>4}  {:>8}".format(
        "part", "tess", "segm", "poly", "mesh", "hex", "prism", "tet", "minSJ", "meanSJ", "inv",
        "volume"))
    for name in names:
        if name not in found:
            print("{:<28} not found".format(name))
            continue
        print(bench(name, found[name]))
        sys.stdout.flush()
    return 0


sys.exit(main(os.environ.get("HEXDOM_BENCH_ARGS", "").split()))
