"""Makes examples/data/bracket.step, the CAD part `make demo` meshes with no manual step: an
L-shaped angle bracket (base plate 60 x 40 x 10 mm, upright 10 x 40 x 50 mm) with a through hole
of diameter 12 mm in the base plate and a 6 mm fillet along the inside corner.

Run:  freecadcmd examples/make_bracket_step.py [output.step] [variant]
(FreeCAD's Part module writes the STEP file; freecadcmd passes no arguments of its own to the
script, so they are read from HEXDOM_BRACKET_ARGS when given there.) Variants: "full" (default:
hole and fillet), "hole", "fillet", "plain".
"""

import os
import sys


def bracket(variant="full"):
    import FreeCAD
    import Part
    V = FreeCAD.Vector
    base = Part.makeBox(60, 40, 10)
    upright = Part.makeBox(10, 40, 50)
    shape = base.fuse(upright).removeSplitter()
    if variant in ("full", "fillet"):
        # The inside corner edge: along y at x = 10, z = 10.
        edges = [e for e in shape.Edges
                 if abs(e.BoundBox.XMin - 10) < 1e-9 and abs(e.BoundBox.XMax - 10) < 1e-9
                 and abs(e.BoundBox.ZMin - 10) < 1e-9 and abs(e.BoundBox.ZMax - 10) < 1e-9]
        if len(edges) != 1:
            raise RuntimeError("inside corner edge not found ({} candidates)".format(len(edges)))
        shape = shape.makeFillet(6.0, edges)
    if variant in ("full", "hole"):
        hole = Part.makeCylinder(6.0, 10.0, V(40, 20, 0), V(0, 0, 1))
        shape = shape.cut(hole).removeSplitter()
    solid = shape.Solids[0] if shape.ShapeType != "Solid" else shape
    if not solid.isValid() or abs(solid.Volume) < 1e-9:
        raise RuntimeError("the bracket is not a valid solid")
    return solid


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    out = argv[0] if argv else os.path.join(here, "data", "bracket.step")
    variant = argv[1] if len(argv) > 1 else "full"
    solid = bracket(variant)
    solid.exportStep(out)
    print("wrote {} ({} faces, volume {:.6g} mm^3)".format(out, len(solid.Faces), solid.Volume))
    return 0


if __name__ in ("__main__", "make_bracket_step"):
    _args = os.environ.get("HEXDOM_BRACKET_ARGS", "").split()
    sys.exit(main(_args))
