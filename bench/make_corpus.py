"""Writes a corpus of our own CAD parts as STEP files, made with FreeCAD's Part (OpenCASCADE), for
the benches that judge a change on many parts (bench/bench_corpus.py, bench_same_results.py
--corpus DIR). None comes from a public dataset: every part is built here.

Two kinds of parts:
  * 17 hand-written parts with fixed names (block, plate_4_holes, l_bracket, ..., u_channel_turned_30)
    that bench_same_results.py compares before and after a change; always written (--no-fixed to
    leave them out);
  * --count parametric parts (default 200) drawn from 20 seeded families of the parts FEM users mesh:
    plates with holes, slots and pockets; L, T and U brackets with fillets and chamfers; bosses, ribs,
    counterbores and drilled holes; flanges and shafts (revolved, grooves, shoulders, keyseats);
    thin-walled boxes and shells; lofts and sweeps; parts placed at an angle; and hard ones (tangent
    cylinders and planes, acute wedges, small features beside large ones, cones). Part k goes to
    family k mod 20 (so a small --count still spans the families), as <family>_<index:03d>;
    in a family with sub-kinds (loft: rect_circle, twisted, ...), part i is of sub-kind i mod their
    number, so that 10 parts per family show every sub-kind.

Reproducible: each parametric part draws its dimensions (mm) from random.Random seeded with the
string "hexdom-corpus:<seed>:<family>:<index>", so a name is the same part for a given --seed
whatever --count is. Every part written is one valid closed solid (isValid, one solid with one
closed shell, volume > 0) whose STEP file reloads with the same volume (relative 1e-6); a draw that
fails to build or to pass these checks is replaced by the next draw of the same generator (at most
--attempts draws, then the script stops with an error: no part is silently dropped).

Writes OUT_DIR/<name>.step and OUT_DIR/manifest.json: {"seed", "count", "families", "parts": {name:
{family, volume (FreeCAD's shape.Volume, mm^3), diagonal (bounding box, mm), both to 12 significant
digits, faces, seed, draws, params}}}.

Run: /usr/bin/python3 bench/make_corpus.py OUT_DIR [--seed 19] [--count 200] [--families a,b]
                                                   [--no-fixed] [--attempts 40]
(prints one line per part and the total; 217 parts take about a minute)
"""

import argparse
import json
import math
import os
import random
import sys
import tempfile
import time

for p in ("/usr/lib/freecad-python3/lib", "/usr/share/freecad/Mod", "/usr/share/freecad/Ext"):
    if p not in sys.path:
        sys.path.append(p)

import FreeCAD  # noqa: E402
import Part  # noqa: E402

V = FreeCAD.Vector
DEFAULT_SEED = 19  # issue 19, "Every closed solid meshes"
DEFAULT_COUNT = 200


def turned(shape, angle, axis):
    s = shape.copy()
    s.rotate(V(0, 0, 0), V(*axis), angle)
    return s


# ---- the 17 hand-written parts (names used by bench_same_results.py: keep them) -----------------

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


# ---- drawing dimensions --------------------------------------------------------------------------

class Draw:
    """The random draws of one part: dimensions rounded as a designer would, each recorded by name
    (the manifest's params) so that a failing part can be rebuilt by hand."""

    def __init__(self, rng, index=0, cycle=True):
        self.r = rng
        self.params = {}
        self.index = index
        self.cycle = cycle

    def kind(self, name, options):
        """The sub-kind of a family: part `index` takes options[index mod len(options)], so that
        every kind appears once the family has as many parts; a random one after failed draws."""
        if self.cycle:
            return self._keep(name, options[self.index % len(options)])
        return self.pick(name, options)

    def _keep(self, name, v):
        if name:
            self.params[name] = v
        return v

    def mm(self, name, a, b, step=0.5):
        """Uniform in [a, b], rounded to `step` (and kept inside [a, b])."""
        v = round(self.r.uniform(a, b) / step) * step
        v = min(max(v, math.ceil(a / step - 1e-9) * step), math.floor(b / step + 1e-9) * step)
        return self._keep(name, round(v, 6))

    def real(self, name, a, b):
        return self._keep(name, round(self.r.uniform(a, b), 4))

    def int(self, name, a, b):
        return self._keep(name, self.r.randint(a, b))

    def pick(self, name, options):
        return self._keep(name, self.r.choice(options))

    def chance(self, name, p):
        return self._keep(name, self.r.random() < p)


# ---- geometry helpers ----------------------------------------------------------------------------

def fuse(*shapes):
    s = shapes[0]
    for t in shapes[1:]:
        s = s.fuse(t)
    return s.removeSplitter()


def cut(shape, *tools):
    s = shape
    for t in tools:
        s = s.cut(t)
    return s.removeSplitter()


def polygon_face(points):
    pts = [V(*p) for p in points]
    return Part.Face(Part.makePolygon(pts + [pts[0]]))


def prism_xz(points, y0, width):
    """A polygon drawn in the XZ plane (points (x, z)), extruded from y = y0 over `width` along +Y."""
    face = polygon_face([(x, y0, z) for x, z in points])
    return face.extrude(V(0, width, 0))


def revolve_rz(points):
    """A solid of revolution about Z: the polygon (r, z) in the XZ plane turned a full turn."""
    return polygon_face([(r, 0, z) for r, z in points]).revolve(V(0, 0, 0), V(0, 0, 1), 360)


def is_line(e):
    return e.Curve.TypeId == "Part::GeomLine"


def is_circle(e):
    return e.Curve.TypeId == "Part::GeomCircle"


def mid(e):
    return e.valueAt(0.5 * (e.FirstParameter + e.LastParameter))


def along(e, axis):
    """A straight edge parallel to axis 0/1/2."""
    if not is_line(e):
        return False
    d = e.Vertexes[1].Point - e.Vertexes[0].Point
    c = [abs(d.x), abs(d.y), abs(d.z)]
    return c[axis] > 1e-6 and sum(c) - c[axis] < 1e-6 * c[axis]


def near(a, b, tol=1e-4):
    return abs(a - b) < tol


def select(shape, keep):
    edges = [e for e in shape.Edges if keep(e)]
    if not edges:
        raise ValueError("no edge to fillet or chamfer")
    return edges


def fillet(shape, r, keep):
    return shape.makeFillet(r, select(shape, keep))


def chamfer(shape, d, keep):
    return shape.makeChamfer(d, select(shape, keep))


def rounded_box(L, W, H, r, at=(0, 0, 0)):
    """Box whose four vertical edges are rounded with radius r (none when r <= 0)."""
    b = Part.makeBox(L, W, H, V(*at))
    if r > 0:
        b = fillet(b, r, lambda e: along(e, 2))
    return b


def stadium(c, w, h):
    """Obround prism (slot tool): centres c apart along X, width w along Y, z in [0, h], centred at 0."""
    if c <= 0:
        return Part.makeCylinder(w / 2, h)
    return fuse(Part.makeBox(c, w, h, V(-c / 2, -w / 2, 0)),
                Part.makeCylinder(w / 2, h, V(-c / 2, 0, 0)), Part.makeCylinder(w / 2, h, V(c / 2, 0, 0)))


def placed(shape, x=0, y=0, z=0, angle=0, axis=(0, 0, 1)):
    s = shape.copy()
    if angle:
        s.rotate(V(0, 0, 0), V(*axis), angle)
    s.translate(V(x, y, z))
    return s


def zhole(r, x, y, z0, h):
    return Part.makeCylinder(r, h, V(x, y, z0))


def drilled(r, depth, x, y, top):
    """A blind drilled hole from z = top down `depth`, with the 118 degree drill point below."""
    tip = r / math.tan(math.radians(59))
    return fuse(Part.makeCylinder(r, depth, V(x, y, top - depth)),
                Part.makeCone(0, r, tip, V(x, y, top - depth - tip)))


def grid(n, lo, hi):
    """n positions evenly spread over [lo, hi] (its middle when n == 1)."""
    if n == 1:
        return [0.5 * (lo + hi)]
    return [lo + (hi - lo) * i / (n - 1) for i in range(n)]


def circle_wire(r, center=(0, 0, 0), normal=(0, 0, 1)):
    return Part.Wire(Part.makeCircle(r, V(*center), V(*normal)))


def rect_wire(w, h, z, cx=0, cy=0, angle=0):
    pts = []
    for x, y in ((-w / 2, -h / 2), (w / 2, -h / 2), (w / 2, h / 2), (-w / 2, h / 2)):
        c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
        pts.append(V(cx + c * x - s * y, cy + s * x + c * y, z))
    return Part.makePolygon(pts + [pts[0]])


# ---- the families --------------------------------------------------------------------------------
# Each builder takes a Draw and returns a shape. Dimensions in mm.

def plate_holes(d):
    L = d.mm("L", 60, 260)
    W = d.mm("W", 40, min(170, L))
    T = d.mm("T", 3, 20)
    r = d.mm("hole_d", 3, min(22, 0.25 * W)) / 2
    margin = max(2.5 * r, 6)
    nx = d.int("nx", 1, max(1, min(5, int((L - 2 * margin) // (4 * r + 4)) + 1)))
    ny = d.int("ny", 1, max(1, min(3, int((W - 2 * margin) // (4 * r + 4)) + 1)))
    plate = rounded_box(L, W, T, d.mm("corner_r", 1, min(15, margin)) if d.chance("rounded", 0.6) else 0)
    holes = [zhole(r, x, y, 0, T) for x in grid(nx, margin, L - margin) for y in grid(ny, margin, W - margin)]
    if nx % 2 == 0 and ny % 2 == 0 and d.chance("centre_hole", 0.5):  # between the four middle holes
        px, py = (L - 2 * margin) / (nx - 1), (W - 2 * margin) / (ny - 1)
        room = 0.5 * math.hypot(px, py) - r - 4
        if room > 2:
            holes.append(zhole(d.mm("centre_d", 4, max(4, 2 * room)) / 2, L / 2, W / 2, 0, T))
    return cut(plate, *holes)


def plate_slots(d):
    L, W = d.mm("L", 80, 260), d.mm("W", 50, 160)
    T = d.mm("T", 3, 16)
    plate = rounded_box(L, W, T, d.mm("corner_r", 2, 12) if d.chance("rounded", 0.5) else 0)
    n = d.int("n", 1, 4)
    w = d.mm("slot_w", 4, min(18, 0.2 * W))
    lanes = grid(n, 0.12 * L + w, 0.88 * L - w)
    pitch = (lanes[1] - lanes[0]) if n > 1 else L
    tools = []
    vertical = d.chance("across", 0.5)
    for k, x in enumerate(lanes):
        if vertical:  # slots along Y, side by side along X
            c = d.mm(f"slot{k}_c", 0, 0.55 * W - w)
            tools.append(placed(stadium(c, w, T), x, W / 2, 0, 90))
        else:  # slots along X in one row: each fits its lane
            c = d.mm(f"slot{k}_c", 0, max(0, min(0.5 * L, pitch - 2 * w - 4)))
            tools.append(placed(stadium(c, w, T), x, W / 2, 0))
    if d.chance("angled_slot", 0.3):
        # one more slot near a corner, at 45 degrees
        c = d.mm("angled_c", 4, 0.2 * min(L, W))
        tools.append(placed(stadium(c, w, T), 0.5 * w + 0.08 * L + c / 2, 0.5 * w + 0.1 * W + c / 2, 0, 45))
    return cut(plate, *tools)


def plate_pockets(d):
    L, W = d.mm("L", 70, 240), d.mm("W", 50, 160)
    T = d.mm("T", 8, 30)
    plate = Part.makeBox(L, W, T)
    n = d.int("n", 1, 3)
    wall = d.mm("wall", 3, 10)
    depth = d.mm("depth", 0.3 * T, 0.75 * T)
    cell = (L - (n + 1) * wall) / n
    tools = []
    for k in range(n):
        pl = d.mm(f"pocket{k}_l", 0.5 * cell, cell)
        pw = d.mm(f"pocket{k}_w", 0.4 * (W - 2 * wall), W - 2 * wall)
        pr = d.mm(f"pocket{k}_r", 1, min(12, 0.45 * min(pl, pw))) if d.chance(f"pocket{k}_round", 0.7) else 0
        x0 = wall + k * (cell + wall) + (cell - pl) / 2
        tools.append(rounded_box(pl, pw, depth + 1, pr, (x0, (W - pw) / 2, T - depth)))
        if d.chance(f"pocket{k}_hole", 0.4):
            tools.append(zhole(d.mm(f"pocket{k}_hole_d", 3, min(12, 0.4 * min(pl, pw))) / 2, x0 + pl / 2, W / 2, 0, T))
    return cut(plate, *tools)


def bracket_l(d):
    A, B = d.mm("A", 30, 130), d.mm("B", 30, 130)
    W = d.mm("W", 20, 90)
    t = d.mm("t", 3, min(15, 0.2 * min(A, B)))
    s = fuse(Part.makeBox(A, W, t), Part.makeBox(t, W, B))
    ri = d.mm("inner_r", 0.5 * t, 1.5 * t) if d.chance("inner_fillet", 0.8) else 0
    if ri:
        s = fillet(s, ri, lambda e: along(e, 1) and near(mid(e).x, t) and near(mid(e).z, t))
        if d.chance("outer_fillet", 0.6):  # bent sheet: constant thickness round the bend
            s = fillet(s, ri + t, lambda e: along(e, 1) and near(mid(e).x, 0) and near(mid(e).z, 0))
    if d.chance("chamfer_ends", 0.5):
        c = d.mm("chamfer", 0.5, 0.5 * t)
        s = chamfer(s, c, lambda e: along(e, 1) and ((near(mid(e).x, A) and near(mid(e).z, t))
                                                    or (near(mid(e).z, B) and near(mid(e).x, t))))
    holes = []
    r = d.mm("hole_d", 3, min(16, 0.4 * W)) / 2
    n = d.int("holes_per_leg", 0, 2)
    x_lo = t + ri + r + 3
    if n and A - r - 4 > x_lo:
        for x in grid(1, x_lo, A - r - 4):
            for y in grid(n, W / 2 if n == 1 else r + 4, W - r - 4 if n > 1 else W / 2):
                holes.append(zhole(r, x, y, 0, t))
    if n and B - r - 4 > x_lo:
        for z in grid(1, x_lo, B - r - 4):
            for y in grid(n, W / 2 if n == 1 else r + 4, W - r - 4 if n > 1 else W / 2):
                holes.append(Part.makeCylinder(r, t, V(0, y, z), V(1, 0, 0)))
    return cut(s, *holes) if holes else s


def bracket_t(d):
    L, W = d.mm("L", 50, 200), d.mm("W", 20, 90)
    t1 = d.mm("flange_t", 3, 16)
    t2 = d.mm("web_t", 3, 16)
    H = d.mm("H", max(20, 2 * t1), 120)
    x0 = L / 2 - t2 / 2
    s = fuse(Part.makeBox(L, W, t1), Part.makeBox(t2, W, H, V(x0, 0, 0)))
    rf = d.mm("fillet", 0.5, min(1.5 * t2, 0.25 * (L - t2), 0.5 * H)) if d.chance("fillets", 0.8) else 0
    if rf:
        s = fillet(s, rf, lambda e: along(e, 1) and near(mid(e).z, t1)
                   and (near(mid(e).x, x0) or near(mid(e).x, x0 + t2)))
    if d.chance("web_chamfer", 0.4):
        s = chamfer(s, d.mm("chamfer", 0.5, 0.4 * t2), lambda e: along(e, 1) and near(mid(e).z, H))
    holes = []
    r = d.mm("hole_d", 3, min(14, 0.4 * W)) / 2
    room = (L - t2) / 2 - rf
    if room > 2 * r + 8 and d.chance("flange_holes", 0.8):
        xc = (x0 - rf) / 2  # the middle of the flange beside the fillet
        for x in (xc, L - xc):
            holes.append(zhole(r, x, W / 2, 0, t1))
    if H - t1 - rf > 2 * r + 8 and d.chance("web_hole", 0.5):
        holes.append(Part.makeCylinder(r, t2, V(x0, W / 2, (t1 + rf + H) / 2), V(1, 0, 0)))
    return cut(s, *holes) if holes else s


def bracket_u(d):
    L, W = d.mm("L", 30, 150), d.mm("W", 20, 90)
    t = d.mm("t", 3, min(14, 0.2 * L))
    H = d.mm("H", 20, 120)
    s = fuse(Part.makeBox(L, W, t), Part.makeBox(t, W, H), Part.makeBox(t, W, H, V(L - t, 0, 0)))
    ri = d.mm("inner_r", 0.5, min(1.5 * t, 0.3 * (L - 2 * t))) if d.chance("inner_fillet", 0.8) else 0
    if ri:
        s = fillet(s, ri, lambda e: along(e, 1) and near(mid(e).z, t)
                   and (near(mid(e).x, t) or near(mid(e).x, L - t)))
    if d.chance("round_tops", 0.4):
        s = fillet(s, d.mm("top_r", 0.5, 0.45 * t), lambda e: along(e, 1) and near(mid(e).z, H))
    holes = []
    r = d.mm("pin_d", 3, min(20, 0.5 * W, 0.5 * (H - t - ri))) / 2
    if d.chance("pin_hole", 0.8):  # coaxial clevis holes through both legs
        holes.append(Part.makeCylinder(r, L, V(0, W / 2, H - max(1.5 * r, r + 4)), V(1, 0, 0)))
    rb = d.mm("base_hole_d", 3, max(3, min(14, 0.3 * (L - 2 * t - 2 * ri)))) / 2
    if L - 2 * t - 2 * ri > 2 * rb + 6 and d.chance("base_hole", 0.6):
        holes.append(zhole(rb, L / 2, W / 2, 0, t))
    return cut(s, *holes) if holes else s


def boss_plate(d):
    L, W = d.mm("L", 60, 220), d.mm("W", 40, 160)
    T = d.mm("T", 4, 16)
    n = d.int("n", 1, 4)
    rb = d.mm("boss_d", 8, min(36, 0.4 * W, 0.8 * L / n)) / 2
    hb = d.mm("boss_h", 4, 35)
    rh = d.mm("hole_d", 2, max(2, 2 * rb - 5)) / 2
    rf = d.mm("base_fillet", 0.5, min(4, 0.4 * hb, 0.5 * rb)) if d.chance("base_fillet", 0.6) else 0
    margin = rb + rf + 3
    xs = grid(n, margin, L - margin)
    y = d.mm("boss_y", margin, max(margin, W - margin))
    s = fuse(Part.makeBox(L, W, T), *[Part.makeCylinder(rb, hb, V(x, y, T)) for x in xs])
    if rf:
        s = fillet(s, rf, lambda e: is_circle(e) and near(e.Curve.Center.z, T) and near(e.Curve.Radius, rb))
    through = d.chance("through", 0.6)
    depth = T + hb if through else d.mm("hole_depth", 0.4 * hb, hb)
    holes = [zhole(rh, x, y, T + hb - depth, depth) for x in xs]
    return cut(s, *holes)


def ribbed(d):
    kind = d.kind("kind", ["gusset", "plate_ribs", "waffle"])
    if kind == "gusset":
        A, B, W = d.mm("A", 40, 140), d.mm("B", 40, 140), d.mm("W", 30, 120)
        t = d.mm("t", 4, min(14, 0.15 * min(A, B)))
        g = d.mm("gusset", 0.4 * min(A, B), 0.85 * min(A, B) - t)
        tg = d.mm("gusset_t", 2, min(t, 0.25 * W))
        n = d.int("n", 1, 3) if W > 3 * tg + 10 else 1
        ribs = [prism_xz([(t, t), (t + g, t), (t, t + g)], y - tg / 2, tg)
                for y in grid(n, tg / 2 + (0 if n == 1 else 2), W - tg / 2 - (0 if n == 1 else 2))]
        return fuse(Part.makeBox(A, W, t), Part.makeBox(t, W, B), *ribs)
    L, W = d.mm("L", 80, 240), d.mm("W", 60, 180)
    T = d.mm("T", 3, 12)
    h = d.mm("rib_h", 5, 40)
    tr = d.mm("rib_t", 1.5, 8)
    nx = d.int("nx", 2, 6)
    inset = 0 if d.chance("edge_ribs", 0.3) else d.mm("inset", 5, 0.15 * min(L, W))  # outer ribs flush or inset
    ribs = [Part.makeBox(tr, W, h, V(x - tr / 2, 0, T)) for x in grid(nx, inset + tr / 2, L - inset - tr / 2)]
    if kind == "waffle":
        ny = d.int("ny", 2, 5)
        ribs += [Part.makeBox(L, tr, h, V(0, y - tr / 2, T)) for y in grid(ny, inset + tr / 2, W - inset - tr / 2)]
    s = fuse(Part.makeBox(L, W, T), *ribs)
    if d.chance("rib_chamfer", 0.3):
        s = chamfer(s, d.mm("chamfer", 0.3, 0.4 * tr), lambda e: is_line(e) and near(mid(e).z, T + h)
                    and (along(e, 0) or along(e, 1)) and 0 < mid(e).x < L and 0 < mid(e).y < W)
    return s


def counterbore(d):
    L, W = d.mm("L", 40, 200), d.mm("W", 30, 140)
    H = d.mm("H", 10, 50)
    s = Part.makeBox(L, W, H)
    r = d.mm("hole_d", 3, min(16, 0.12 * W)) / 2
    R = d.mm("bore_d", 2 * r + 3, min(3.2 * r, 2 * r + 16)) / 2
    pitch = 2 * R + d.mm("gap", 4, 20)  # the closest the holes may be
    m = R + d.mm("edge", 3, 15)  # a hole's centre to the block's side
    nx = max(1, min(5, int((L - 2 * m) // pitch) + 1))
    ny = max(1, min(3, int((W - 2 * m) // pitch) + 1))
    nx, ny = d.int("nx", 1, nx), d.int("ny", 1, ny)
    tools = []
    for i, x in enumerate(grid(nx, m, L - m)):
        for j, y in enumerate(grid(ny, m, W - m)):
            kind = d.pick(f"hole{i}{j}", ["counterbore", "countersink", "spotface", "drilled"])
            if kind == "counterbore":
                dep = d.mm(f"hole{i}{j}_depth", 1, 0.5 * H)
                tools += [zhole(r, x, y, 0, H), zhole(R, x, y, H - dep, dep)]
            elif kind == "countersink":  # 90 degree countersink
                tools += [zhole(r, x, y, 0, H), Part.makeCone(r, R, R - r, V(x, y, H - (R - r)))]
            elif kind == "spotface":
                tools += [zhole(r, x, y, 0, H), zhole(R, x, y, H - d.mm(f"hole{i}{j}_depth", 0.5, 1.5), 2)]
            else:
                tools.append(drilled(r, d.mm(f"hole{i}{j}_depth", 2 * r, 0.7 * H), x, y, H))
    if d.chance("side_hole", 0.3):
        tools.append(Part.makeCylinder(d.mm("side_d", 3, min(10, 0.3 * H)) / 2, L, V(0, W / 2 + 0.5 * r, H / 2), V(1, 0, 0)))
    return cut(s, *tools)


def flange(d):
    rb = d.mm("bore_d", 8, 80) / 2
    rh = d.mm("hub_d", 2 * rb + 8, 2 * rb + 40) / 2
    rd = d.mm("disc_d", 2 * rh + 30, 2 * rh + 120) / 2
    td = d.mm("disc_t", 6, 30)
    hh = d.mm("hub_h", 4, 60)
    pts = [(rb, 0), (rd, 0), (rd, td), (rh, td), (rh, td + hh), (rb, td + hh)]
    if d.chance("raised_face", 0.4):
        rf = d.mm("raised_d", 2 * rh, 2 * rh + 0.5 * (rd - rh)) / 2
        hr = d.mm("raised_h", 1, 4)
        pts = [(rb, -hr), (rf, -hr), (rf, 0)] + pts[1:]
    s = revolve_rz(pts)
    if d.chance("hub_fillet", 0.6):
        s = fillet(s, d.mm("hub_r", 1, min(10, 0.5 * hh, 0.3 * (rd - rh))),
                   lambda e: is_circle(e) and near(e.Curve.Center.z, td) and near(e.Curve.Radius, rh))
    if d.chance("chamfer", 0.5):
        s = chamfer(s, d.mm("chamfer_c", 0.5, min(3, 0.4 * (rh - rb))),
                    lambda e: is_circle(e) and near(e.Curve.Center.z, td + hh) and near(e.Curve.Radius, rh))
    n = d.pick("bolts", [3, 4, 6, 8, 12])
    rbolt = d.mm("bolt_d", 4, min(24, 0.35 * (rd - rh))) / 2
    pcd = d.mm("pcd", 2 * (rh + rbolt + 3) + 6, 2 * (rd - rbolt - 3)) / 2
    if 2 * pcd * math.sin(math.pi / n) < 2 * rbolt + 3:
        raise ValueError("bolt holes overlap")
    holes = [Part.makeCylinder(rbolt, td + 10, V(pcd * math.cos(2 * math.pi * k / n), pcd * math.sin(2 * math.pi * k / n), -5))
             for k in range(n)]
    return cut(s, *holes)


def shaft(d):
    n = d.int("sections", 2, 5)
    radii, lengths = [], []
    for k in range(n):  # shoulders: each diameter within 0.55..1.8 times the previous one
        lo, hi = (8, 60) if k == 0 else (max(8, 1.1 * radii[-1]), min(60, 3.6 * radii[-1]))
        radii.append(d.mm(f"d{k}", lo, hi) / 2)
        lengths.append(d.mm(f"l{k}", 8, 90))
    c = d.mm("end_chamfer", 0.5, 0.3 * min(radii[0], radii[-1], 3)) if d.chance("chamfers", 0.7) else 0
    pts = [(0, 0)]
    pts += [(radii[0] - c, 0), (radii[0], c)] if c else [(radii[0], 0)]
    z = 0.0
    grooves = []
    for k in range(n):
        z0, z1 = z, z + lengths[k]
        r = radii[k]
        if lengths[k] > 12 and d.chance(f"groove{k}", 0.4):  # retaining-ring groove
            gw, gd = d.mm(f"groove{k}_w", 1, 3, 0.1), d.mm(f"groove{k}_depth", 0.4, min(2.5, 0.15 * r), 0.1)
            gz = d.mm(f"groove{k}_z", z0 + 4, z1 - 4 - gw)
            pts += [(r, gz), (r - gd, gz), (r - gd, gz + gw), (r, gz + gw)]
            grooves.append(k)
        if k + 1 < n and abs(radii[k + 1] - r) >= 1e-9:  # a shoulder; equal diameters run on
            pts += [(r, z1), (radii[k + 1], z1)]
        z = z1
    total = z
    pts += [(radii[-1], total - c), (radii[-1] - c, total)] if c else [(radii[-1], total)]
    pts.append((0, total))
    clean = [pts[0]]
    for p in pts[1:]:
        if abs(p[0] - clean[-1][0]) > 1e-9 or abs(p[1] - clean[-1][1]) > 1e-9:
            clean.append(p)
    s = revolve_rz(clean)
    tools = []
    k = d.int("key_section", 0, n - 1)
    if lengths[k] > 20 and radii[k] >= 6 and d.chance("keyseat", 0.5):
        zk = sum(lengths[:k])
        w = d.mm("key_w", 2, 0.5 * radii[k])
        kl = d.mm("key_l", w + 2, lengths[k] - 6)
        depth = d.mm("key_depth", 1, 0.3 * radii[k], 0.1)
        tool = placed(stadium(kl - w, w, depth + 5), 0, 0, 0, 90, (0, 1, 0))
        tool.translate(V(radii[k] - depth, 0, zk + lengths[k] / 2))
        tools.append(tool)
    if d.chance("centre_hole", 0.3):
        rc = d.mm("centre_hole_d", 2, 0.5 * radii[0]) / 2
        tools.append(drilled(rc, d.mm("centre_hole_depth", 2 * rc, min(3 * rc + 5, lengths[0])), 0, 0, 0).mirror(V(0, 0, 0), V(0, 0, 1)))
    if d.chance("cross_hole", 0.3):
        k = d.int("cross_section", 0, n - 1)
        rx = d.mm("cross_d", 2, max(2, 0.6 * radii[k])) / 2
        zx = sum(lengths[:k]) + lengths[k] / 2
        tools.append(Part.makeCylinder(rx, 2 * radii[k] + 10, V(-radii[k] - 5, 0, zx), V(1, 0, 0)))
    return cut(s, *tools) if tools else s


def box_thin(d):
    L, W, H = d.mm("L", 40, 220), d.mm("W", 30, 160), d.mm("H", 20, 100)
    t = d.mm("wall", 1, 4, 0.25)
    tb = d.mm("bottom", t, 2 * t, 0.25)
    ro = d.mm("corner_r", t + 1, min(20, 0.2 * min(L, W))) if d.chance("rounded", 0.6) else 0
    mode = d.pick("mode", ["cut", "thickness"])
    if mode == "thickness" and ro:
        outer = rounded_box(L, W, H, ro)
        top = [f for f in outer.Faces if near(f.CenterOfMass.z, H) and abs(f.normalAt(0, 0).z - 1) < 1e-6]
        s = outer.makeThickness(top, -t, 1e-3)
    else:
        outer = rounded_box(L, W, H, ro)
        inner = rounded_box(L - 2 * t, W - 2 * t, H - tb + 1, ro - t if ro else 0, (t, t, tb))
        s = outer.cut(inner)
    parts = [s]
    n = d.int("dividers", 0, 3) if L > 60 else 0
    for x in grid(n, L / (n + 1), L - L / (n + 1)) if n else []:
        parts.append(Part.makeBox(t, W - 2 * t, d.mm("divider_h", 0.4 * H, H - tb), V(x - t / 2, t, tb)))
    if d.chance("lip", 0.3):  # a flange round the top
        lw = d.mm("lip_w", 2, 10)
        lip = rounded_box(L + 2 * lw, W + 2 * lw, t, ro + lw if ro else 0, (-lw, -lw, H - t))
        lip = lip.cut(rounded_box(L - 2 * t, W - 2 * t, t, ro - t if ro else 0, (t, t, H - t)))
        parts.append(lip)
    s = fuse(*parts) if len(parts) > 1 else s.removeSplitter()
    if d.chance("bottom_holes", 0.4):
        r = d.mm("hole_d", 2, 8) / 2
        s = cut(s, *[zhole(r, x, W / 2, 0, tb) for x in grid(2, max(ro, 3 * r) + t + 2, L - max(ro, 3 * r) - t - 2)])
    return s


def shell_revolved(d):
    kind = d.kind("kind", ["cup", "dome", "funnel", "thickness"])
    t = d.mm("wall", 1, 5, 0.25)
    if kind == "cup":
        R, H = d.mm("R", 15, 100), d.mm("H", 15, 150)
        tb = d.mm("bottom", t, 3 * t, 0.25)
        pts = [(0, 0), (R, 0), (R, H), (R - t, H), (R - t, tb), (0, tb)]
        if d.chance("rim", 0.4):
            rw = d.mm("rim_w", 2, 12)
            pts = [(0, 0), (R, 0), (R, H - t), (R + rw, H - t), (R + rw, H), (R - t, H), (R - t, tb), (0, tb)]
        return revolve_rz(pts)
    if kind == "dome":
        R = d.mm("R", 20, 120)
        cap = d.real("cap", 0.2, 0.95)  # height of the cap over R
        z0 = R * (1 - 2 * cap)
        s = Part.makeSphere(R).cut(Part.makeSphere(R - t)).common(Part.makeBox(4 * R, 4 * R, 2 * R, V(-2 * R, -2 * R, z0)))
        if d.chance("base_ring", 0.5):
            rr = math.sqrt(max(R * R - z0 * z0, 1))
            rw = d.mm("ring_w", 2, 15)
            ring = Part.makeCylinder(rr + rw, t, V(0, 0, z0)).cut(Part.makeCylinder(max(rr - t - 0.5, 1), t, V(0, 0, z0)))
            s = s.fuse(ring)
        return s.removeSplitter()
    if kind == "funnel":
        r1, r2, H = d.mm("r1", 5, 40), d.mm("r2", 20, 100), d.mm("H", 15, 120)
        return revolve_rz([(r1, 0), (r1 + t, 0), (r2 + t, H), (r2, H)])
    # thickness: a filleted or plain solid hollowed by OpenCASCADE's offset, one face open
    base = d.pick("base", ["cylinder", "box"])
    if base == "cylinder":
        R, H = d.mm("R", 15, 80), d.mm("H", 15, 120)
        s = Part.makeCylinder(R, H)
        if d.chance("bottom_fillet", 0.6):
            s = fillet(s, d.mm("fillet_r", 2, 0.5 * min(R, H)), lambda e: is_circle(e) and near(e.Curve.Center.z, 0))
    else:
        L, W, H = d.mm("L", 30, 160), d.mm("W", 25, 120), d.mm("H", 15, 80)
        s = Part.makeBox(L, W, H)
        s = fillet(s, d.mm("fillet_r", t + 1, 0.3 * min(L, W, H)),
                   lambda e: is_line(e) and not (near(mid(e).z, H) and not along(e, 2)))
    top = [f for f in s.Faces if near(f.CenterOfMass.z, s.BoundBox.ZMax) and f.Surface.TypeId == "Part::GeomPlane"]
    return s.makeThickness(top, -t, 1e-3)


def loft(d):
    kind = d.kind("kind", ["rect_circle", "twisted", "eccentric", "three", "duct"])
    H = d.mm("H", 20, 160)
    if kind == "rect_circle" or kind == "duct":
        a, b = d.mm("a", 20, 120), d.mm("b", 15, 100)
        r = d.mm("r", 8, 0.6 * max(a, b))
        w1, w2 = rect_wire(a, b, 0), circle_wire(r, (0, 0, H))
        s = Part.makeLoft([w1, w2], True, d.chance("ruled", 0.3))
        if kind == "duct":
            t = d.mm("wall", 1.5, min(5, 0.1 * min(a, b, 2 * r)), 0.25)
            # inner passage a little longer than the duct so that the ends are open
            wi1 = rect_wire(a - 2 * t, b - 2 * t, -1)
            wi2 = circle_wire(r - t, (0, 0, H + 1))
            s = s.cut(Part.makeLoft([wi1, wi2], True, False))
        return s
    if kind == "twisted":
        a, b = d.mm("a", 20, 100), d.mm("b", 10, 80)
        ang = d.mm("twist", 10, 60, 1)
        sc = d.real("scale", 0.4, 1.0)
        return Part.makeLoft([rect_wire(a, b, 0), rect_wire(a * sc, b * sc, H, 0, 0, ang)], True, d.chance("ruled", 0.5))
    if kind == "eccentric":
        r1, r2 = d.mm("r1", 10, 60), d.mm("r2", 5, 50)
        off = d.mm("offset", 0, 0.8 * max(r1, r2))
        return Part.makeLoft([circle_wire(r1), circle_wire(r2, (off, 0, H))], True, False)
    a, b = d.mm("a", 30, 120), d.mm("b", 20, 100)
    r = d.mm("r", 6, 0.4 * min(a, b))
    sc = d.real("mid_scale", 0.5, 1.3)
    return Part.makeLoft([rect_wire(a, b, 0), rect_wire(a * sc, b * sc, H / 2, 0, 0, d.mm("mid_angle", 0, 30, 1)),
                          circle_wire(r, (d.mm("top_dx", -10, 10), 0, H))], True, False)


def sweep(d):
    kind = d.kind("kind", ["elbow", "s_bend", "helix", "tube_elbow", "rect_elbow"])
    if kind == "helix":
        R = d.mm("R", 8, 60)
        r = d.mm("wire_d", 2, min(16, 0.6 * R)) / 2
        pitch = d.mm("pitch", 2 * r + 2, 2 * r + 30)
        turns = d.real("turns", 0.75, 3.0)
        path = Part.Wire(Part.makeHelix(pitch, pitch * turns, R))
        e = path.Edges[0]
        p0, tan = e.valueAt(e.FirstParameter), e.tangentAt(e.FirstParameter)
        prof = Part.Wire(Part.makeCircle(r, p0, tan))
        return path.makePipeShell([prof], True, True)
    Rb = d.mm("bend_r", 15, 120)
    L1, L2 = d.mm("L1", 0, 120), d.mm("L2", 0, 120)
    ang = d.mm("angle", 30, 150, 5) if kind != "s_bend" else d.mm("angle", 20, 90, 5)
    edges = []
    p = V(0, 0, 0)
    if L1 > 0:
        edges.append(Part.LineSegment(p, V(0, 0, L1)).toShape())
        p = V(0, 0, L1)
    # arc in the XZ plane, centred at (Rb, 0, p.z), from p turning towards +X
    a = math.radians(ang)
    c = V(Rb, 0, p.z)
    def on_arc(t, centre, sign):
        return V(centre.x - sign * Rb * math.cos(t), 0, centre.z + Rb * math.sin(t))
    edges.append(Part.Arc(p, on_arc(a / 2, c, 1), on_arc(a, c, 1)).toShape())
    end, tangent = on_arc(a, c, 1), V(math.sin(a), 0, math.cos(a))
    if kind == "s_bend":  # the same bend back: the first arc turned half a turn about its end
        start = p
        edges.append(Part.Arc(end, end * 2 - on_arc(a / 2, c, 1), end * 2 - start).toShape())
        end, tangent = end * 2 - start, V(0, 0, 1)
    if L2 > 0:
        edges.append(Part.LineSegment(end, end + tangent * L2).toShape())
    path = Part.Wire(edges)
    if kind in ("elbow", "s_bend"):
        r = d.mm("bar_d", 6, min(60, 1.4 * Rb)) / 2
        return path.makePipeShell([circle_wire(r)], True, True)
    if kind == "rect_elbow":
        w, h = d.mm("bar_w", 5, min(60, 1.4 * Rb)), d.mm("bar_h", 5, 60)
        return path.makePipeShell([rect_wire(w, h, 0)], True, True)
    ro = d.mm("tube_d", 8, min(80, 1.4 * Rb)) / 2
    ri = ro - d.mm("tube_wall", 1, min(6, 0.3 * ro), 0.25)
    return path.makePipeShell([circle_wire(ro), ], True, True).cut(path.makePipeShell([circle_wire(ri)], True, True))


ANGLED_BASES = ["plate_holes", "bracket_l", "bracket_u", "boss_plate", "counterbore", "shaft", "flange", "plate_slots"]


def angled(d):
    base = d.kind("base", ANGLED_BASES)
    s = FAMILIES[base](d)
    axis = [d.real(f"axis_{c}", -1, 1) for c in "xyz"]
    if sum(a * a for a in axis) < 0.05:
        axis = [1, 1, 1]
    ang = d.mm("angle", 7, 83, 1)
    if ang % 45 == 0:
        ang += 7
    s = s.copy()
    s.rotate(V(0, 0, 0), V(*axis), ang)
    s.translate(V(d.mm("dx", -200, 200), d.mm("dy", -200, 200), d.mm("dz", -200, 200)))
    return s


def tangent(d):
    """Cylinders tangent to planes or to each other: smooth joins the feature-edge logic does not see."""
    kind = d.kind("kind", ["link", "tee", "stadium_bar", "boss_flush"])
    if kind == "link":  # two bosses joined by a web tangent to both: a connecting rod / lever
        R1, R2 = d.mm("R1", 8, 40), d.mm("R2", 5, 35)
        D = d.mm("centres", R1 + R2 + 10, R1 + R2 + 160)
        T = d.mm("T", 4, 25)
        th = math.acos((R1 - R2) / D)
        pa, pb = V(R1 * math.cos(th), R1 * math.sin(th), 0), V(D + R2 * math.cos(th), R2 * math.sin(th), 0)
        qa, qb = V(pa.x, -pa.y, 0), V(pb.x, -pb.y, 0)
        w = Part.Wire([Part.Arc(qa, V(-R1, 0, 0), pa).toShape(), Part.LineSegment(pa, pb).toShape(),
                       Part.Arc(pb, V(D + R2, 0, 0), qb).toShape(), Part.LineSegment(qb, qa).toShape()])
        s = Part.Face(w).extrude(V(0, 0, T))
        holes = [zhole(d.mm("hole1_d", 3, 2 * R1 - 4) / 2, 0, 0, 0, T), zhole(d.mm("hole2_d", 2, 2 * R2 - 3) / 2, D, 0, 0, T)]
        return cut(s, *holes)
    if kind == "tee":  # two cylinders of the same radius crossing: their surfaces touch tangentially
        R = d.mm("R", 5, 40)
        L, H = d.mm("L", 4 * R, 10 * R), d.mm("H", 2 * R, 8 * R)
        s = fuse(Part.makeCylinder(R, L, V(-L / 2, 0, 0), V(1, 0, 0)), Part.makeCylinder(R, H, V(0, 0, 0)))
        if d.chance("bore", 0.5):
            t = d.mm("wall", 1, 0.35 * R)
            s = cut(s, Part.makeCylinder(R - t, L, V(-L / 2, 0, 0), V(1, 0, 0)), Part.makeCylinder(R - t, H, V(0, 0, 0)))
        return s
    if kind == "stadium_bar":  # full round ends: half cylinders tangent to the flat sides
        L, w, T = d.mm("L", 30, 200), d.mm("W", 6, 60), d.mm("T", 3, 30)
        s = stadium(L - w, w, T)
        if d.chance("slot", 0.5):
            ws = d.mm("slot_w", 2, w - 3)
            s = cut(s, stadium(d.mm("slot_c", 0, L - w - 4), ws, T))
        return s
    # boss_flush: a cylinder on a block whose side touches the block's side plane along a line
    L, W, H = d.mm("L", 30, 160), d.mm("W", 30, 120), d.mm("H", 5, 40)
    R = d.mm("R", 4, 0.45 * min(L, W))
    h = d.mm("boss_h", 3, 60)
    x = d.mm("x", R, L - R)
    s = fuse(Part.makeBox(L, W, H), Part.makeCylinder(R, h, V(x, R, H)))
    if d.chance("hole", 0.5):
        s = cut(s, zhole(d.mm("hole_d", 2, 2 * R - 3) / 2, x, R, 0, H + h))
    return s


def acute_wedge(d):
    kind = d.kind("kind", ["triangle", "blade", "wedge", "dovetail"])
    if kind == "triangle":
        L, W = d.mm("L", 20, 150), d.mm("W", 10, 100)
        a = d.mm("apex_deg", 5, 35, 1)
        return prism_xz([(0, 0), (L, 0), (L, L * math.tan(math.radians(a)))], 0, W)
    if kind == "blade":
        L, T, W = d.mm("L", 30, 200), d.mm("T", 2, 15), d.mm("W", 10, 80)
        s_ = d.mm("bevel", 2 * T, 8 * T)
        return prism_xz([(0, 0), (L + s_, 0), (L, T), (0, T)], 0, W)
    if kind == "wedge":  # a frustum whose top face is a sliver
        L, Wd, H = d.mm("L", 20, 120), d.mm("W", 20, 120), d.mm("H", 15, 100)
        e = d.mm("top", 0.5, 0.2 * L)
        xc = d.mm("top_x", 0, L - e)
        return Part.makeWedge(0, 0, 0, 0, xc, L, H, Wd, Wd, xc + e)
    L, W, H = d.mm("L", 40, 200), d.mm("W", 40, 150), d.mm("H", 15, 60)
    a = d.mm("dovetail_deg", 45, 70, 1)
    dep = d.mm("depth", 0.25 * H, 0.6 * H)
    top = d.mm("opening", 8, 0.5 * W)
    bot = top + 2 * dep / math.tan(math.radians(a))
    if bot > W - 6:
        raise ValueError("dovetail wider than the block")
    yc = W / 2
    tool = Part.Face(Part.makePolygon([V(-1, yc - top / 2, H), V(-1, yc + top / 2, H), V(-1, yc + bot / 2, H - dep),
                                       V(-1, yc - bot / 2, H - dep), V(-1, yc - top / 2, H)])).extrude(V(L + 2, 0, 0))
    return cut(Part.makeBox(L, W, H), tool)


def small_features(d):
    """A large part with features 100 times smaller: tiny holes, a thin step, a small boss."""
    L, W, T = d.mm("L", 150, 400), d.mm("W", 100, 300), d.mm("T", 8, 40)
    s = Part.makeBox(L, W, T)
    feats = []
    if d.chance("tiny_holes", 0.7):
        r = d.mm("tiny_d", 1, 3, 0.1) / 2
        feats += [zhole(r, x, 0.2 * W, 0, T) for x in grid(d.int("tiny_n", 1, 4), 0.1 * L, 0.4 * L)]
    tools = list(feats)
    adds = []
    if d.chance("thin_step", 0.6):
        h = d.mm("step_h", 0.2, 1.5, 0.1)
        tools.append(Part.makeBox(0.3 * L, W, h + 1, V(0.7 * L, 0, T - h)))
    if d.chance("small_boss", 0.6):
        adds.append(Part.makeCylinder(d.mm("boss_d", 2, 6, 0.5) / 2, d.mm("boss_h", 1, 5, 0.5), V(0.5 * L, 0.7 * W, T)))
    if d.chance("narrow_slot", 0.5):
        tools.append(placed(stadium(d.mm("slot_l", 5, 30), d.mm("slot_w", 1, 2.5, 0.1), d.mm("slot_depth", 0.5, 3) + 1),
                            0.3 * L, 0.6 * W, T - d.params["slot_depth"]))
    if not tools and not adds:
        tools.append(zhole(1, 0.5 * L, 0.5 * W, 0, T))
    if adds:
        s = fuse(s, *adds)
    s = cut(s, *tools) if tools else s
    if d.chance("small_chamfer", 0.5):
        s = chamfer(s, d.mm("chamfer", 0.3, 1.0, 0.1), lambda e: along(e, 0) and near(mid(e).y, 0) and near(mid(e).z, 0))
    return s


def cone(d):
    kind = d.kind("kind", ["full", "frustum", "pin", "bicone", "nozzle", "hollow_frustum"])
    if kind == "full":
        return Part.makeCone(d.mm("R", 5, 80), 0, d.mm("H", 5, 150))
    if kind == "frustum":
        R = d.mm("R", 10, 80)
        return Part.makeCone(R, d.mm("r", 1, 0.9 * R), d.mm("H", 5, 120))
    if kind == "pin":  # cylinder with a pointed end
        R, L = d.mm("R", 2, 25), d.mm("L", 10, 150)
        return fuse(Part.makeCylinder(R, L), Part.makeCone(R, 0, R / math.tan(math.radians(d.mm("half_angle", 15, 60, 1))), V(0, 0, L)))
    if kind == "bicone":
        R = d.mm("R", 5, 60)
        return fuse(Part.makeCone(0, R, d.mm("H1", 5, 100)), Part.makeCone(R, 0, d.mm("H2", 5, 100), V(0, 0, d.params["H1"])))
    if kind == "nozzle":
        R, r = d.mm("R", 10, 50), d.mm("r", 2, 8)
        r = min(r, 0.4 * R)
        h1, h2, h3 = d.mm("h1", 5, 40), d.mm("h2", 10, 80), d.mm("h3", 3, 30)
        bore = d.mm("bore_d", 1, max(1, 2 * r - 2)) / 2
        return revolve_rz([(bore, 0), (R, 0), (R, h1), (r, h1 + h2), (r, h1 + h2 + h3), (bore, h1 + h2 + h3)])
    R = d.mm("R", 10, 80)
    r = d.mm("r", 5, 0.9 * R)
    t = d.mm("wall", 1.5, 0.5 * r)
    H = d.mm("H", 5, 120)
    return revolve_rz([(R - t, 0), (R, 0), (r, H), (r - t, H)])


FAMILIES = {
    "plate_holes": plate_holes,
    "bracket_l": bracket_l,
    "flange": flange,
    "box_thin": box_thin,
    "loft": loft,
    "angled": angled,
    "tangent": tangent,
    "cone": cone,
    "boss_plate": boss_plate,
    "shaft": shaft,
    "sweep": sweep,
    "acute_wedge": acute_wedge,
    "plate_slots": plate_slots,
    "bracket_t": bracket_t,
    "shell_revolved": shell_revolved,
    "counterbore": counterbore,
    "small_features": small_features,
    "plate_pockets": plate_pockets,
    "bracket_u": bracket_u,
    "ribbed": ribbed,
}


# ---- checks and the main loop -------------------------------------------------------------------

def single_solid(shape):
    """The one closed solid of `shape`, or a ValueError saying why not."""
    if shape is None or shape.isNull():
        raise ValueError("null shape")
    solids = shape.Solids
    if len(solids) != 1:
        raise ValueError(f"{len(solids)} solids")
    s = solids[0]
    if not shape.isValid() or not s.isValid():
        raise ValueError("not valid")
    if len(s.Shells) != 1 or not s.Shells[0].isClosed():
        raise ValueError(f"{len(s.Shells)} shells or an open shell")
    if not s.Volume > 0:
        raise ValueError(f"volume {s.Volume}")
    return s


def not_self_intersecting(solid):
    """ValueError when OpenCASCADE's boolean check finds faces or edges of `solid` crossing each
    other (a profile folding back on itself, tools overlapping): a surface no mesher should take."""
    try:
        solid.check(True)
    except Exception as e:  # Part.OCCError / ValueError naming the BOP errors
        # Only crossings: a helical sweep's C0 surface ("BOPAlgo GeomAbs_C0") is a valid part.
        if "SelfIntersect" in str(e):
            raise ValueError("self-intersecting: " + " ".join(str(e).split())[:120])


def reloads(solid, path):
    """Writes the STEP file and checks that it reads back as one valid solid of the same volume."""
    solid.exportStep(path)
    back = single_solid(Part.read(path))
    if abs(back.Volume - solid.Volume) > 1e-6 * solid.Volume:
        raise ValueError(f"STEP reload volume {back.Volume} != {solid.Volume}")


def sig(x, digits=12):
    """x to `digits` significant digits: OpenCASCADE's offsets (makeThickness) may give volumes
    that differ in the last bits from one run to the next; the manifest must not."""
    return float(f"{x:.{digits}g}")


def entry(solid, family, seed, draws=1, params=None):
    bb = solid.BoundBox
    out = {"family": family, "volume": sig(solid.Volume), "diagonal": sig(bb.DiagonalLength),
           "faces": len(solid.Faces), "seed": seed, "draws": draws}
    if params is not None:
        out["params"] = params
    return out


def build(family, index, seed, attempts, tmp):
    """(solid, draws, params) of part `index` of `family`: the first of at most `attempts` draws of
    its seeded generator that builds one valid closed solid, not crossing itself, which reloads
    from STEP."""
    rng = random.Random(f"hexdom-corpus:{seed}:{family}:{index}")
    errors = []
    for k in range(1, attempts + 1):
        d = Draw(rng, index, cycle=k <= attempts // 2)
        try:
            s = single_solid(FAMILIES[family](d))
            not_self_intersecting(s)
            reloads(s, os.path.join(tmp, "check.step"))
            return s, k, d.params
        except Exception as e:  # OpenCASCADE raises Part.OCCError, ValueError, ...
            errors.append(f"{type(e).__name__}: {str(e).strip()[:80]}")
    raise RuntimeError(f"{family}_{index:03d}: no valid solid in {attempts} draws; last: " + " | ".join(errors[-3:]))


def plan(count, families):
    """[(family, index)]: part k goes to family k mod len(families)."""
    return [(families[k % len(families)], k // len(families)) for k in range(count)]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("out", help="folder to write <name>.step and manifest.json into")
    ap.add_argument("--seed", type=int, default=DEFAULT_SEED, help=f"default {DEFAULT_SEED}")
    ap.add_argument("--count", type=int, default=DEFAULT_COUNT,
                    help=f"parametric parts (default {DEFAULT_COUNT}), on top of the 17 fixed ones")
    ap.add_argument("--families", help="comma-separated subset of: " + ",".join(FAMILIES))
    ap.add_argument("--no-fixed", action="store_true", help="leave out the 17 hand-written parts")
    ap.add_argument("--attempts", type=int, default=40, help="draws per part before giving up (default 40)")
    args = ap.parse_args(argv)
    families = list(FAMILIES)
    if args.families:
        families = [f.strip() for f in args.families.split(",") if f.strip()]
        unknown = [f for f in families if f not in FAMILIES]
        if unknown:
            ap.error("unknown families: " + ", ".join(unknown))
    os.makedirs(args.out, exist_ok=True)
    t_all = time.perf_counter()
    manifest = {"seed": args.seed, "count": args.count, "families": families, "parts": {}}
    written = 0

    def write(name, solid, info):
        nonlocal written
        path = os.path.join(args.out, name + ".step")
        solid.exportStep(path)
        manifest["parts"][name] = info
        written += 1
        return path

    with tempfile.TemporaryDirectory() as tmp:
        if not args.no_fixed:
            for name, shape in parts().items():
                t0 = time.perf_counter()
                solid = single_solid(shape)  # these are fixed: a failure is a bug here, not a draw
                reloads(solid, os.path.join(tmp, "check.step"))
                path = write(name, solid, entry(solid, "fixed", None))
                print(f"{name:26s} fixed          {len(solid.Faces):4d} faces  volume {solid.Volume:12.1f}"
                      f"  {time.perf_counter() - t0:5.2f}s -> {path}", flush=True)
        for family, index in plan(args.count, families):
            t0 = time.perf_counter()
            name = f"{family}_{index:03d}"
            solid, draws, params = build(family, index, args.seed, args.attempts, tmp)
            path = write(name, solid, entry(solid, family, args.seed, draws, params))
            extra = f" ({draws} draws)" if draws > 1 else ""
            kind = params.get("kind") or params.get("base") or ""
            print(f"{name:26s} {kind:14s} {len(solid.Faces):4d} faces  volume {solid.Volume:12.1f}"
                  f"  {time.perf_counter() - t0:5.2f}s -> {path}{extra}", flush=True)
    with open(os.path.join(args.out, "manifest.json"), "w") as f:
        json.dump(manifest, f, indent=1, sort_keys=True)
    by_family = {}
    for info in manifest["parts"].values():
        by_family[info["family"]] = by_family.get(info["family"], 0) + 1
    print(f"{written} parts ({', '.join(f'{k} {v}' for k, v in by_family.items())}) in "
          f"{time.perf_counter() - t_all:.1f} s -> {args.out}/manifest.json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
