"""FEM accuracy against degrees of freedom (issue "second-order elements"): problems with known
answers solved by CalculiX through FreeCAD's own FEM set-up (ObjectsFem constraints, a material,
femtools.ccxtools writing the input and reading the results), on our meshes (Mesh Part, order 1
and 2) and on FreeCAD's Gmsh meshes (FemMeshGmsh, ElementOrder 1st and 2nd: tet4, tet10), each at
four element sizes.

Problems (steel, E 210000 MPa, nu 0.3; the cantilever and the plate nu 0, see below):
- cantilever: a 200 x 10 x 10 beam clamped at x = 0, 100 N along z on its far end; the mean z
  displacement of the far end against Timoshenko's P L^3 / 3EI + P L / (5/6 G A). With nu 0.3 the
  clamped face, held whole, cannot contract as the beam does and the 3D beam is 0.40% stiffer than
  that (every fine mesh, ours and Gmsh's, converges there); with nu 0 the clamp adds nothing and
  5/6 is the shear coefficient of a square section (Cowper's 10 (1 + nu) / (12 + 11 nu)).
- plate_hole: a 200 x 100 x 5 plate with a central hole of diameter 20, clamped at x = 0, pulled
  with 10 kN along x at x = 200; the largest xx stress on the hole against Heywood's finite-width
  concentration (Peterson's charts), K_net = 2 + (1 - d/W)^3 on the net section. That is a plane
  stress (2D) answer; with nu 0.3 the 3D plate's stress at the hole rises towards the mid-plane (a
  few percent above the 2D value for a thickness of half the radius: the meshes that resolve the
  thickness converge there, not to the formula), so the plate is solved with nu 0, for which the 3D
  solution is the plane stress one.
- thick_cylinder: a quarter of a ring (radii 10 and 20, height 10) on symmetry planes (x = 0, y = 0,
  and z = 0 held along z), 100 MPa inside; the mean radial displacement of the bore against Lame's
  open-ended (plane stress) solution.
- torsion: a round bar (radius 10, length 80) clamped at z = 0 and twisted through a square lug at
  its far end by a force along each of its sides (FreeCAD 0.20 has no torque load; see Torsion);
  the twist rate of the middle half against T / (G J), per torque FreeCAD's writer applied.

Per run: nodes, DOFs (3 per node), solve seconds (CalculiX), the measured value and its error. Then,
per problem and mesh kind, the DOFs from which on the error stays within 1% (log-log interpolation
between sizes; "-" when the finest size is above it) and the ratio of Gmsh tet10's to our second-order hexes'. With --png
the curves (error against DOFs) go to that file.

Run: /usr/bin/python3 bench/bench_fem_accuracy.py [--png docs/images/fem_accuracy.png]
     [--problems cantilever,plate_hole,thick_cylinder,torsion]
(HEXDOM_BUILD_DIR or build/ gives _hexdom.) Prints; never asserts.
"""

import argparse
import contextlib
import io
import math
import os
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
for p in ("/usr/lib/freecad-python3/lib", "/usr/share/freecad/Mod", "/usr/share/freecad/Mod/Fem",
          "/usr/share/freecad/Ext", REPO):
    if p not in sys.path:
        sys.path.append(p)
os.environ.setdefault("HEXDOM_BUILD_DIR", os.path.join(REPO, "build"))

import FreeCAD  # noqa: E402
import ObjectsFem  # noqa: E402
import Part  # noqa: E402
import numpy as np  # noqa: E402

import HexDomWorkbench as hexdom  # noqa: E402

E, NU = 210000.0, 0.3
G = E / (2 * (1 + NU))


def face_where(shape, test):
    for i, f in enumerate(shape.Faces, 1):
        if test(f):
            return "Face{}".format(i)
    raise RuntimeError("no such face")


def edge_along(shape, axis):
    for i, e in enumerate(shape.Edges, 1):
        d = e.Vertexes[-1].Point - e.Vertexes[0].Point
        if d.Length > 0 and abs(abs(d[axis]) - d.Length) < 1e-9:
            return "Edge{}".format(i)
    raise RuntimeError("no edge along axis {}".format(axis))


def near(a, b):
    return abs(a - b) < 1e-7


class Cantilever:
    name, sizes = "cantilever", (20.0, 10.0, 5.0, 2.5)
    L, h, P = 200.0, 10.0, 100.0
    nu = 0.0  # the 3D answer is then the beam formula's (see the module doc)

    def shape(self):
        return Part.makeBox(self.L, self.h, self.h)

    def set_up(self, doc, part, analysis):
        s = part.Shape
        fixed = ObjectsFem.makeConstraintFixed(doc, "Clamp")
        fixed.References = [(part, face_where(s, lambda f: near(f.BoundBox.XMax, 0)))]
        load = ObjectsFem.makeConstraintForce(doc, "Load")
        self.tip = face_where(s, lambda f: near(f.BoundBox.XMin, self.L))
        load.References = [(part, self.tip)]
        load.Force = self.P
        load.Direction = (part, [edge_along(s, 2)])
        return [fixed, load]

    def exact(self):
        shear = E / (2 * (1 + self.nu))
        return self.P * self.L ** 3 / (3 * E * self.h ** 4 / 12) + self.P * self.L / (5 / 6 * shear * self.h ** 2)

    def measure(self, part, fem, result):
        nodes = fem.getNodesByFace(part.Shape.getElement(self.tip))
        u = dict(zip(result.NodeNumbers, result.DisplacementVectors))
        return abs(float(np.mean([u[n].z for n in nodes])))


class PlateHole:
    name, sizes = "plate_hole", (20.0, 10.0, 5.0, 2.5)
    L, W, t, d, F = 200.0, 100.0, 5.0, 20.0, 10000.0
    nu = 0.0  # the 3D answer is then the 2D one the formula gives (see the module doc)

    def shape(self):
        plate = Part.makeBox(self.L, self.W, self.t)
        hole = Part.makeCylinder(self.d / 2, self.t + 2, FreeCAD.Vector(self.L / 2, self.W / 2, -1))
        return plate.cut(hole)

    def set_up(self, doc, part, analysis):
        s = part.Shape
        fixed = ObjectsFem.makeConstraintFixed(doc, "Clamp")
        fixed.References = [(part, face_where(s, lambda f: near(f.BoundBox.XMax, 0)))]
        load = ObjectsFem.makeConstraintForce(doc, "Load")
        load.References = [(part, face_where(s, lambda f: near(f.BoundBox.XMin, self.L)))]
        load.Force = self.F
        load.Direction = (part, [edge_along(s, 0)])
        self.hole = face_where(s, lambda f: isinstance(f.Surface, Part.Cylinder))
        return [fixed, load]

    def exact(self):
        k_net = 2 + (1 - self.d / self.W) ** 3
        return k_net * self.F / ((self.W - self.d) * self.t)

    def measure(self, part, fem, result):
        nodes = set(fem.getNodesByFace(part.Shape.getElement(self.hole)))
        return max(sxx for n, sxx in zip(result.NodeNumbers, result.NodeStressXX) if n in nodes)


class ThickCylinder:
    name, sizes = "thick_cylinder", (10.0, 5.0, 2.5, 1.25)
    a, b, h, p = 10.0, 20.0, 10.0, 100.0

    def shape(self):
        ring = Part.makeCylinder(self.b, self.h).cut(Part.makeCylinder(self.a, self.h))
        quarter = Part.makeBox(self.b, self.b, self.h)
        return ring.common(quarter).removeSplitter()

    def set_up(self, doc, part, analysis):
        s = part.Shape
        objs = []
        for axis, test in ((0, lambda f: near(f.BoundBox.XMax, 0)), (1, lambda f: near(f.BoundBox.YMax, 0)),
                           (2, lambda f: near(f.BoundBox.ZMax, 0))):
            c = ObjectsFem.makeConstraintDisplacement(doc, "Symmetry" + "xyz"[axis])
            c.References = [(part, face_where(s, test))]
            for k, name in enumerate("xyz"):
                setattr(c, name + "Free", k != axis)
                setattr(c, name + "Fix", k == axis)
            objs.append(c)
        pressure = ObjectsFem.makeConstraintPressure(doc, "Pressure")
        self.bore = face_where(s, lambda f: isinstance(f.Surface, Part.Cylinder) and near(f.Surface.Radius, self.a))
        pressure.References = [(part, self.bore)]
        pressure.Pressure = self.p
        objs.append(pressure)
        return objs

    def exact(self):
        a, b, p = self.a, self.b, self.p
        A, B = p * a * a / (b * b - a * a), p * a * a * b * b / (b * b - a * a)
        return ((1 - NU) * A * a + (1 + NU) * B / a) / E

    def measure(self, part, fem, result):
        nodes = fem.getNodesByFace(part.Shape.getElement(self.bore))
        u = dict(zip(result.NodeNumbers, result.DisplacementVectors))
        return float(np.mean([(u[n].x * fem.Nodes[n].x + u[n].y * fem.Nodes[n].y) / math.hypot(fem.Nodes[n].x, fem.Nodes[n].y)
                              for n in nodes]))


class Torsion:
    """A round bar clamped at z = 0 and twisted through a square lug at its far end. FreeCAD 0.20 has
    no torque load: each of the lug's four sides carries a force F along it (x = +a: +y, y = +a: -x,
    ...), uniform over the face as ccxtools spreads it: no net force, a torque 4 a F whatever the
    spread over each face. The torque actually applied is read back from the *CLOAD lines FreeCAD
    wrote (a mesh face that is not wholly on a CAD face gets no load from FreeCAD's writer, so a
    mesh not following the lug's edges gets less); the twist rate is scaled to the nominal torque
    (printed beside: the share of the force applied). Far from the ends (Saint-Venant) the bar
    twists at T / (G J), J = pi R^4 / 2: measured as the slope of the twist angle of the bar's
    outer surface nodes against z over the middle half of the bar (least squares)."""
    name, sizes = "torsion", (10.0, 7.0, 5.0, 3.5)
    R, L, a, lug, F = 10.0, 80.0, 12.0, 12.0, 1000.0

    def shape(self):
        bar = Part.makeCylinder(self.R, self.L)
        lug = Part.makeBox(2 * self.a, 2 * self.a, self.lug, FreeCAD.Vector(-self.a, -self.a, self.L))
        return bar.fuse(lug).removeSplitter().Solids[0]

    def set_up(self, doc, part, analysis):
        s = part.Shape
        fixed = ObjectsFem.makeConstraintFixed(doc, "Clamp")
        fixed.References = [(part, face_where(s, lambda f: near(f.BoundBox.ZMax, 0)))]
        x_edge, y_edge = edge_along(s, 0), edge_along(s, 1)
        loads = []
        for axis, side in ((0, 1), (1, 1), (0, -1), (1, -1)):
            name = face_where(s, lambda f, axis=axis, side=side: near(f.BoundBox.ZMin, self.L) and near(
                f.BoundBox.ZMax, self.L + self.lug) and near(f.BoundBox.Center[axis], side * self.a))
            # Counter-clockwise about +z: on x = +a along +y, on y = +a along -x, and so on.
            along, sign = (1, side) if axis == 0 else (0, -side)
            load = ObjectsFem.makeConstraintForce(doc, "Load" + "xy"[axis] + ("p" if side > 0 else "m"))
            load.References = [(part, name)]
            load.Force = self.F
            load.Direction = (part, [y_edge if along == 1 else x_edge])
            doc.recompute()
            if load.DirectionVector[along] * sign < 0:
                load.Reversed = not load.Reversed
                doc.recompute()
            loads.append(load)
        self.side = part.Shape.getElement(face_where(s, lambda f: isinstance(f.Surface, Part.Cylinder)))
        return [fixed] + loads

    def torque(self):
        return 4 * self.a * self.F

    def exact(self):
        return self.torque() / (G * math.pi * self.R ** 4 / 2)

    def written(self, inp):
        """The torque about z and the net force of the *CLOAD lines of the input file ``inp``."""
        text = open(inp).read()
        nodes, load, block = {}, np.zeros((2, 3)), None
        for line in text.splitlines():
            if line.startswith("**"):  # a comment
                continue
            if line.startswith("*"):
                block = line.split(",")[0].strip().upper()
                continue
            cells = [c.strip() for c in line.split(",")]
            if block == "*NODE" and len(cells) >= 4:
                nodes[int(cells[0])] = np.array([float(c) for c in cells[1:4]])
            elif block == "*CLOAD" and len(cells) == 3:
                f = np.zeros(3)
                f[int(cells[1]) - 1] = float(cells[2])
                p = nodes[int(cells[0])]
                load += [np.cross(p, f), f]
        self.applied = load[0][2] / self.torque()
        self.net = np.linalg.norm(load[1]) / self.F

    def measure(self, part, fem, result):
        u = dict(zip(result.NodeNumbers, result.DisplacementVectors))
        z, angle = [], []
        for n in fem.getNodesByFace(self.side):
            p = fem.Nodes[n]
            if self.L / 4 <= p.z <= 3 * self.L / 4:
                z.append(p.z)
                angle.append((p.x * u[n].y - p.y * u[n].x) / (p.x ** 2 + p.y ** 2))
        return abs(float(np.polyfit(z, angle, 1)[0])) / self.applied


PROBLEMS = {p.name: p for p in (Cantilever, PlateHole, ThickCylinder, Torsion)}
KINDS = ("hexdom 1", "hexdom 2", "gmsh tet4", "gmsh tet10")


def make_mesh(doc, part, kind, size):
    if kind.startswith("hexdom"):
        objs = hexdom.mesh_part(doc, part, size=size, order=int(kind[-1]), allow_inverted=True)
        return objs["mesh"]
    from femmesh.gmshtools import GmshTools
    gm = ObjectsFem.makeMeshGmsh(doc, "Gmsh")
    gm.Part = part
    gm.CharacteristicLengthMax = size
    gm.ElementOrder = "2nd" if kind.endswith("10") else "1st"
    doc.recompute()
    error = GmshTools(gm).create_mesh()
    if error:
        raise RuntimeError("gmsh: " + str(error))
    return gm


def solve(problem, kind, size, work):
    from femtools import ccxtools
    doc = FreeCAD.newDocument("fem_" + problem.name)
    try:
        part = doc.addObject("Part::Feature", "Part")
        part.Shape = problem.shape()
        doc.recompute()
        mesh = make_mesh(doc, part, kind, size)
        analysis = ObjectsFem.makeAnalysis(doc, "Analysis")
        solver = ObjectsFem.makeSolverCalculixCcxTools(doc, "Solver")
        material = ObjectsFem.makeMaterialSolid(doc, "Steel")
        mat = material.Material
        mat.update({"Name": "Steel", "YoungsModulus": "{} MPa".format(E),
                    "PoissonRatio": str(getattr(problem, "nu", NU))})
        material.Material = mat
        for o in [solver, material, mesh] + problem.set_up(doc, part, analysis):
            analysis.addObject(o)
        doc.recompute()
        fea = ccxtools.FemToolsCcx(analysis=analysis, solver=solver)
        fea.update_objects()
        fea.setup_working_dir(work)
        message = fea.check_prerequisites()
        if message:
            raise RuntimeError(message)
        with contextlib.redirect_stdout(io.StringIO()):  # FreeCAD's writer prints its material table
            fea.write_inp_file()
        if hasattr(problem, "written"):
            problem.written(fea.inp_file_name)
        fea.setup_ccx()
        t = time.perf_counter()
        if fea.ccx_run() != 0:
            raise RuntimeError("ccx failed: " + str(fea.ccx_stdout)[-300:])
        seconds = time.perf_counter() - t
        with contextlib.redirect_stdout(io.StringIO()):
            fea.load_results()
        result = [o for o in analysis.Group if o.isDerivedFrom("Fem::FemResultObject")][0]
        fem = mesh.FemMesh
        return fem.NodeCount, problem.measure(part, fem, result), seconds
    finally:
        FreeCAD.closeDocument(doc.Name)


def dofs_at(rows, target=0.01):
    """DOFs from which on |error| stays within target (a coarse size that meets it by chance, its
    finer neighbour above it again, does not count), log-log interpolated between the last size
    above target and the next; the coarsest's DOFs when every size is within, None when the
    finest is not."""
    rows = sorted(rows)
    if not rows or rows[-1][1] > target:
        return None
    above = [i for i, (_, e) in enumerate(rows) if e > target]
    if not above:
        return rows[0][0]
    (d0, e0), (d1, e1) = rows[above[-1]], rows[above[-1] + 1]
    if e1 <= 0:
        return d1
    f = math.log(e0 / target) / math.log(e0 / e1)
    return math.exp(math.log(d0) + f * (math.log(d1) - math.log(d0)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--problems", default=",".join(PROBLEMS))
    ap.add_argument("--png")
    a = ap.parse_args()
    curves = {}
    print(f"{'problem':15s} {'mesh':10s} {'size':>6s} {'nodes':>7s} {'DOFs':>7s} {'value':>12s} {'exact':>12s} "
          f"{'error':>8s} {'solve s':>7s}")
    with tempfile.TemporaryDirectory() as tmp:
        for name in a.problems.split(","):
            problem = PROBLEMS[name]()
            exact = problem.exact()
            for kind in KINDS:
                for size in problem.sizes:
                    work = os.path.join(tmp, f"{name}_{kind.replace(' ', '_')}_{size}")
                    os.makedirs(work)
                    try:
                        nodes, value, seconds = solve(problem, kind, size, work)
                    except Exception as e:  # a failed run is a figure too
                        print(f"{name:15s} {kind:10s} {size:6g} failed: {str(e).splitlines()[0][:80]}", flush=True)
                        continue
                    error = abs(value / exact - 1)
                    curves.setdefault((name, kind), []).append((3 * nodes, error))
                    note = (f"  (force applied {problem.applied:.1%}, net {problem.net:.1%} of F)"
                            if hasattr(problem, "applied") else "")
                    print(f"{name:15s} {kind:10s} {size:6g} {nodes:7d} {3 * nodes:7d} {value:12.6g} {exact:12.6g} "
                          f"{error:8.3%} {seconds:7.2f}{note}", flush=True)
    print("\nDOFs from which on the error stays within 1% (log-log between sizes; - : the finest is above)")
    for name in a.problems.split(","):
        reach = {kind: dofs_at(curves.get((name, kind), [])) for kind in KINDS}
        text = ", ".join(f"{k} {v:.0f}" if v else f"{k} -" for k, v in reach.items())
        ratio = (f"; tet10 / hex20 = {reach['gmsh tet10'] / reach['hexdom 2']:.2f}"
                 if reach["gmsh tet10"] and reach["hexdom 2"] else "")
        print(f"  {name}: {text}{ratio}")
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        names = a.problems.split(",")
        fig, axes = plt.subplots(1, len(names), figsize=(5 * len(names), 4))
        for ax, name in zip(np.atleast_1d(axes), names):
            for kind in KINDS:
                pts = sorted(curves.get((name, kind), []))
                if pts:
                    ax.loglog([p[0] for p in pts], [max(p[1], 1e-5) for p in pts], "o-", label=kind)
            ax.axhline(0.01, color="gray", lw=0.8, ls="--")
            ax.set_title(name)
            ax.set_xlabel("degrees of freedom")
            ax.set_ylabel("relative error")
            ax.legend()
        fig.tight_layout()
        fig.savefig(a.png, dpi=100)
        print("wrote " + a.png)


if __name__ == "__main__":
    main()
    sys.exit(0)
