"""`hexdom mesh` on a CAD file with several solids: each solid meshed, its cells in region k for
solid k, every region filling its solid (volumes by VTK's vtkCellSizeFilter against FreeCAD's);
--solid N meshes one; solids that touch are meshed with a warning that the meshes do not conform
where they meet. The parts are made here with FreeCAD (boxes and a cylinder)."""

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
