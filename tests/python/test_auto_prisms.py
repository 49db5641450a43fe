"""Prism blocks along a knife edge (issue 9): `hexdom mesh` of the thin wedge (15 degree knife edge,
remeshed so that the label repair's band along the edge can be narrow) collapses the band's strip
into prism blocks. Checked from outside: the structure file's blocks parsed independently
(hexdom_oracles.parse_k), the mesh read by VTK and judged by Verdict per cell type, the volume
against the surface's own."""

import subprocess

import numpy as np
import pytest

import hexdom_oracles as oracle
import hexdom_test_support as support


def _run(*args):
    r = subprocess.run([str(support.hexdom_bin()), *map(str, args)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r


def _enclosed(V, F):
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


@pytest.fixture(scope="module")
def knife_edge(tmp_path_factory):
    """The thin wedge remeshed to triangles of 0.15, meshed twice by `hexdom mesh`: hex blocks only
    (--sliver-ratio 0) and with the default (prisms along the knife edge)."""
    d = tmp_path_factory.mktemp("knife_edge")
    V, F, P = support.thin_wedge()
    support.write_k_surface(d / "raw.k", V, F, P)
    _run("remesh", "-i", d / "raw.k", "-o", d / "wedge.k", "--size", 0.15)
    runs = {}
    for name, extra in (("hex", ["--sliver-ratio", 0]), ("prism", [])):
        out = d / f"{name}.vtu"
        r = _run("mesh", d / "wedge.k", "-o", out, "--keep", *extra)
        g = oracle.read_vtu(out)
        sj, _ = oracle.verdict_metrics(g)
        types = np.array([g.GetCellType(i) for i in range(g.GetNumberOfCells())])
        runs[name] = dict(out=out, stdout=r.stdout, stderr=r.stderr, grid=g, sj=sj, types=types,
                          volume=float(oracle.signed_volumes(g).sum()),
                          blocks=oracle.parse_k(d / f"{name}_structure.k")["solids"])
    k = oracle.parse_k(d / "wedge.k")
    ids = {nid: i for i, nid in enumerate(k["nodes"])}
    SV = np.array(list(k["nodes"].values()), float)
    SF = np.array([[ids[n] for n in s[2][:3]] for s in k["shells"]])
    return runs, _enclosed(SV, SF)


def test_knife_edge_wedge_gets_prism_blocks_and_cells(knife_edge):
    runs, _ = knife_edge
    r = runs["prism"]
    prism_blocks = [b for b in r["blocks"] if len(set(b[2])) == 6]
    assert prism_blocks, "no prism block in the structure"
    assert all(len(set(b[2])) in (6, 8) for b in r["blocks"])
    nprism = int(np.sum(r["types"] == oracle.WEDGE))
    assert nprism == 8 * len(prism_blocks)  # level 1: 8 prisms per prism block
    # Hex blocks only when the collapse is off.
    assert all(len(set(b[2])) == 8 for b in runs["hex"]["blocks"])
    assert not np.any(runs["hex"]["types"] == oracle.WEDGE)


def test_knife_edge_wedge_mesh_is_valid_and_keeps_the_volume(knife_edge):
    runs, volume = knife_edge
    r = runs["prism"]
    assert np.all(r["sj"] > 0), f"inverted cells: {int(np.sum(~(r['sj'] > 0)))}"
    assert r["volume"] == pytest.approx(volume, rel=0.01)
    worst = {n: float(r["sj"][r["types"] == t].min()) for t, n in ((oracle.HEX, "hex"), (oracle.WEDGE, "prism"))}
    assert worst["prism"] > 0.1, worst
    assert worst["hex"] >= 0.3, worst


def test_prisms_do_not_lower_the_worst_cell(knife_edge):
    """The collapse is kept only where the blocks are not worse; the mesh's worst cell (any type,
    Verdict) and its inverted count are at least as good as with hex blocks only."""
    runs, _ = knife_edge
    assert np.sum(~(runs["prism"]["sj"] > 0)) <= np.sum(~(runs["hex"]["sj"] > 0))
    assert runs["prism"]["sj"].min() >= runs["hex"]["sj"].min() - 1e-9


def test_polycube_auto_writes_prism_blocks_that_generate_takes(knife_edge, tmp_path):
    """`hexdom polycube --auto` on the knife edge's labels (written by `mesh --keep`) writes prism
    blocks as collapsed hexes and a patch file with one patch per boundary block face (the prisms'
    end triangles included); `generate` takes the pair unchanged: 8 prisms per prism block, no cell
    inverted, the volume kept."""
    runs, volume = knife_edge
    labels = runs["prism"]["out"].parent / "prism_labels.k"
    r = _run("polycube", "--auto", "-i", labels, "-o", tmp_path / "s.k")
    blocks = oracle.parse_k(tmp_path / "s.k")["solids"]
    prisms = sum(len(set(b[2])) == 6 for b in blocks)
    assert prisms > 0 and f"blocks:             {len(blocks) - prisms} hex, {prisms} prism, 0 tet" in r.stdout
    patches = oracle.parse_k(tmp_path / "s_patches.k")
    npatches = len({s[1] for s in patches["shells"]})
    assert f"({npatches} patches" in r.stdout
    # One patch per boundary face of the blocks (faces of collapsed hexes by distinct nodes).
    hex_faces = [(0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    faces = {}
    for b in blocks:
        for f in hex_faces:
            key = frozenset(b[2][i] for i in f)
            if len(key) >= 3:
                faces[key] = faces.get(key, 0) + 1
    assert max(faces.values()) <= 2
    boundary = [k for k, n in faces.items() if n == 1]
    assert len(boundary) == npatches and any(len(k) == 3 for k in boundary)
    _run("generate", "-i", tmp_path / "s_patches.k", "-p", tmp_path / "s.k", "-s", 1, "-o", tmp_path / "m.vtk")
    g, _ = oracle.read_legacy_vtk(tmp_path / "m.vtk")
    sj, _ = oracle.verdict_metrics(g)
    types = np.array([g.GetCellType(i) for i in range(g.GetNumberOfCells())])
    assert int(np.sum(types == oracle.WEDGE)) == 8 * prisms
    assert np.all(sj > 0), f"inverted cells: {int(np.sum(~(sj > 0)))}"
    assert float(oracle.signed_volumes(g).sum()) == pytest.approx(volume, rel=0.01)
