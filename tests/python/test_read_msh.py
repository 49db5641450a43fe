"""Gmsh .msh files read by the program (`hexdom convert -i in.msh -o out.vtk`, `hexdom quality`).

Oracle: Gmsh itself (its Python module) meshes a box with tets (two volumes in two physical
groups), a box with hexes (transfinite, recombined), an extruded triangle mesh (prisms, no physical
group: the region is the volume's tag), and the same three in second order (tet10, hex20,
prism15), and writes each as MSH 4.1 and 2.2, ASCII and binary. VTK reads the converted file: its
node count, its cell count per type and the region count per region must be Gmsh's, VTK's signed
cell volumes (vtkCellSizeFilter) must be positive and add up to the box's volume, and the program's
quality report must count no inverted cell."""

import json
import subprocess

import numpy as np
import pytest
import vtk
from vtk.util.numpy_support import vtk_to_numpy

import hexdom_oracles as O

gmsh = pytest.importorskip("gmsh")

# Gmsh element type -> the VTK type the program writes it as.
VTK_OF_GMSH = {4: 10, 5: 12, 6: 13, 11: 24, 17: 25, 18: 26}
VARIANTS = [(4.1, 0), (4.1, 1), (2.2, 0), (2.2, 1)]
KINDS = ["tet", "hex", "prism", "tet10", "hex20", "prism15"]
BOX_VOLUME = {"tet": 2.5, "hex": 3.0, "prism": 3.0}


@pytest.fixture(scope="module")
def gmsh_session():
    gmsh.initialize(readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    yield gmsh
    gmsh.finalize()


def build(kind):
    """Meshes one of KINDS in a new Gmsh model; returns the first-order kind's name."""
    gmsh.clear()
    gmsh.model.add(kind)
    base = {"tet10": "tet", "hex20": "hex", "prism15": "prism"}.get(kind, kind)
    if base == "tet":
        gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
        gmsh.model.occ.addBox(1, 0, 0, 1.5, 1, 1)
        gmsh.model.occ.fragment([(3, 1)], [(3, 2)])
        gmsh.model.occ.synchronize()
        for tag in (1, 2):
            x = gmsh.model.occ.getCenterOfMass(3, tag)[0]
            gmsh.model.addPhysicalGroup(3, [tag], 11 if x < 1 else 12)
        gmsh.option.setNumber("Mesh.MeshSizeMax", 0.35)
    elif base == "hex":
        O.gmsh_structured_box(gmsh, "hex", (2, 1, 1.5), 3)
        gmsh.model.addPhysicalGroup(3, [1], 21)
    else:
        gmsh.option.setNumber("Mesh.MeshSizeMax", 0.4)
        O.gmsh_structured_box(gmsh, "prism", (2, 1, 1.5), 3)
    gmsh.model.mesh.generate(3)
    if kind != base:
        gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)  # hex20 and prism15, not hex27 / prism18
        gmsh.model.mesh.setOrder(2)
    return base


def gmsh_expected():
    """Node count, cell count per VTK type, cell count per region id, of the model in Gmsh."""
    nodes = len(gmsh.model.mesh.getNodes()[0])
    types, regions = {}, {}
    for _, tag in gmsh.model.getEntities(3):
        groups = gmsh.model.getPhysicalGroupsForEntity(3, tag)
        region = int(groups[0]) if len(groups) else tag
        for t, elements, _ in zip(*gmsh.model.mesh.getElements(3, tag)):
            types[VTK_OF_GMSH[int(t)]] = types.get(VTK_OF_GMSH[int(t)], 0) + len(elements)
            regions[region] = regions.get(region, 0) + len(elements)
    return nodes, types, regions


def write_msh(path, version, binary, save_all=0):
    gmsh.option.setNumber("Mesh.MshFileVersion", version)
    gmsh.option.setNumber("Mesh.Binary", binary)
    gmsh.option.setNumber("Mesh.SaveAll", save_all)
    gmsh.write(str(path))


def run(hexdom_bin, *args):
    return subprocess.run([str(hexdom_bin), *map(str, args)], capture_output=True, text=True)


def read_vtk(path):
    g, _ = O.read_legacy_vtk(path)
    region = vtk_to_numpy(g.GetCellData().GetArray("region")).astype(int)
    return g, region


def check_converted(hexdom_bin, msh, tmp_path, expected, volume):
    out = tmp_path / (msh.stem + ".vtk")
    r = run(hexdom_bin, "convert", "-i", msh, "-o", out)
    assert r.returncode == 0, r.stderr
    g, region = read_vtk(out)
    nodes, types, regions = expected
    assert g.GetNumberOfPoints() == nodes
    assert O.cell_type_counts(g) == types
    assert dict(zip(*[v.tolist() for v in np.unique(region, return_counts=True)])) == regions
    vols = O.signed_volumes(g)
    assert vols.min() > 0, f"{(vols <= 0).sum()} cells with VTK volume <= 0"
    assert abs(vols.sum() - volume) <= 1e-9 * volume
    q = run(hexdom_bin, "quality", "-i", msh, "--json")
    assert q.returncode == 0, q.stderr
    report = json.loads(q.stdout)
    keys = ["hex20", "wedge15", "tet10"] if report.get("order") == 2 else ["hex", "prism", "tet"]
    assert sum(report[k]["count"] for k in keys if k in report) == sum(types.values())
    assert all(report[k]["inverted"] == 0 for k in keys if k in report), report
    return g, region


@pytest.mark.parametrize("version,binary", VARIANTS, ids=[f"{v}{'-bin' if b else '-ascii'}" for v, b in VARIANTS])
@pytest.mark.parametrize("kind", KINDS)
def test_gmsh_meshes_convert_with_their_nodes_cells_regions_and_volume(gmsh_session, hexdom_bin, tmp_path, kind,
                                                                       version, binary):
    base = build(kind)
    expected = gmsh_expected()
    msh = tmp_path / f"{kind}_{version}_{binary}.msh"
    write_msh(msh, version, binary)
    check_converted(hexdom_bin, msh, tmp_path, expected, BOX_VOLUME[base])


def test_prisms_are_vtk_wedges_not_mirrored(gmsh_session, hexdom_bin, tmp_path):
    """The extruded mesh's prisms as the program writes them: every wedge's first triangle turns
    its right-hand normal away from the second triangle (VTK's convention), checked on the points."""
    build("prism")
    msh = tmp_path / "prisms.msh"
    write_msh(msh, 4.1, 0)
    g, _ = check_converted(hexdom_bin, msh, tmp_path, gmsh_expected(), 3.0)
    P, types, conn = O.grid_arrays(g)
    assert set(types.tolist()) == {O.WEDGE}
    for c in conn:
        a, b = P[c[:3]], P[c[3:6]]
        normal = np.cross(a[1] - a[0], a[2] - a[0])
        assert normal @ (b.mean(axis=0) - a.mean(axis=0)) < 0


def test_save_all_skips_boundary_elements(gmsh_session, hexdom_bin, tmp_path):
    """Mesh.SaveAll writes the triangles, lines and points too (skipped). In 4.1 the tet box's
    regions stay its groups' ($Entities keeps them); Gmsh's 2.2 writer then gives every element
    physical tag 0, so the regions are the volumes' own tags."""
    build("tet")
    nodes, types, regions = gmsh_expected()
    by_volume = {}
    for _, tag in gmsh.model.getEntities(3):
        by_volume[tag] = len(gmsh.model.mesh.getElements(3, tag)[1][0])
    assert sorted(by_volume.values()) == sorted(regions.values())
    for version, expected_regions in ((4.1, regions), (2.2, by_volume)):
        msh = tmp_path / f"save_all_{version}.msh"
        write_msh(msh, version, 0, save_all=1)
        assert "$EndElements" in msh.read_text() and " 15 " in msh.read_text()  # points are in the file
        check_converted(hexdom_bin, msh, tmp_path, (nodes, types, expected_regions), 2.5)


def test_surface_mesh_reads_as_triangles(gmsh_session, hexdom_bin, tmp_path):
    """A file with no volume element is the surface of its triangles (regions: the surfaces' tags)."""
    gmsh.clear()
    gmsh.model.add("square")
    gmsh.model.occ.addRectangle(0, 0, 0, 1, 2)
    gmsh.model.occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.3)
    gmsh.model.mesh.generate(2)
    triangles = len(gmsh.model.mesh.getElementsByType(2)[0])
    msh = tmp_path / "square.msh"
    write_msh(msh, 4.1, 1)
    out = tmp_path / "square.vtk"
    r = run(hexdom_bin, "convert", "-i", msh, "-o", out)
    assert r.returncode == 0, r.stderr
    g, region = read_vtk(out)
    assert O.cell_type_counts(g) == {O.TRIANGLE: triangles}
    assert set(region.tolist()) == {1}


@pytest.mark.parametrize("text,line,message", [
    ("$MeshFormat\n4.0 0 8\n$EndMeshFormat\n", 2, "MSH version '4.0' is not supported"),
    ("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n$Elements\n1\n"
     "1 4 2 0 1 1 1 1 2\n$EndElements\n", 10, "element 1 refers to node tag 2, which $Nodes does not give"),
    ("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n$Elements\n1\n"
     "9 7 2 0 1 1 2 3 4 4\n$EndElements\n", 13, "element 9: Gmsh element type 7 (5-node pyramid) is not supported"),
])
def test_malformed_file_fails_naming_file_and_line_and_writes_nothing(hexdom_bin, tmp_path, text, line, message):
    msh = tmp_path / "bad.msh"
    msh.write_text(text)
    out = tmp_path / "bad.vtk"
    r = run(hexdom_bin, "convert", "-i", msh, "-o", out)
    assert r.returncode == 1
    assert f"{msh}:{line}: {message}" in r.stderr
    assert not out.exists()
