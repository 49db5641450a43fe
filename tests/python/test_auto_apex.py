"""Parts whose faces are triangles (issue 9, "use prism / tet blocks where a chart is triangular"):
a cone, a sharper cone, a square pyramid, a tetrahedron and a box with a corner cut off, made with
FreeCAD Part, written as STEP and meshed by `hexdom mesh` at the default size (diagonal / 30).
Before the apex caps the first four failed in autopolycube (the label repair merged every chart
around the tip and gave up); before split_oblique_faces the tetrahedron still did.

Oracles nobody here wrote: FreeCAD's Part (the B-rep volume, distToShape of the boundary nodes to
the faces), VTK (the mesh read back, vtkDataSetSurfaceFilter for the boundary nodes, Verdict's
scaled Jacobian per cell type through vtkMeshQuality).

Measured (level 1 unless said), after session 6: cone R25 x 40 1,408 hex, worst 0.429, -0.66% (the
base rim keeps 0.6 of its length in cells, PolycubeMapOptions::keep_lengths; before: 876 hex, 0.461,
-1.16% with 24 nodes around the rim); pyramid 40 x 40 x 30 635 hex (level 0), worst 0.325, -0.00%;
cone R10 x 60: 320 hex, worst 0.240, -10.0% (the polycube is one cell across); tetrahedron (slanted
face split from its corners, split_oblique_faces): 704 hex, worst 0.450, -0.00% (before: no mesh);
box 40 with a corner cut off at 15 (its triangular face split the same way): 4,088 hex, worst 0.500.
With tet blocks at the tip the pyramid gave 288 hex (0.204) / 984 prisms (0.212) / 144 tets (0.222):
`hexdom mesh` keeps the hex blocks under the caps, whose worst cell is better."""

import subprocess

import numpy as np
import pytest

import hexdom_oracles as oracle
import hexdom_test_support as support


def _shapes(FreeCAD, Part):
    V = FreeCAD.Vector
    base = Part.Face(Part.makePolygon([V(0, 0, 0), V(40, 0, 0), V(40, 40, 0), V(0, 40, 0), V(0, 0, 0)]))
    sides = [Part.Face(Part.makePolygon([a, b, V(20, 20, 30), a]))
             for a, b in [(V(0, 0, 0), V(40, 0, 0)), (V(40, 0, 0), V(40, 40, 0)), (V(40, 40, 0), V(0, 40, 0)),
                          (V(0, 40, 0), V(0, 0, 0))]]
    p = [V(0, 0, 0), V(40, 0, 0), V(0, 40, 0), V(0, 0, 40)]
    tetra = [Part.Face(Part.makePolygon([p[a], p[b], p[c], p[a]])) for a, b, c in [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]]
    # A box with a corner cut off by a plane of normal (1, 1, 1): its triangular face lies between
    # +X, +Y and +Z faces (a notch's corner once split), where the tetrahedron's lies between -X, -Y, -Z.
    q = [V(40, 40, 40), V(25, 40, 40), V(40, 25, 40), V(40, 40, 25)]
    corner = [Part.Face(Part.makePolygon([q[a], q[b], q[c], q[a]]))
              for a, b, c in [(0, 1, 2), (0, 2, 3), (0, 3, 1), (1, 3, 2)]]
    return {
        "cut_corner": Part.makeBox(40, 40, 40).cut(Part.Solid(Part.Shell(corner))),
        "cone": Part.makeCone(25, 0, 40),
        "sharp_cone": Part.makeCone(10, 0, 60),
        "pyramid": Part.Solid(Part.Shell([base] + sides)),
        "tetrahedron": Part.Solid(Part.Shell(tetra)),
    }


SHAPES = ["cone", "sharp_cone", "pyramid", "tetrahedron", "cut_corner"]
_NOT_MESHED = {}
# sharp_cone (R10 x 60): its polycube is one cell across (worst hex SJ 0.240, volume -10.0%, issue 9);
# auto then meshes the overlay grid too and keeps it, which meets both targets.
_SJ_DEFECT = {}
_VOLUME_DEFECT = {}


def _marks(defects):
    out = []
    for s in SHAPES:
        reason = _NOT_MESHED.get(s) or defects.get(s)
        out.append(pytest.param(s, marks=pytest.mark.xfail(strict=True, reason=reason)) if reason else s)
    return out


@pytest.fixture(scope="module")
def meshed(freecad, tmp_path_factory, core):
    if not core._hexdom.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")
    FreeCAD, Part = freecad
    shapes = _shapes(FreeCAD, Part)
    cache = {}

    def get(name):
        if name not in cache:
            d = tmp_path_factory.mktemp(name)
            shape = shapes[name]
            assert shape.isValid()
            shape.exportStep(str(d / f"{name}.step"))
            out = d / f"{name}.vtu"
            r = subprocess.run([str(support.hexdom_bin()), "mesh", str(d / f"{name}.step"), "-o", str(out)],
                               capture_output=True, text=True)
            cache[name] = (shape, r, out)
        shape, r, out = cache[name]
        assert r.returncode == 0, f"hexdom mesh {name} exited {r.returncode}: {r.stderr.strip()[-400:]}"
        g, sj, types = oracle.vtu_sj_types(out)
        return shape, g, sj, types, r.stdout + r.stderr
    return get


@pytest.mark.parametrize("name", _marks({}))
def test_triangular_part_meshes_with_no_inverted_cell(name, meshed):
    _, g, sj, types, log = meshed(name)
    assert g.GetNumberOfCells() > 0
    assert np.all(sj > 0), f"{name}: {int(np.sum(~(sj > 0)))} inverted cells"
    # The quality summary has a row per cell type; its counts are the file's.
    for t, row in ((oracle.HEX, "hex"), (oracle.WEDGE, "prism"), (oracle.TET, "tet")):
        assert any(line.split()[:2] == [row, str(int(np.sum(types == t)))] for line in log.splitlines()), (row, log[-600:])


@pytest.mark.parametrize("name", _marks({}))
def test_triangular_part_boundary_lies_on_the_brep(name, meshed, freecad):
    FreeCAD, Part = freecad
    shape, g, _, _, _ = meshed(name)
    d = oracle.max_brep_distance(FreeCAD, Part, shape, g)
    assert d <= 1e-7 * shape.BoundBox.DiagonalLength, f"{name}: {d:.3g} off the B-rep"


@pytest.mark.parametrize("name", _marks(_VOLUME_DEFECT))
def test_triangular_part_volume_within_1_percent(name, meshed):
    shape, g, _, _, _ = meshed(name)
    volume = float(oracle.signed_volumes(g).sum())
    print(f"{name}: mesh volume {volume:.6g}, B-rep {shape.Volume:.6g} ({100 * (volume - shape.Volume) / shape.Volume:+.2f}%)")
    assert volume == pytest.approx(shape.Volume, rel=0.01)


@pytest.mark.parametrize("name", _marks(_SJ_DEFECT))
def test_triangular_part_worst_hex_sj_at_least_0_3(name, meshed):
    _, _, sj, types, _ = meshed(name)
    hexes = sj[types == oracle.HEX]
    for t, n in ((oracle.WEDGE, "prism"), (oracle.TET, "tet")):
        if np.any(types == t):
            print(f"{name}: {n} worst SJ {sj[types == t].min():.3f}")
    if hexes.size:
        print(f"{name}: {hexes.size} hexes, worst SJ {hexes.min():.3f}")
        assert hexes.min() >= 0.3


@pytest.mark.parametrize("name", _marks({}))
def test_triangular_part_edge_ratio_at_most_10(name, meshed):
    # The pyramid's polycube mesh had 13.2 (2 hexes at its base corners) while its worst hex SJ,
    # 0.324, barred every move that shortened them; the ratio stage now lowers that bar in steps.
    _, g, _, types, _ = meshed(name)
    P, _, conn = oracle.grid_arrays(g)
    worst = 0.0
    for t in (oracle.HEX, oracle.WEDGE, oracle.TET):
        cells = [conn[c] for c in np.flatnonzero(types == t)]
        if cells:
            worst = max(worst, float(oracle.edge_ratios(P[np.array(cells)], t).max()))
    print(f"{name}: largest edge ratio {worst:.3f}")
    assert worst <= 10 + 1e-6


def test_the_polycube_reports_every_figure_of_the_core(freecad, tmp_path, core):
    # The figures come from AutoPolycube::for_each_figure, the one list; the tetrahedron's slanted
    # face is split from its corners, so oblique_faces counts it.
    if not core._hexdom.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")
    FreeCAD, Part = freecad
    _shapes(FreeCAD, Part)["tetrahedron"].exportStep(str(tmp_path / "tetrahedron.step"))
    info = core.mesh_part(str(tmp_path / "tetrahedron.step")).polycube.info
    assert set(info) == {"cell", "charts", "relabelled", "chords", "planes", "pushed", "squares", "blocks",
                         "boundary_vertices", "interior_vertices", "slivers", "prism_blocks", "tet_blocks",
                         "oblique_faces", "apexes", "apexes_collapsed", "widened", "min_block_quality",
                         "inverted_blocks"}
    assert info["oblique_faces"] >= 1 and info["blocks"] > 0 and info["cell"] > 0
