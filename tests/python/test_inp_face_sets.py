"""`hexdom mesh PART -o mesh.inp` names the CAD faces: a node set and an element surface Face<k> per
FreeCAD face, usable by CalculiX as FreeCAD's own set-up uses them (*BOUNDARY on one face's nodes,
*DSLOAD on another's surface).

Oracles: FreeCAD makes the box and numbers its faces (Face1 at x = 0, Face2 at x = 40, ...);
meshio reads the .inp and its node sets; CalculiX solves, and the reaction on the fixed face must
balance the pressure times the loaded face's area (equilibrium), first and second order."""

import re
import shutil
import subprocess

import meshio
import numpy as np
import pytest


@pytest.fixture(scope="module")
def box_step(freecad, tmp_path_factory):
    FreeCAD, Part = freecad
    path = tmp_path_factory.mktemp("box") / "box.step"
    box = Part.makeBox(40, 20, 10)
    assert abs(box.Faces[0].Surface.Position.x) < 1e-12 and abs(box.Faces[1].Surface.Position.x - 40) < 1e-12
    box.exportStep(str(path))
    return path


@pytest.mark.parametrize("order", [1, 2])
def test_face_sets_hold_the_face_nodes_and_calculix_loads_them(hexdom_bin, box_step, tmp_path, order):
    out = tmp_path / "box.inp"
    r = subprocess.run([str(hexdom_bin), "mesh", str(box_step), "-o", str(out), "--size", "4", "--order", str(order)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    text = out.read_text()
    for k in range(1, 7):
        assert f"*NSET, NSET=Face{k}\n" in text and f"*SURFACE, NAME=Face{k}, TYPE=ELEMENT\n" in text
    m = meshio.read(out)
    axis_of = {1: (0, 0.0), 2: (0, 40.0), 3: (1, 0.0), 4: (1, 20.0), 5: (2, 0.0), 6: (2, 10.0)}
    for k, (axis, value) in axis_of.items():
        on_face = set(np.flatnonzero(np.abs(m.points[:, axis] - value) < 1e-9).tolist())
        assert set(m.point_sets[f"Face{k}"].tolist()) == on_face, k

    if shutil.which("ccx") is None:
        pytest.skip("ccx (calculix-ccx) not installed")
    job = tmp_path / "job.inp"
    job.write_text("*INCLUDE, INPUT=box.inp\n*MATERIAL, NAME=STEEL\n*ELASTIC\n210000, 0.3\n"
                   "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n*STEP\n*STATIC\n*BOUNDARY\nFace1, 1, 3\n"
                   "*DSLOAD\nFace2, P, -2.0\n*NODE PRINT, NSET=Face1, TOTALS=ONLY\nRF\n*END STEP\n")
    run = subprocess.run(["ccx", "job"], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout[-2000:]
    dat = (tmp_path / "job.dat").read_text()
    match = re.search(r"total force \(fx,fy,fz\) for set FACE1 and time\s+\S+\s+(\S+)\s+(\S+)\s+(\S+)", dat)
    assert match, dat
    force = np.array([float(v) for v in match.groups()])
    # A pull of 2 on the 20 x 10 face at x = 40: the support at x = 0 holds -400 along x.
    np.testing.assert_allclose(force, [-400.0, 0.0, 0.0], atol=1e-6)


FACE_PLANES = {1: (0, 0.0, 200.0), 2: (0, 40.0, 200.0), 3: (1, 0.0, 400.0), 4: (1, 20.0, 400.0),
               5: (2, 0.0, 800.0), 6: (2, 10.0, 800.0)}  # FreeCAD face: (axis, value, area)


@pytest.mark.parametrize("order", [1, 2])
def test_msh_has_a_physical_group_per_cad_face(hexdom_bin, box_step, tmp_path, order):
    """The .msh: Gmsh (python3-gmsh) lists a physical group Face<k> per FreeCAD face, 2D elements
    on that face only and covering it (their areas add up to the face's), together every boundary
    face of the volume once; and the volume groups hold every cell (meshio agrees)."""
    gmsh = pytest.importorskip("gmsh")
    out = tmp_path / "box.msh"
    r = subprocess.run([str(hexdom_bin), "mesh", str(box_step), "-o", str(out), "--size", "4", "--order", str(order)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    gmsh.initialize()
    gmsh.option.setNumber("General.Verbosity", 1)
    try:
        gmsh.open(str(out))
        groups = {(d, gmsh.model.getPhysicalName(d, t)): t for d, t in gmsh.model.getPhysicalGroups()}
        assert {name for d, name in groups if d == 2} == {f"Face{k}" for k in range(1, 7)}
        faces, cells = 0, 0
        for (dim, name), tag in groups.items():
            for entity in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
                types, _, node_tags = gmsh.model.mesh.getElements(dim, entity)
                for t, nodes in zip(types, node_tags):
                    _, _, _, n, _, _ = gmsh.model.mesh.getElementProperties(t)
                    corners = 4 if t in (3, 16) else 3 if t in (2, 9) else None
                    elements = np.asarray(nodes).reshape(-1, n)
                    if dim == 3:
                        cells += len(elements)
                        continue
                    faces += len(elements)
                    axis, value, area = FACE_PLANES[int(name[4:])]
                    xyz = np.array([gmsh.model.mesh.getNode(int(v))[0] for v in elements[:, :corners].ravel()])
                    assert np.abs(xyz[:, axis] - value).max() < 1e-9, name
                    P = xyz.reshape(len(elements), corners, 3)
                    q = (np.cross(P[:, 2] - P[:, 0], P[:, 3] - P[:, 1]) if corners == 4
                         else np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]))
                    assert 0.5 * np.linalg.norm(q, axis=1).sum() == pytest.approx(area, rel=1e-9), name
    finally:
        gmsh.finalize()
    m = meshio.read(out)
    volume_cells = sum(len(c.data) for c in m.cells if c.type.startswith(("hexahedron", "wedge", "tetra")))
    assert cells == volume_cells > 0
    # Every boundary face of the volume is in exactly one group: count faces used by one hex.
    hexes = np.concatenate([c.data[:, :8] for c in m.cells if c.type.startswith("hexahedron")])
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    keys = [tuple(sorted(h[list(q)])) for h in hexes for q in quads]
    _, counts = np.unique(np.array(keys), axis=0, return_counts=True)
    assert faces == int((counts == 1).sum())


@pytest.mark.parametrize("order", [1, 2])
def test_core_face_sets_are_the_nodes_on_each_face(freecad, tmp_path, order):
    """core.face_sets (the workbench's FEM groups): for each FreeCAD face of the box, exactly the
    mesh nodes on its plane, mid-edge nodes included at order 2."""
    from hexdom_test_support import load_core
    core = load_core()
    if not core._hexdom.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")
    FreeCAD, Part = freecad
    run = core.mesh_part(Part.makeBox(40, 20, 10).exportBrepToString(), size=4, order=order)
    sets = core.face_sets(run.mesh, run.surface)
    assert sorted(sets) == [1, 2, 3, 4, 5, 6]
    P = np.asarray(run.mesh.V)
    for k, (axis, value, _) in FACE_PLANES.items():
        on_face = np.flatnonzero(np.abs(P[:, axis] - value) < 1e-9)
        assert sets[k].tolist() == on_face.tolist(), k
    assert core.face_sets(run.mesh, None) == {}


@pytest.mark.parametrize("order", [1, 2])
def test_vtu_boundary_faces_carry_their_cad_face(hexdom_bin, box_step, tmp_path, order):
    """`--boundary-faces` on a .vtu: after the volume cells VTK reads quads (quad8 at order 2) with a
    face_id array; the quads of face k lie on its plane and their areas (vtkCellSizeFilter) add up
    to FreeCAD's area of the face; the volume cells are those of the plain .vtu; the program
    reads the file back as the volume mesh alone."""
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    plain, faces = tmp_path / "plain.vtu", tmp_path / "faces.vtu"
    for out, extra in ((plain, []), (faces, ["--boundary-faces"])):
        r = subprocess.run([str(hexdom_bin), "mesh", str(box_step), "-o", str(out), "--size", "4", "--order", str(order),
                            *extra], capture_output=True, text=True, timeout=300)
        assert r.returncode == 0, r.stderr
    volumes = meshio.read(plain).cells
    m = meshio.read(faces)
    assert [(c.type, len(c.data)) for c in m.cells[:len(volumes)]] == [(c.type, len(c.data)) for c in volumes]
    quad = "quad" if order == 1 else "quad8"
    assert [c.type for c in m.cells[len(volumes):]] == [quad]
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(faces))
    reader.Update()
    g = reader.GetOutput()
    face_id = vtk_to_numpy(g.GetCellData().GetArray("face_id"))
    sizes = vtk.vtkCellSizeFilter()
    sizes.SetInputData(g)
    sizes.Update()
    area = vtk_to_numpy(sizes.GetOutput().GetCellData().GetArray("Area"))
    P = vtk_to_numpy(g.GetPoints().GetData())
    n_volumes = sum(len(c.data) for c in volumes)
    assert not face_id[:n_volumes].any()
    for k, (axis, value, face_area) in FACE_PLANES.items():
        cells = np.flatnonzero(face_id == k)
        assert len(cells) > 0 and cells.min() >= n_volumes, k
        for c in cells:
            cell = g.GetCell(int(c))
            ids = [cell.GetPointId(j) for j in range(cell.GetNumberOfPoints())]
            assert np.all(np.abs(P[ids, axis] - value) < 1e-9), (k, c)
        assert area[cells].sum() == pytest.approx(face_area, rel=1e-9), k
    assert len(face_id) == n_volumes + sum(len(np.flatnonzero(face_id == k)) for k in FACE_PLANES)
    r = subprocess.run([str(hexdom_bin), "quality", "-i", str(faces)], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines()[1].split()[:2] == ["hex", str(n_volumes)], r.stdout


def _k_segment_sets(path):
    """{title: (set id, [(n1, n2, n3, n4), ...])} of the *SET_SEGMENT_TITLE blocks of an LS-DYNA .k
    (fixed 10-character fields), and {node id: (x, y, z)} of its *NODE lines (comma format)."""
    sets, nodes, block, title = {}, {}, None, None
    for line in open(path):
        line = line.rstrip("\n")
        if not line or line.startswith("$"):
            continue
        if line.startswith("*"):
            block, title = line[1:].strip().upper(), None
            continue
        if block == "NODE":
            i, x, y, z = line.split(",")
            nodes[int(i)] = (float(x), float(y), float(z))
        elif block == "SET_SEGMENT_TITLE":
            if title is None:
                title = line.strip()
            elif title not in sets:
                sets[title] = (int(line[:10]), [])
            else:
                sets[title][1].append(tuple(int(line[10 * j:10 * j + 10]) for j in range(4)))
    return sets, nodes


def test_k_has_a_segment_set_per_cad_face(hexdom_bin, box_step, tmp_path):
    """The .k: a *SET_SEGMENT_TITLE Face<k> (set id k) per FreeCAD face, whose quads lie on its
    plane, turn their normal out of the box and cover its area; the program still reads the file."""
    out = tmp_path / "box.k"
    r = subprocess.run([str(hexdom_bin), "mesh", str(box_step), "-o", str(out), "--size", "4"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    sets, nodes = _k_segment_sets(out)
    assert sorted(sets) == [f"Face{k}" for k in range(1, 7)]
    for k, (axis, value, face_area) in FACE_PLANES.items():
        sid, segments = sets[f"Face{k}"]
        assert sid == k and segments
        outward = 1.0 if value > 0 else -1.0
        total = 0.0
        for seg in segments:
            P = np.array([nodes[n] for n in seg])
            assert np.all(np.abs(P[:, axis] - value) < 1e-9), (k, seg)
            normal = 0.5 * (np.cross(P[1] - P[0], P[2] - P[0]) + np.cross(P[2] - P[0], P[3] - P[0]))
            assert normal[axis] * outward > 0, (k, seg)
            total += np.linalg.norm(normal)
        assert total == pytest.approx(face_area, rel=1e-9), k
    r = subprocess.run([str(hexdom_bin), "quality", "-i", str(out)], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
