"""`hexdom mesh` on a CAD file with several solids: each solid meshed, its cells in region k for
solid k, every region filling its solid (volumes by VTK's vtkCellSizeFilter against FreeCAD's);
--solid N meshes one; solids that touch are meshed with a warning that the meshes do not conform
where they meet. The parts are made here with FreeCAD (boxes and a cylinder)."""

import re
import subprocess

import meshio
import numpy as np
import pytest

import hexdom_oracles as oracles


def _step(freecad, path, shapes):
    FreeCAD, Part = freecad
    Part.makeCompound(shapes).exportStep(str(path))
    return path


def _mesh(hexdom_bin, src, out, *extra):
    return subprocess.run([str(hexdom_bin), "mesh", str(src), "-o", str(out), "--size", "4", *extra],
                          capture_output=True, text=True, timeout=300)


def _region_volumes(path):
    g = oracles.read_vtu(path)
    vol = oracles.signed_volumes(g)
    region = np.ravel(meshio.read(path).cell_data["region"][0])
    assert vol.min() > 0
    return {int(r): float(vol[region == r].sum()) for r in np.unique(region)}


@pytest.fixture(scope="module")
def parts(freecad, tmp_path_factory):
    FreeCAD, Part = freecad
    d = tmp_path_factory.mktemp("solids")
    V = FreeCAD.Vector
    apart = [Part.makeBox(20, 10, 10), Part.makeCylinder(6, 15, V(40, 5, 0))]
    touching = [Part.makeBox(20, 10, 10), Part.makeBox(10, 10, 10, V(20, 0, 0))]
    return {"apart": (_step(freecad, d / "apart.step", apart), [s.Volume for s in apart]),
            "touching": (_step(freecad, d / "touching.step", touching), [s.Volume for s in touching])}


def test_every_solid_is_meshed_in_its_own_region(hexdom_bin, parts, tmp_path):
    step, volumes = parts["apart"]
    out = tmp_path / "apart.vtu"
    r = _mesh(hexdom_bin, step, out)
    assert r.returncode == 0, r.stderr
    assert "holds 2 solids: each is meshed" in r.stderr
    assert "touch" not in r.stderr
    got = _region_volumes(out)
    assert sorted(got) == [1, 2]
    for k, v in enumerate(volumes, start=1):
        assert got[k] == pytest.approx(v, rel=0.01), (k, got[k], v)
    # The printed reference is both solids' B-rep volume.
    assert f"B-rep volume {sum(volumes):.4f}"[:22] in r.stdout, r.stdout


def test_solid_option_meshes_only_that_one(hexdom_bin, parts, tmp_path):
    step, volumes = parts["apart"]
    out = tmp_path / "second.vtu"
    r = _mesh(hexdom_bin, step, out, "--solid", "2")
    assert r.returncode == 0, r.stderr
    assert "holds 2 solids" not in r.stderr
    g = oracles.read_vtu(out)
    assert oracles.signed_volumes(g).sum() == pytest.approx(volumes[1], rel=0.01)
    # Its faces keep the numbers FreeCAD gives them in the whole file: the cylinder's are Face7..Face9.
    inp = tmp_path / "second.inp"
    r = _mesh(hexdom_bin, step, inp, "--solid", "2", "--face-size", "7=3")
    assert r.returncode == 0, r.stderr
    assert sorted(k for k in meshio.read(inp).point_sets if k.startswith("Face")) == ["Face7", "Face8", "Face9"]
    r = _mesh(hexdom_bin, step, inp, "--solid", "2", "--face-size", "1=3")
    assert r.returncode == 1 and "Face1, which is not a face of the solid meshed (Face7, Face8, Face9)" in r.stderr


def test_touching_solids_are_meshed_with_a_warning(hexdom_bin, parts, tmp_path):
    step, volumes = parts["touching"]
    out = tmp_path / "touching.vtu"
    r = _mesh(hexdom_bin, step, out)
    assert r.returncode == 0, r.stderr
    assert "warning: solids 1 and 2 touch: their meshes are made one by one and do not conform" in r.stderr
    got = _region_volumes(out)
    for k, v in enumerate(volumes, start=1):
        assert got[k] == pytest.approx(v, rel=0.01)


def test_second_order_solids_are_put_together_too(hexdom_bin, parts, tmp_path):
    step, volumes = parts["apart"]
    out = tmp_path / "apart2.vtu"
    r = _mesh(hexdom_bin, step, out, "--order", "2")
    assert r.returncode == 0, r.stderr
    m = meshio.read(out)
    assert [c.type for c in m.cells] == ["hexahedron20"]
    region = np.ravel(m.cell_data["region"][0])
    assert sorted(set(region.tolist())) == [1, 2]
    # Each solid's nodes are its own: no cell of region 1 shares a node with one of region 2.
    cells = m.cells[0].data
    assert not set(cells[region == 1].ravel()) & set(cells[region == 2].ravel())


def test_face_sets_of_several_solids_are_numbered_as_freecad_numbers_the_compound(freecad, hexdom_bin, parts,
                                                                                  tmp_path):
    """The .inp's Face<k> node sets follow FreeCAD's Face<k> of the whole STEP (box 1-6, cylinder 7-9):
    every node of each set lies on that face of the compound FreeCAD reads (the snap's faces of each
    node: also where a boundary quad of the overlay straddles the cylinder's rim, which before put
    its cap node in the side's set) and far from the other solid, and a size given on the cylinder's
    Face7 refines the cylinder's cells only."""
    FreeCAD, Part = freecad
    step, _ = parts["apart"]
    compound = Part.read(str(step))
    assert len(compound.Faces) == 9
    out = tmp_path / "apart.inp"
    r = _mesh(hexdom_bin, step, out)
    assert r.returncode == 0, r.stderr
    other = {k: Part.Compound(compound.Solids[1 if k <= 6 else 0].Faces) for k in range(1, 10)}

    def check_sets(path):
        m = meshio.read(path)
        for k in range(1, 10):
            nodes = m.point_sets[f"Face{k}"]
            assert len(nodes) > 4, k
            points = [Part.Vertex(FreeCAD.Vector(*map(float, m.points[i]))) for i in nodes]
            on = np.array([compound.Faces[k - 1].distToShape(p)[0] for p in points])
            assert (on < 1e-6).all(), (path.name, k, int((on >= 1e-6).sum()), len(on), on.max())
            assert min(other[k].distToShape(p)[0] for p in points) > 5, k
        assert "Face10" not in m.point_sets

    check_sets(out)

    def figures(path):  # (cells of the box, nodes of Face7)
        m = meshio.read(path)
        return sum(len(c) for c in m.cell_sets["REGION_1"]), len(m.point_sets["Face7"])

    plain, sized = tmp_path / "plain.inp", tmp_path / "sized.inp"
    for path, extra in ((plain, []), (sized, ["--face-size", "7=0.5"])):
        r = _mesh(hexdom_bin, step, path, "--method", "overlay", *extra)
        assert r.returncode == 0, r.stderr
        if path == plain:
            said = re.search(r"faces: (\d+) of (\d+) boundary faces", r.stderr)
    check_sets(plain)  # the overlay's (38 of 3088 nodes off their face before)
    # The boundary quads whose corners lie on no one face of the compound (FreeCAD's distToShape):
    # the count the program says cross a CAD edge.
    m = meshio.read(plain)
    hexes = np.concatenate([c.data for c in m.cells if c.type == "hexahedron"])
    local = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    count = {}
    for q in hexes[:, local].reshape(-1, 4):
        key = tuple(sorted(q))
        count[key] = count.get(key, 0) + 1
    quads = [k for k, c in count.items() if c == 1]
    used = sorted({n for q in quads for n in q})
    on = {n: {k for k, f in enumerate(compound.Faces)
              if f.distToShape(Part.Vertex(FreeCAD.Vector(*map(float, m.points[n]))))[0] < 1e-6} for n in used}
    crossing = sum(1 for q in quads if not set.intersection(*(on[n] for n in q)))
    assert crossing > 0 and said and int(said.group(1)) == crossing and int(said.group(2)) == len(quads), (
        crossing, len(quads), said and said.group(0))
    (box_before, face_before), (box_after, face_after) = figures(plain), figures(sized)
    assert box_after == box_before and face_after > 3 * face_before, (figures(plain), figures(sized))
    r = _mesh(hexdom_bin, step, tmp_path / "none.vtu", "--face-size", "10=1")
    assert r.returncode == 1 and "Face10" in r.stderr and not (tmp_path / "none.vtu").exists()


def test_core_meshes_every_solid_of_a_brep_numbered_as_freecad(freecad, parts):
    """_hexdom.mesh_cad through HexDomWorkbench.core.mesh_part, on the BREP text FreeCAD exports for a
    compound (what the workbench's Mesh Part hands over): both solids meshed in regions 1 and 2, the
    tessellation's face ids FreeCAD's Face1..Face9 of the compound (each triangle's corners on that
    face), the snap's face nodes on the face its entity names; touching solids listed."""
    from hexdom_test_support import load_core
    core = load_core()
    if not core._hexdom.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")
    FreeCAD, Part = freecad
    compound = Part.read(str(parts["apart"][0]))
    run = core.mesh_part(compound.exportBrepToString(), size=4)
    assert run.solids == 2 and run.touching == []
    region = np.asarray(run.mesh.region)
    assert sorted(set(region.tolist())) == [1, 2]
    assert run.quality["total_volume"] == pytest.approx(sum(s.Volume for s in compound.Solids), rel=0.01)
    V, F, face_id = np.asarray(run.surface.V), np.asarray(run.surface.F), np.asarray(run.surface.patch)
    assert sorted(set(face_id.tolist())) == list(range(1, 10))
    for t in range(0, len(F), 11):
        face = compound.Faces[int(face_id[t]) - 1]
        for v in F[t]:
            assert face.distToShape(Part.Vertex(FreeCAD.Vector(*map(float, V[v]))))[0] < 1e-6, (t, face_id[t])
    kind, entity = np.asarray(run.snap["kind"]), np.asarray(run.snap["entity"])
    P = np.asarray(run.mesh.V)
    assert len(kind) == len(P)
    for v in np.flatnonzero(kind == 1)[::13]:
        face = compound.Faces[int(entity[v]) - 1]
        assert face.distToShape(Part.Vertex(FreeCAD.Vector(*map(float, P[v]))))[0] < 1e-6, (v, entity[v])
    touching = Part.read(str(parts["touching"][0]))
    assert core.mesh_part(touching.exportBrepToString(), size=4).touching == [(1, 2)]
