"""Writes a corpus of our own CAD parts as STEP files, made with FreeCAD's Part (OpenCASCADE), for
the benches that judge a change on many parts (bench_same_results.py --corpus DIR, and the
every-solid pass rates to come). Simple and mechanical shapes in the sizes engineers draw: blocks,
plates with holes, brackets, round stock, tubes, cones and pyramids, fillets and chamfers, parts
turned off the model's axes. None comes from a public dataset.

Run: /usr/bin/python3 bench/make_corpus.py OUT_DIR    (prints one line per part)
"""

import math
import os
import sys

for p in ("/usr/lib/freecad-python3/lib", "/usr/share/freecad/Mod", "/usr/share/freecad/Ext"):
    if p not in sys.path:
        sys.path.append(p)

import FreeCAD  # noqa: E402
import Part  # noqa: E402

V = FreeCAD.Vector


def turned(shape, angle, axis):
    s = shape.copy()
    s.rotate(V(0, 0, 0), V(*axis), angle)
    return s


def parts():
    box = Part.makeBox(60, 40, 20)
    plate = Part.makeBox(100, 60, 8)
    for x, y in ((20, 15), (80, 15), (20, 45), (80, 45)):
        plate = plate.cut(Part.makeCylinder(4, 8, V(x, y, 0)))
    l_bracket = Part.makeBox(60, 40, 8).fuse(Part.makeBox(8, 40, 50)).removeSplitter()
    l_holed = l_bracket.cut(Part.makeCylinder(5, 8, V(35, 20, 0))).cut(
        Part.makeCylinder(5, 8, V(0, 20, 30), V(1, 0, 0)))
    t_block = Part.makeBox(80, 20, 20).fuse(Part.makeBox(20, 20, 60, V(30, 0, 0))).removeSplitter()
    u_channel = Part.makeBox(60, 40, 30).cut(Part.makeBox(60, 24, 22, V(0, 8, 8)))
    stepped = Part.makeBox(90, 40, 10).fuse(Part.makeBox(60, 40, 10, V(0, 0, 10))).fuse(
        Part.makeBox(30, 40, 10, V(0, 0, 20))).removeSplitter()
    tube = Part.makeCylinder(20, 60).cut(Part.makeCylinder(12, 60))
    shaft = Part.makeCylinder(10, 40).fuse(Part.makeCylinder(16, 20, V(0, 0, 40))).removeSplitter()
    filleted = Part.makeBox(50, 40, 30)
    filleted = filleted.makeFillet(5, [e for e in filleted.Edges if abs(e.Vertexes[0].Point.z - e.Vertexes[1].Point.z) > 1])
    chamfered = Part.makeBox(50, 40, 30)
    chamfered = chamfered.makeChamfer(4, [e for e in chamfered.Edges if abs(e.Vertexes[0].Point.z - 30) < 1e-9
                                          and abs(e.Vertexes[1].Point.z - 30) < 1e-9])
    flange = Part.makeCylinder(40, 10).fuse(Part.makeCylinder(20, 30)).removeSplitter()
    for k in range(4):
        a = k * math.pi / 2
        flange = flange.cut(Part.makeCylinder(4, 10, V(30 * math.cos(a), 30 * math.sin(a), 0)))
    base = Part.Face(Part.makePolygon([V(0, 0, 0), V(40, 0, 0), V(40, 40, 0), V(0, 40, 0), V(0, 0, 0)]))
    sides = [Part.Face(Part.makePolygon([a, b, V(20, 20, 30), a]))
             for a, b in [(V(0, 0, 0), V(40, 0, 0)), (V(40, 0, 0), V(40, 40, 0)), (V(40, 40, 0), V(0, 40, 0)),
                          (V(0, 40, 0), V(0, 0, 0))]]
    return {
        "block": box,
        "plate_4_holes": plate,
        "l_bracket": l_bracket,
        "l_bracket_holes": l_holed,
        "t_block": t_block,
        "u_channel": u_channel,
        "stepped_block": stepped,
        "tube": tube,
        "stepped_shaft": shaft,
        "block_filleted": filleted,
        "block_chamfered": chamfered,
        "flange": flange,
        "cone": Part.makeCone(25, 0, 40),
        "pyramid": Part.Solid(Part.Shell([base] + sides)),
        "sphere": Part.makeSphere(20),
        "l_bracket_turned_45z": turned(l_holed, 45, (0, 0, 1)),
        "u_channel_turned_30": turned(u_channel, 30, (1, 2, 3)),
    }


def main(out):
    os.makedirs(out, exist_ok=True)
    for name, shape in parts().items():
        if not shape.isValid() or len(shape.Solids) != 1:
            print(f"{name}: not one valid solid, skipped")
            continue
        path = os.path.join(out, name + ".step")
        shape.exportStep(path)
        print(f"{name}: {len(shape.Faces)} faces, volume {shape.Volume:.1f} -> {path}")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
