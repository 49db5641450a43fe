"""`hexdom polycube --auto -i PATCHES.k -o STRUCTURE.k [--size H]` (issue 9's form of the automatic
polycube step): the structure and its patch surface, which `hexdom generate` takes unchanged.

Input: the shipped L-bracket's patch file (examples/data, made by examples/make_lbracket.py), whose
part ids are patch numbers, and the same surface with labels 1..6 as part ids, computed here in
numpy (axis nearest each patch's area-weighted normal). Oracles: our own LS-DYNA reader in
hexdom_oracles (independent of the core's), meshio and VTK's Verdict for the generated mesh.
"""

import subprocess
from pathlib import Path

import meshio
import numpy as np
import pytest

import hexdom_oracles as oracles

REPO = Path(__file__).resolve().parents[2]
PATCHES = REPO / "examples" / "data" / "lbracket_patches.k"
AXES = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float)


def _run(hexdom_bin, *args):
    return subprocess.run([str(hexdom_bin), *map(str, args)], capture_output=True, text=True)


def _surface(path):
    k = oracles.parse_k(path)
    ids = list(k["nodes"])
    index = {n: i for i, n in enumerate(ids)}
    V = np.array([k["nodes"][n] for n in ids], float)
    F = np.array([[index[n] for n in s[2][:3]] for s in k["shells"]], np.int64)
    part = np.array([s[1] for s in k["shells"]], np.int64)
    return V, F, part


def _labels_file(path):
    """The patch file with each shell's part id replaced by its patch's label, line for line."""
    V, F, part = _surface(PATCHES)
    n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    label = {}
    for p in np.unique(part):
        label[int(p)] = int(np.argmax(AXES @ n[part == p].sum(axis=0))) + 1
    out, section = [], None
    for line in PATCHES.read_text().splitlines():
        if line.startswith("*"):
            section = line.strip()
        elif section == "*ELEMENT_SHELL" and line.strip() and not line.startswith("$"):
            f = line.split()
            line = "%8d%8d" % (int(f[0]), label[int(f[1])]) + "".join("%8d" % int(x) for x in f[2:])
        out.append(line)
    path.write_text("\n".join(out) + "\n")
    return sorted(set(label.values())), len(label)


def test_auto_structure_from_labels_feeds_generate(hexdom_bin, tmp_path):
    labels = tmp_path / "labels.k"
    used, npatches = _labels_file(labels)
    assert npatches > 6 and len(used) == 6  # the shipped file holds patches, not labels
    structure = tmp_path / "structure.k"
    r = _run(hexdom_bin, "polycube", "--auto", "-i", labels, "-o", structure, "--size", 2.5, "-s", 1)
    assert r.returncode == 0, r.stderr
    patches = tmp_path / "structure_patches.k"  # the default --patches-out
    assert patches.exists()
    blocks = oracles.parse_k(structure)["solids"]
    assert len(blocks) > 0
    assert f"blocks:             {len(blocks)} hex" in r.stdout
    # The patch surface: one patch per boundary block face, each a closed surface's piece.
    _, Fp, part = _surface(patches)
    squares = int(r.stdout.split("boundary squares:")[1].split()[0])
    assert len(np.unique(part)) == squares
    edges = np.sort(Fp[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    _, uses = np.unique(edges, axis=0, return_counts=True)
    assert set(uses.tolist()) == {2}

    mesh = tmp_path / "mesh.vtu"
    g = _run(hexdom_bin, "generate", "-i", patches, "-p", structure, "-s", 1, "-o", mesh)
    assert g.returncode == 0, g.stderr
    m = meshio.read(mesh)
    assert [c.type for c in m.cells] == ["hexahedron"]
    assert len(m.cells[0].data) == 8 * len(blocks)
    grid = oracles.vtk_grid(m.points, m.cells[0].data, np.full(len(m.cells[0].data), oracles.HEX))
    sj, _ = oracles.verdict_metrics(grid)
    assert sj.min() > 0


def test_auto_takes_patch_numbers_as_their_nearest_axes(hexdom_bin, tmp_path):
    # The same surface given with patch numbers and with labels gives the same structure.
    labels = tmp_path / "labels.k"
    _labels_file(labels)
    a, b = tmp_path / "a.k", tmp_path / "b.k"
    ra = _run(hexdom_bin, "polycube", "--auto", "-i", PATCHES, "-o", a, "--size", 2.5)
    rb = _run(hexdom_bin, "polycube", "--auto", "-i", labels, "-o", b, "--size", 2.5)
    assert ra.returncode == 0 and rb.returncode == 0, ra.stderr + rb.stderr
    assert "part ids are patches, not labels 1..6" in ra.stderr
    assert "part ids are patches" not in rb.stderr
    assert oracles.parse_k(a) == oracles.parse_k(b)
    assert oracles.parse_k(tmp_path / "a_patches.k") == oracles.parse_k(tmp_path / "b_patches.k")


def test_auto_options_need_auto_and_bad_input_leaves_nothing(hexdom_bin, tmp_path):
    out = tmp_path / "s.k"
    r = _run(hexdom_bin, "polycube", "-i", PATCHES, "-o", out, "--size", 2.5)
    assert r.returncode != 0 and "--size requires --auto" in r.stderr
    r = _run(hexdom_bin, "polycube", "--auto", "--corners", "-i", PATCHES, "-o", out)
    assert r.returncode != 0 and "excludes" in r.stderr
    r = _run(hexdom_bin, "polycube", "--auto", "-i", tmp_path / "none.k", "-o", out)
    assert r.returncode == 1 and "none.k" in r.stderr
    assert not out.exists() and not (tmp_path / "s_patches.k").exists()
