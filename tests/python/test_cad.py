"""CAD import and tessellation through _hexdom and the hexdom program, checked with oracles that
share no code with the C++ core: numpy (closedness, orientation, divergence-theorem volume, angles),
VTK (vtkMassProperties volume, vtkFeatureEdges for open and non-manifold edges, the legacy VTK
reader for the program's output) and, where FreeCAD's Python modules import, FreeCAD itself (the
B-rep's volume and Face<N> numbering through shape.Faces and distToShape).

Data: the STEP parts under <HEXDOM_DATA>/cad (default ../shared/data/cad); a missing part is a
skip naming its path.
"""

import os
import subprocess
from pathlib import Path

import numpy as np
import pytest
import vtk
from vtk.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy

import hexdom_test_support as support

CAD_DATA = support.DATA_ROOT / "cad"
STEP_PARTS = ["i01o_m1.step", "i10o_simp.step", "i11o_s1.step", "n11o_limit_cycle.stp",
              "s09o_bridge.step", "s11o_cube_cyl.stp", "s12o_cube_rounded_1.stp",
              "s14o_cube_corner_sub_sphere.stp", "s15o_cylinder.stp"]


@pytest.fixture(scope="module")
def hx(core):
    """The compiled module under test (the CAD functions are not wrapped by core.py yet)."""
    if not core._hexdom.has_opencascade():
        pytest.skip("_hexdom was built without OpenCASCADE (HEXDOM_WITH_CAD=OFF)")
    return core._hexdom


def step_part(name):
    path = CAD_DATA / name
    if not path.exists():
        pytest.skip(support.missing(path))
    return path


# ---- independent checks -------------------------------------------------------------------------

def edge_counts(F):
    """(undirected edge -> count, directed edges all distinct)."""
    d = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    u = np.sort(d, axis=1)
    _, counts = np.unique(u, axis=0, return_counts=True)
    directed_unique = len(np.unique(d, axis=0)) == len(d)
    return counts, directed_unique


def divergence_volume(V, F):
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0


def triangle_angles(V, F):
    """#F x 3 interior angles in degrees."""
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]

    def ang(u, v):
        return np.degrees(np.arctan2(np.linalg.norm(np.cross(u, v), axis=1), (u * v).sum(1)))
    return np.stack([ang(b - a, c - a), ang(a - b, c - b), ang(a - c, b - c)], 1)


def vtk_polydata(V, F):
    pts = vtk.vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(V, float), deep=True))
    cells = np.hstack([np.full((len(F), 1), 3), F]).astype(np.int64).ravel()
    ca = vtk.vtkCellArray()
    ca.SetCells(len(F), numpy_to_vtkIdTypeArray(cells, deep=True))
    pd = vtk.vtkPolyData()
    pd.SetPoints(pts)
    pd.SetPolys(ca)
    return pd


def vtk_volume_and_bad_edges(V, F):
    """VTK's enclosed volume and its count of boundary plus non-manifold edges."""
    pd = vtk_polydata(V, F)
    mp = vtk.vtkMassProperties()
    mp.SetInputData(pd)
    mp.Update()
    fe = vtk.vtkFeatureEdges()
    fe.SetInputData(pd)
    fe.BoundaryEdgesOn()
    fe.NonManifoldEdgesOn()
    fe.FeatureEdgesOff()
    fe.ManifoldEdgesOff()
    fe.Update()
    return mp.GetVolume(), fe.GetOutput().GetNumberOfCells()


def sharp_corner_points(V, F, face_id, corners):
    """CAD vertices where the triangles of one face meet at less than 20 degrees in total (a cusp):
    no triangle at such a corner can have a larger angle than the corner."""
    A = triangle_angles(V, F)
    sharp = []
    for p in corners:
        d = np.linalg.norm(V - p, axis=1)
        v = int(np.argmin(d))
        if d[v] > 1e-9 * max(1.0, np.abs(V).max()):
            continue
        rows, cols = np.nonzero(F == v)
        for f in np.unique(face_id[rows]):
            if A[rows[face_id[rows] == f], cols[face_id[rows] == f]].sum() < 20:
                sharp.append(p)
    return np.array(sharp).reshape(-1, 3)


def check_surface(hx, source, V, F, face_id, size, info, volume_tolerance=0.005):
    """Every property of a tessellation, checked independently; returns figures for the report."""
    assert V.shape[1] == 3 and F.shape[1] == 3 and len(face_id) == len(F)
    counts, directed_unique = edge_counts(F)
    assert (counts == 2).all(), f"{(counts != 2).sum()} edges not shared by exactly two triangles"
    assert directed_unique, "two triangles run along an edge in the same direction"
    vol = divergence_volume(V, F)
    vtk_vol, bad_edges = vtk_volume_and_bad_edges(V, F)
    assert bad_edges == 0
    assert vol > 0, "triangles face inward"
    assert abs(vtk_vol - vol) < 1e-6 * vol
    err = (vol - info["volume"]) / info["volume"]
    assert abs(err) < volume_tolerance, f"volume {vol} vs B-rep {info['volume']}"
    assert set(face_id.tolist()) == set(range(1, info["faces"] + 1))
    # Vertices on the B-rep.
    _, dist, _ = hx.project_to_shape(source, V)
    diag = np.linalg.norm(np.subtract(info["bbox_max"], info["bbox_min"]))
    assert dist.max() < 1e-6 * diag
    # Face ids: centroids on their own face (planar: exactly), never clearly nearer to another.
    sharp = sharp_corner_points(V, F, face_id, info["vertex_points"])
    near_sharp = np.zeros(len(F), bool)
    for p in sharp:
        near_sharp |= (np.linalg.norm(V[F] - p, axis=2) < size).any(1)
    C = V[F].mean(1)
    _, nearest, _ = hx.project_to_shape(source, C)
    planar = np.array([info["face_types"][f - 1] == "plane" for f in face_id])
    for f in np.unique(face_id):
        sel = (face_id == f) & ~near_sharp
        if not sel.any():
            continue
        _, own, _ = hx.project_to_face(source, int(f), C[sel])
        assert (own <= nearest[sel] + 0.05 * size).all(), f"triangles of Face{f} nearer to another face"
        assert own.max() < 0.1 * size
        if info["face_types"][f - 1] == "plane":
            assert own.max() < 1e-7 * diag, f"triangles off planar Face{f}"
    # Angles and sizes.
    min_angle = triangle_angles(V, F).min(1)
    keep = planar & ~near_sharp
    if keep.any():
        assert min_angle[keep].min() >= 20.0
    E = np.linalg.norm(V[F] - V[np.roll(F, -1, axis=1)], axis=2)
    assert E.max() < 1.5 * size
    return {"triangles": len(F), "volume_error": err, "min_angle": min_angle.min(),
            "min_angle_planar": min_angle[planar].min() if planar.any() else 180.0,
            "min_angle_planar_away": min_angle[keep].min() if keep.any() else 180.0,
            "mean_edge_planar": E[planar].mean() if planar.any() else float("nan")}


# ---- the shared STEP parts ----------------------------------------------------------------------

@pytest.mark.parametrize("name", STEP_PARTS)
def test_step_part_tessellation(hx, name):
    path = os.fspath(step_part(name))
    info = hx.cad_info(path)
    size = np.linalg.norm(np.subtract(info["bbox_max"], info["bbox_min"])) / 30
    V, F, face_id = hx.tessellate_file(path, size=size)
    assert V.dtype == np.float64 and F.dtype == np.int32 and face_id.dtype == np.int32
    r = check_surface(hx, path, V, F, face_id, size, info)
    print(f"{name}: {r['triangles']} triangles, min angle planar {r['min_angle_planar']:.2f} "
          f"({r['min_angle_planar_away']:.2f} away from cusps), overall {r['min_angle']:.2f}, "
          f"volume error {100 * r['volume_error']:+.3f}%")


def test_cad_volume_matches_freecad(hx, freecad):
    FreeCAD, Part = freecad
    for name in ["s11o_cube_cyl.stp", "i10o_simp.step"]:
        path = os.fspath(step_part(name))
        shape = Part.read(path)
        solid = shape.Solids[0]
        assert hx.cad_volume(path) == pytest.approx(solid.Volume, rel=1e-9)
        assert hx.cad_info(path)["faces"] == len(solid.Faces)


def test_size_follows_the_option(hx):
    path = os.fspath(step_part("s11o_cube_cyl.stp"))
    info = hx.cad_info(path)
    diag = np.linalg.norm(np.subtract(info["bbox_max"], info["bbox_min"]))
    triangles = []
    for size in (diag / 20, diag / 40):
        V, F, face_id = hx.tessellate_file(path, size=size)
        r = check_surface(hx, path, V, F, face_id, size, info, volume_tolerance=0.01)
        assert 0.7 * size < r["mean_edge_planar"] < 1.15 * size
        triangles.append(len(F))
    assert 3.0 < triangles[1] / triangles[0] < 5.0


def test_brep_string_equals_file(hx, freecad):
    """The BREP hand-over gives the same solid as the file (volume, faces, tessellation)."""
    FreeCAD, Part = freecad
    path = os.fspath(step_part("s14o_cube_corner_sub_sphere.stp"))
    brep = Part.read(path).Solids[0].exportBrepToString()
    assert hx.cad_volume(brep) == pytest.approx(hx.cad_volume(path), rel=1e-12)
    V, F, face_id = hx.tessellate_brep(brep)
    W, G, gid = hx.tessellate_file(path)
    # FreeCAD reads the STEP file with its own settings: the same solid up to round-off, so the
    # same faces with about the same triangles each.
    a, b = np.bincount(face_id), np.bincount(gid)
    assert len(a) == len(b)
    assert np.allclose(a, b, rtol=0.1, atol=10)


def test_wireframe_brep_is_a_geometry_error(hx):
    with pytest.raises(hx.GeometryError, match="no solid, only 1 edge"):
        hx.tessellate_brep(EDGE_BREP)


# ---- FreeCAD hand-over: parts built with Part, passed as exportBrepToString() --------------------

def freecad_parts(FreeCAD, Part):
    V = FreeCAD.Vector
    box = Part.makeBox(10, 8, 6)
    hole = Part.makeBox(20, 20, 10).cut(Part.makeCylinder(4, 12, V(10, 10, -1)))
    profile = Part.Face(Part.makePolygon([V(0, 0, 0), V(30, 0, 0), V(30, 6, 0), V(6, 6, 0), V(6, 20, 0),
                                          V(0, 20, 0), V(0, 0, 0)]))
    bracket = profile.extrude(V(0, 0, 15))
    cylinder = Part.makeCylinder(5, 12)
    # A document object's Placement reaches OCCT as a TopLoc_Location on the shape.
    placed = hole.copy()
    placed.Placement = FreeCAD.Placement(V(100, -50, 30), FreeCAD.Rotation(V(1, 2, 3), 37))
    return {"box": box, "box_with_hole": hole, "l_bracket": bracket, "cylinder": cylinder,
            "placed_box_with_hole": placed}


@pytest.mark.parametrize("name", ["box", "box_with_hole", "l_bracket", "cylinder", "placed_box_with_hole"])
def test_freecad_part_hand_over(hx, freecad, name):
    FreeCAD, Part = freecad
    shape = freecad_parts(FreeCAD, Part)[name]
    brep = shape.exportBrepToString()
    info = hx.cad_info(brep)
    assert info["faces"] == len(shape.Faces)
    assert info["volume"] == pytest.approx(shape.Volume, rel=1e-9)
    size = shape.BoundBox.DiagonalLength / 30
    V, F, face_id = hx.tessellate_brep(brep, size=size)
    check_surface(hx, brep, V, F, face_id, size, info)
    if name == "box":
        assert sorted(set(face_id.tolist())) == [1, 2, 3, 4, 5, 6]
    # FreeCAD's own numbering: triangle t lies on shape.Faces[face_id[t] - 1].
    C = V[F].mean(1)
    for t in range(0, len(F), max(1, len(F) // 150)):
        d = shape.Faces[face_id[t] - 1].distToShape(Part.Vertex(FreeCAD.Vector(*C[t])))[0]
        assert d < 0.1 * size, f"triangle {t} labelled Face{face_id[t]} is {d} from it"


def test_freecad_non_solids_are_geometry_errors(hx, freecad):
    FreeCAD, Part = freecad
    face = Part.makePlane(2, 3)
    with pytest.raises(hx.GeometryError, match="no solid, only 1 face"):
        hx.tessellate_brep(face.exportBrepToString())
    shell = Part.Shell(Part.makeBox(1, 1, 1).Faces[:5])
    with pytest.raises(hx.GeometryError, match="no solid but 1 shell"):
        hx.tessellate_brep(shell.exportBrepToString())
    assert issubclass(hx.GeometryError, hx.Error) and issubclass(hx.Error, RuntimeError)


# ---- projection -----------------------------------------------------------------------------------

def test_project_to_face_on_a_cylinder(hx):
    path = os.fspath(step_part("s15o_cylinder.stp"))
    info = hx.cad_info(path)
    side = info["face_types"].index("cylinder") + 1
    lo, hi = np.array(info["bbox_min"]), np.array(info["bbox_max"])
    centre = (lo + hi) / 2
    extent = hi - lo
    axis = int(np.argmax(np.abs(extent - np.median(extent))))  # the one extent unlike the other two
    radius = np.delete(extent, axis).mean() / 2
    rng = np.random.default_rng(1)
    theta = rng.uniform(0, 2 * np.pi, 20)
    radial = np.zeros((20, 3))
    others = [i for i in range(3) if i != axis]
    radial[:, others[0]] = np.cos(theta)
    radial[:, others[1]] = np.sin(theta)
    P = centre + radial * (radius + 2.0)
    P[:, axis] += rng.uniform(-0.3, 0.3, 20) * extent[axis]
    Q, dist, uv = hx.project_to_face(path, side, P)
    assert np.allclose(np.linalg.norm((Q - centre)[:, others], axis=1), radius, atol=1e-6)
    assert np.allclose(dist, 2.0, atol=1e-6)
    assert np.allclose(Q[:, axis], P[:, axis], atol=1e-6)
    assert uv.shape == (20, 2)
    with pytest.raises(hx.InputError, match="Face99"):
        hx.project_to_face(path, 99, P)


def test_project_to_edge_clamps_to_the_ends(hx):
    path = os.fspath(step_part("s11o_cube_cyl.stp"))
    info = hx.cad_info(path)
    lo, hi = np.array(info["bbox_min"]), np.array(info["bbox_max"])
    far = hi + 10 * (hi - lo)  # beyond every edge's end
    for e in range(1, info["edges"] + 1):
        Q, dist, t = hx.project_to_edge(path, e, far[None, :])
        # The nearest point of an edge to a far point is on the B-rep, and is one of the CAD vertices
        # or inside the bounding box.
        assert (Q[0] >= lo - 1e-6).all() and (Q[0] <= hi + 1e-6).all()
        assert dist[0] == pytest.approx(np.linalg.norm(Q[0] - far))
        _, on, _ = hx.project_to_shape(path, Q)
        assert on[0] < 1e-7
    with pytest.raises(hx.InputError, match="Edge999"):
        hx.project_to_edge(path, 999, far[None, :])


# ---- errors -----------------------------------------------------------------------------------------

def test_missing_file_is_an_input_error(hx, tmp_path):
    missing = tmp_path / "nothing.step"
    with pytest.raises(hx.InputError, match="nothing.step: cannot open file"):
        hx.tessellate_file(os.fspath(missing))
    with pytest.raises(hx.InputError):
        hx.cad_volume(os.fspath(missing))


def test_corrupt_step_is_an_input_error(hx, tmp_path):
    bad = tmp_path / "corrupt.step"
    bad.write_text("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1 = CARTESIAN_POINT('',(0.,0.,0.);\nENDSEC;\n")
    with pytest.raises(hx.InputError, match=r"corrupt.step:5: Incorrect syntax"):
        hx.tessellate_file(os.fspath(bad))


def test_garbage_brep_is_an_input_error(hx):
    with pytest.raises(hx.InputError, match="<BREP string>"):
        hx.tessellate_brep("CASCADE Topology V1, (c) Matra-Datavision\nnonsense\n")


def test_without_opencascade_every_entry_point_says_so(core, hexdom_bin, tmp_path):
    """A build with HEXDOM_WITH_CAD=OFF keeps the functions and the command, which fail clearly."""
    hx = core._hexdom
    if hx.has_opencascade():
        pytest.skip("this build has OpenCASCADE")
    for call in (lambda: hx.tessellate_file("part.step"), lambda: hx.tessellate_brep("x"),
                 lambda: hx.cad_volume("part.step"), lambda: hx.cad_info("part.step"),
                 lambda: hx.project_to_face("part.step", 1, np.zeros((1, 3)))):
        with pytest.raises(hx.Error, match="built without OpenCASCADE: cannot"):
            call()
    out = tmp_path / "out.k"
    r = subprocess.run([hexdom_bin, "tessellate", "part.step", "-o", out], capture_output=True, text=True)
    assert r.returncode == 1
    assert "built without OpenCASCADE: cannot" in r.stderr
    assert not out.exists()


# ---- the hexdom program -----------------------------------------------------------------------------

def read_vtk_triangles(path):
    r = vtk.vtkGenericDataObjectReader()
    r.SetFileName(os.fspath(path))
    r.Update()
    grid = r.GetOutput()
    V = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    if isinstance(grid, vtk.vtkPolyData):
        conn = vtk_to_numpy(grid.GetPolys().GetConnectivityArray())
    else:
        conn = vtk_to_numpy(grid.GetCells().GetConnectivityArray())
    return V, conn.reshape(-1, 3)


def k_shell_parts(path):
    """Part id of every *ELEMENT_SHELL line of an LS-DYNA file (comma or fixed-width fields)."""
    pids, section = [], None
    for line in Path(path).read_text().splitlines():
        if line.startswith("*"):
            section = line.strip().upper()
            continue
        if line.startswith("$") or not line.strip():
            continue
        if section == "*ELEMENT_SHELL":
            fields = line.replace(",", " ").split() if "," in line else [line[i:i + 8] for i in range(0, 16, 8)]
            pids.append(int(fields[1]))
    return np.array(pids)


@pytest.mark.parametrize("ext", ["vtk", "k", "stl", "obj"])
def test_cli_tessellate_writes_every_format(hx, hexdom_bin, tmp_path, ext):
    path = step_part("s11o_cube_cyl.stp")
    out = tmp_path / f"surface.{ext}"
    r = subprocess.run([hexdom_bin, "tessellate", path, "-o", out, "--size", "2"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert out.exists()
    lines = dict(line.split(":", 1) for line in r.stdout.splitlines() if ":" in line)
    assert lines["closed 2-manifold"].strip() == "yes"
    assert "min angle" in lines and "planar faces" in lines["min angle"]
    triangles = int(lines["triangles"])
    V, F, face_id = hx.tessellate_file(os.fspath(path), size=2.0)
    assert triangles == len(F)
    if ext == "vtk":
        Vv, Fv = read_vtk_triangles(out)
        assert len(Fv) == triangles
        assert divergence_volume(Vv, Fv) == pytest.approx(divergence_volume(V, F), rel=1e-6)
    if ext == "k":
        pids = k_shell_parts(out)
        assert len(pids) == triangles
        assert sorted(set(pids.tolist())) == list(range(1, hx.cad_info(os.fspath(path))["faces"] + 1))


def test_cli_options_reach_the_mesher(hx, hexdom_bin, tmp_path):
    path = step_part("s15o_cylinder.stp")
    counts = []
    for size in ("3", "1.5"):
        out = tmp_path / f"c{size}.stl"
        r = subprocess.run([hexdom_bin, "tessellate", path, "-o", out, "--size", size, "--deflection", "0.5",
                            "--angle", "45"], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        counts.append(int(dict(x.split(":", 1) for x in r.stdout.splitlines() if ":" in x)["triangles"]))
    assert counts[1] > 3 * counts[0]


@pytest.mark.parametrize("case", ["missing", "corrupt", "not_a_solid", "bad_solid_index", "bad_output_type",
                                  "bad_size"])
def test_cli_bad_input_exits_1_and_writes_nothing(hx, hexdom_bin, tmp_path, case):
    out = tmp_path / "out.k"
    args = [hexdom_bin, "tessellate"]
    expect = None
    if case == "missing":
        args += [tmp_path / "missing.step", "-o", out]
        expect = "missing.step: cannot open file"
    elif case == "corrupt":
        bad = tmp_path / "corrupt.stp"
        bad.write_text("garbage\n" * 10)
        args += [bad, "-o", out]
        expect = "corrupt.stp"
    elif case == "not_a_solid":
        # A wireframe: a BREP file with one edge.
        wire = tmp_path / "edge.brep"
        wire.write_text(EDGE_BREP)
        args += [wire, "-o", out]
        expect = "no solid"
    elif case == "bad_solid_index":
        args += [step_part("s15o_cylinder.stp"), "-o", out, "--solid", "2"]
        expect = "solid 2 requested"
    elif case == "bad_output_type":
        out = tmp_path / "out.xyz"
        args += [step_part("s15o_cylinder.stp"), "-o", out]
        expect = "out.xyz"
    elif case == "bad_size":
        args += [step_part("s15o_cylinder.stp"), "-o", out, "--size", "0.0001"]
        expect = "triangles"
    r = subprocess.run(args, capture_output=True, text=True)
    assert r.returncode == 1, r.stderr
    assert r.stderr.startswith("hexdom: error: "), r.stderr
    assert expect in r.stderr
    assert not out.exists()
    assert list(tmp_path.glob("out*")) == []


# One straight edge from (0,0,0) to (1,0,0): FreeCAD's Part.makeLine(...).exportBrepToString().
EDGE_BREP = ("\nCASCADE Topology V1, (c) Matra-Datavision\nLocations 0\nCurve2ds 0\nCurves 1\n1 0 0 0 1 0 0 \n"
             "Polygon3D 0\nPolygonOnTriangulations 0\nSurfaces 0\nTriangulations 0\n\nTShapes 3\nVe\n1e-07\n"
             "0 0 0\n0 0\n\n0101101\n*\nVe\n1e-07\n1 0 0\n0 0\n\n0101101\n*\nEd\n 1e-07 1 1 0\n"
             "1  1 0 0 1\n0\n\n1101000\n+3 0 -2 0 *\n\n+1 0 ")
