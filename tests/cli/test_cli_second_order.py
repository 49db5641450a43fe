"""Second-order elements (`hexdom mesh --order 2`): hex20 / wedge15 / tet10 in VTK's quadratic node
order, written to .vtk, .vtu and .inp (C3D20 / C3D15 / C3D10), the boundary's mid-edge nodes on
the B-rep.

Oracles: meshio reads every file; VTK's own quadratic shape functions
(vtkQuadraticHexahedron.InterpolateDerivs) give the curved cells' Jacobians and volumes; FreeCAD's
distToShape measures the mid-edge nodes' distance to the B-rep; CalculiX solves the .inp."""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import hexdom_oracles as oracles

BRACKET = Path(__file__).resolve().parents[2] / "examples" / "data" / "bracket.step"


@pytest.fixture(scope="module")
def freecad_part():
    """(FreeCAD, Part), FreeCAD's modules as /usr/bin/python3 finds them, or a skip."""
    for p in ("/usr/lib/freecad-python3/lib", "/usr/share/freecad/Mod", "/usr/share/freecad/Ext"):
        if p not in sys.path:
            sys.path.append(p)
    try:
        import FreeCAD
        import Part
    except ImportError as e:
        pytest.skip(f"FreeCAD not importable: {e}")
    return FreeCAD, Part


def _run(hexdom_bin, *args):
    return subprocess.run([str(hexdom_bin), *map(str, args)], capture_output=True, text=True)


@pytest.fixture(scope="module")
def bracket(hexdom_bin, tmp_path_factory):
    """The bundled bracket meshed at order 1 (.vtu, .inp) and order 2 (.vtu, .vtk, .inp, report)."""
    d = tmp_path_factory.mktemp("second_order")
    out = {}
    for order, names in ((1, ("vtu", "inp")), (2, ("vtu", "vtk", "inp"))):
        for ext in names:
            path = d / f"bracket{order}.{ext}"
            args = ["mesh", BRACKET, "-o", path, "--order", order]
            if order == 2 and ext == "vtu":
                args += ["--report", d / "report2.json"]
            r = _run(hexdom_bin, *args)
            assert r.returncode == 0, r.stderr
            out[(order, ext)] = path
            out[("log", order, ext)] = r.stderr + r.stdout
    out["report"] = json.loads((d / "report2.json").read_text())
    out["dir"] = d
    return out


def test_every_format_holds_the_second_order_cells_on_the_first_order_corners(bracket):
    import meshio
    first = meshio.read(bracket[(1, "vtu")])
    n1 = len(first.points)
    hexes = first.cells_dict["hexahedron"]
    for ext in ("vtu", "vtk", "inp"):
        m = meshio.read(bracket[(2, ext)])
        assert list(m.cells_dict) == ["hexahedron20"], (ext, list(m.cells_dict))
        h20 = m.cells_dict["hexahedron20"]
        assert h20.shape == (len(hexes), 20)
        # The corners are the first-order mesh's nodes, in its numbering; the mid-edge nodes follow.
        assert np.array_equal(h20[:, :8], hexes), ext
        assert np.abs(m.points[:n1] - first.points).max() <= 1e-12 * np.abs(first.points).max(), ext
        assert h20[:, 8:].min() >= n1
        # One node per mesh edge, shared by the cells around it.
        edges = {tuple(sorted((a, b))) for c in hexes for a, b in ((c[i], c[j]) for i, j in oracles.HEX_EDGES)}
        assert len(m.points) == n1 + len(edges), ext
        for k, (i, j) in enumerate(oracles.HEX_EDGES):
            key = np.sort(hexes[:, [i, j]], axis=1)
            ids = h20[:, 8 + k]
            # the same edge always gets the same node
            seen = {}
            for e, v in zip(map(tuple, key), ids):
                assert seen.setdefault(e, v) == v
    r = bracket["report"]
    assert r["order"] == 2 and r["hex20"]["count"] == len(hexes) and r["hex20"]["inverted"] == 0
    # VTK's own readers: quadratic hexahedra (25) of 20 points, the same connectivity.
    import vtk
    for reader, ext in ((vtk.vtkXMLUnstructuredGridReader(), "vtu"), (vtk.vtkUnstructuredGridReader(), "vtk")):
        reader.SetFileName(str(bracket[(2, ext)]))
        reader.Update()
        g = reader.GetOutput()
        assert g.GetNumberOfCells() == len(hexes) and g.GetNumberOfPoints() == len(m.points), ext
        assert {g.GetCellType(c) for c in range(g.GetNumberOfCells())} == {vtk.VTK_QUADRATIC_HEXAHEDRON}, ext
        ids = g.GetCell(7).GetPointIds()
        assert [ids.GetId(i) for i in range(ids.GetNumberOfIds())] == h20[7].tolist(), ext


def _vtk_hex20_jacobians(points, cells):
    """det J at the 27 Gauss points of each hex20 (VTK's quadratic shape functions on [0, 1]^3)
    and the Gauss weights (times 1/8 of [-1, 1]^3's)."""
    import vtk
    g = np.sqrt(0.6)
    x = [(1 - g) / 2, 0.5, (1 + g) / 2]
    w = [5 / 18, 8 / 18, 5 / 18]
    cell = vtk.vtkQuadraticHexahedron()
    dets, weights = [], []
    derivs = [0.0] * 60
    for i in range(3):
        for j in range(3):
            for k in range(3):
                cell.InterpolateDerivs([x[i], x[j], x[k]], derivs)
                D = np.array(derivs).reshape(3, 20)  # d/dr, d/ds, d/dt of the 20 functions
                J = np.einsum("cnk,dn->cdk", points[cells], D)  # (#C, 3 derivatives, 3 coordinates)
                dets.append(np.linalg.det(J))
                weights.append(w[i] * w[j] * w[k])
    return np.array(dets).T, np.array(weights)


def test_vtk_s_quadratic_hexahedron_gives_the_reported_volume_and_no_fold(bracket):
    import meshio
    m = meshio.read(bracket[(2, "vtu")])
    dets, weights = _vtk_hex20_jacobians(m.points, m.cells_dict["hexahedron20"])
    assert dets.min() > 0
    volume = (dets * weights).sum()
    r = bracket["report"]
    assert volume == pytest.approx(r["total_volume"], rel=1e-9)
    # The curved cells close most of the chords' volume deficit on the hole and the fillet.
    brep = float(bracket[("log", 2, "vtu")].split("B-rep volume ")[1].split()[0])
    first = meshio.read(bracket[(1, "vtu")])
    d1, w1 = _vtk_hex20_jacobians(*_straight_hex20(first.points, first.cells_dict["hexahedron"]))
    v1 = (d1 * w1).sum()
    print(f"bracket: B-rep {brep:.6f}, first order {v1:.6f} ({(v1 - brep) / brep:+.4%}), "
          f"second order {volume:.6f} ({(volume - brep) / brep:+.4%})")
    assert abs(volume - brep) < 0.1 * abs(v1 - brep)


def _straight_hex20(points, hexes):
    """A first-order mesh as hex20 cells with their mid-edge nodes at the midpoints."""
    mids = np.stack([(points[hexes[:, i]] + points[hexes[:, j]]) / 2 for i, j in oracles.HEX_EDGES], axis=1)
    P = np.concatenate([points, mids.reshape(-1, 3)])
    cells = np.concatenate([hexes, len(points) + np.arange(12 * len(hexes)).reshape(-1, 12)], axis=1)
    return P, cells


def test_the_boundary_s_mid_edge_nodes_lie_on_the_brep(bracket, freecad_part):
    import meshio
    FreeCAD, Part = freecad_part
    m = meshio.read(bracket[(2, "vtu")])
    h20 = m.cells_dict["hexahedron20"]
    faces = {}
    for c, cell in enumerate(h20):
        for f in oracles.HEX_FACES:
            key = tuple(sorted(cell[list(f)]))
            faces[key] = faces.get(key, 0) + 1
    boundary = {k for k, n in faces.items() if n == 1}
    mids = set()
    for cell in h20:
        for k, (i, j) in enumerate(oracles.HEX_EDGES):
            for f in oracles.HEX_FACES:
                if i in f and j in f and tuple(sorted(cell[list(f)])) in boundary:
                    mids.add(int(cell[8 + k]))
    shape = Part.read(str(BRACKET)).Solids[0]
    diag = shape.BoundBox.DiagonalLength
    faces_shape = Part.Compound(shape.Faces)
    d = np.array([faces_shape.distToShape(Part.Vertex(FreeCAD.Vector(*map(float, m.points[v]))))[0] for v in mids])
    log = bracket[("log", 2, "vtu")]
    print(f"bracket: {len(mids)} boundary mid-edge nodes, B-rep distance max {d.max() / diag:.2e} x diagonal")
    assert f"second order: {len(mids)} boundary mid-edge nodes" in log, log
    assert d.max() <= 1e-7 * diag


def _solve(inp, work):
    """CalculiX on the mesh of ``inp``: the base's bottom (z = 0) fixed, 100 N along x spread over
    the upright's top (z = 50); the largest x displacement."""
    import meshio
    P = meshio.read(inp).points
    fixed = np.flatnonzero(np.abs(P[:, 2]) < 1e-6) + 1
    top = np.flatnonzero(np.abs(P[:, 2] - 50) < 1e-6) + 1
    deck = Path(inp).read_text().replace("*NODE\n", "*NODE, NSET=NALL\n", 1)
    deck += ("*NSET, NSET=FIXED\n" + "".join(f"{i},\n" for i in fixed) +
             "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000, 0.3\n*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n"
             "*STEP\n*STATIC\n*BOUNDARY\nFIXED, 1, 3, 0.\n*CLOAD\n" +
             "".join(f"{i}, 1, {100.0 / len(top)!r}\n" for i in top) + "*NODE PRINT, NSET=NALL\nU\n*END STEP\n")
    work.mkdir()
    (work / "job.inp").write_text(deck)
    r = subprocess.run(["ccx", "job"], cwd=work, capture_output=True, text=True)
    assert r.returncode == 0 and "Job finished" in r.stdout, r.stdout[-2000:]
    U = []
    for line in (work / "job.dat").read_text().splitlines():
        f = line.split()
        if len(f) == 4 and f[0].isdigit():
            U.append([float(v) for v in f[1:]])
    assert len(U) == len(P)
    return np.abs(np.array(U)[:, 0]).max()


@pytest.mark.skipif(not any((Path(p) / "ccx").exists() for p in os.environ.get("PATH", "").split(os.pathsep)),
                    reason="CalculiX (ccx) is not installed")
def test_calculix_solves_the_c3d20_mesh(bracket):
    u1 = _solve(bracket[(1, "inp")], bracket["dir"] / "ccx1")
    u2 = _solve(bracket[(2, "inp")], bracket["dir"] / "ccx2")
    print(f"bracket upright, 100 N at its top: C3D8 {u1:.6g} mm, C3D20 {u2:.6g} mm")
    # Fully integrated C3D8 is too stiff in bending; C3D20 bends more, not wildly more.
    assert u1 > 0 and 1.0 < u2 / u1 < 1.5


def test_quality_and_convert_read_the_second_order_file(bracket, hexdom_bin):
    r = _run(hexdom_bin, "quality", "-i", bracket[(2, "vtk")])
    assert r.returncode == 0, r.stderr
    line = next(l for l in r.stdout.splitlines() if l.startswith("hex20"))
    assert float(line.split()[2]) == pytest.approx(bracket["report"]["hex20"]["sj_min"], abs=1e-4)
    out = bracket["dir"] / "converted.inp"
    r = _run(hexdom_bin, "convert", "-i", bracket[(2, "vtk")], "-o", out)
    assert r.returncode == 0, r.stderr
    # `hexdom mesh` adds the CAD faces' sets after the mesh; convert has no CAD part to name them by.
    meshed = bracket[(2, "inp")].read_text()
    assert "*NSET, NSET=Face1\n" in meshed and "*NSET, NSET=Face" not in out.read_text()
    assert out.read_text() == meshed[:meshed.index("*NSET, NSET=Face")]


def _k_solids(path):
    """(points by LS-DYNA node id, {keyword: [node id lists]}) of a .k file, read here by LS-DYNA's
    card layout (8-character fields; a 20-node hex on three cards, a ten-node-format tet on two)."""
    points, cells, key, pending = {}, {}, None, None
    for line in Path(path).read_text().splitlines():
        if not line.strip() or line.startswith("$"):
            continue
        if line.startswith("*"):
            key, pending = line.strip(), None
            continue
        if key == "*NODE":
            i, x, y, z = line.split(",")
            points[int(i)] = (float(x), float(y), float(z))
        elif key in ("*ELEMENT_SOLID_H20", "*ELEMENT_SOLID (ten nodes format)"):
            fields = [int(line[k:k + 8]) for k in range(0, len(line), 8)]
            if pending is None:
                assert len(fields) == 2, line  # eid, pid
                pending = []
                continue
            pending += fields
            if len(pending) == (20 if key.endswith("H20") else 10):
                cells.setdefault(key, []).append(pending)
                pending = None
    return points, cells


def test_order_2_into_a_k_file_holds_twenty_node_solids(bracket, hexdom_bin, tmp_path):
    import meshio
    out = tmp_path / "bracket.k"
    r = _run(hexdom_bin, "mesh", BRACKET, "-o", out, "--order", "2")
    assert r.returncode == 0, r.stderr
    points, cells = _k_solids(out)
    m = meshio.read(bracket[(2, "vtu")])
    h20 = m.cells_dict["hexahedron20"]
    assert list(cells) == ["*ELEMENT_SOLID_H20"]
    k = np.array(cells["*ELEMENT_SOLID_H20"]) - 1
    # LS-DYNA's 20-node order is VTK's: the same cells on the same points as the .vtu.
    assert np.array_equal(k, h20)
    xyz = np.array([points[i + 1] for i in range(len(points))])
    assert np.abs(xyz - m.points).max() <= 1e-12 * np.abs(m.points).max()
    # hexdom reads it back: the same second-order quality as the .vtu's.
    q = [_run(hexdom_bin, "quality", "-i", f) for f in (out, bracket[(2, "vtu")])]
    assert q[0].returncode == 0, q[0].stderr
    lines = [next(l for l in x.stdout.splitlines() if l.startswith("hex20")) for x in q]
    assert lines[0] == lines[1]


def test_order_2_wedges_into_a_k_file_or_order_3_are_refused_without_output(hexdom_bin, tmp_path):
    # One 15-node wedge (VTK's type 26): LS-DYNA's keyword has no such element.
    c = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1)]
    edges = [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)]
    pts = c + [tuple((np.add(c[a], c[b]) / 2).tolist()) for a, b in edges]
    src = tmp_path / "wedge15.vtk"
    src.write_text("# vtk DataFile Version 4.2\nwedge15\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 15 double\n"
                   + "".join("{} {} {}\n".format(*p) for p in pts)
                   + "CELLS 1 16\n15 " + " ".join(map(str, range(15))) + "\nCELL_TYPES 1\n26\n")
    out = tmp_path / "wedge.k"
    r = _run(hexdom_bin, "convert", "-i", src, "-o", out)
    assert r.returncode == 1 and "no 15-node pentahedron" in r.stderr and str(out) in r.stderr, r.stderr
    assert not out.exists()
    r = _run(hexdom_bin, "mesh", BRACKET, "-o", tmp_path / "b.vtu", "--order", "3")
    assert r.returncode != 0 and not (tmp_path / "b.vtu").exists()


def _box_stl(path, lx, ly, lz):
    """A closed triangle surface of the box [0, lx] x [0, ly] x [0, lz] (12 triangles, outward)."""
    c = [(lx if i & 1 else 0.0, ly if i & 2 else 0.0, lz if i & 4 else 0.0) for i in range(8)]
    tris = [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4),
            (2, 6, 7), (2, 7, 3), (0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5)]
    lines = ["solid box"]
    for t in tris:
        lines += ["facet normal 0 0 0", "outer loop"] + ["vertex %r %r %r" % c[k] for k in t] + ["endloop", "endfacet"]
    path.write_text("\n".join(lines + ["endsolid box"]) + "\n")
    return path


@pytest.mark.skipif(not any((Path(p) / "ccx").exists() for p in os.environ.get("PATH", "").split(os.pathsep)),
                    reason="CalculiX (ccx) is not installed")
def test_a_hex20_cantilever_bends_as_timoshenko_s_beam(hexdom_bin, tmp_path):
    # 200 x 10 x 10, one end clamped, 100 N across the other: deflection P L^3 / 3EI + P L / (k G A),
    # k = 5/6. Cells of 5 (2 across): C3D20 within 1% (the clamped end's constraint is most of the
    # rest), C3D8 on the same cells far stiffer (shear locking).
    L, h, E, nu, P = 200.0, 10.0, 210000.0, 0.3, 100.0
    exact = P * L ** 3 / (3 * E * h ** 4 / 12) + P * L / (5 / 6 * E / (2 * (1 + nu)) * h * h)
    src = _box_stl(tmp_path / "beam.stl", L, h, h)
    tip = {}
    for order in (1, 2):
        out = tmp_path / f"beam{order}.inp"
        r = _run(hexdom_bin, "mesh", src, "-o", out, "--size", "5", "--order", order)
        assert r.returncode == 0, r.stderr
        import meshio
        X = meshio.read(out).points
        clamped = np.flatnonzero(np.abs(X[:, 0]) < 1e-9) + 1
        end = np.flatnonzero(np.abs(X[:, 0] - L) < 1e-9) + 1
        deck = out.read_text().replace("*NODE\n", "*NODE, NSET=NALL\n", 1)
        deck += ("*NSET, NSET=CLAMPED\n" + "".join(f"{i},\n" for i in clamped) +
                 "*NSET, NSET=TIP\n" + "".join(f"{i},\n" for i in end) +
                 f"*MATERIAL, NAME=STEEL\n*ELASTIC\n{E}, {nu}\n*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n"
                 "*STEP\n*STATIC\n*BOUNDARY\nCLAMPED, 1, 3, 0.\n*CLOAD\n" +
                 "".join(f"{i}, 3, {P / len(end)!r}\n" for i in end) + "*NODE PRINT, NSET=TIP\nU\n*END STEP\n")
        work = tmp_path / f"ccx{order}"
        work.mkdir()
        (work / "job.inp").write_text(deck)
        r = subprocess.run(["ccx", "job"], cwd=work, capture_output=True, text=True)
        assert r.returncode == 0 and "Job finished" in r.stdout, r.stdout[-2000:]
        uz = [float(line.split()[3]) for line in (work / "job.dat").read_text().splitlines()
              if len(line.split()) == 4 and line.split()[0].isdigit()]
        assert len(uz) == len(end)
        tip[order] = float(np.mean(uz))
    print(f"cantilever tip: exact {exact:.5f}, C3D8 {tip[1]:.5f} ({tip[1] / exact - 1:+.2%}), "
          f"C3D20 {tip[2]:.5f} ({tip[2] / exact - 1:+.2%})")
    assert abs(tip[2] / exact - 1) <= 0.01
    assert tip[1] / exact - 1 < -0.05
