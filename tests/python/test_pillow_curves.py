"""`hexdom mesh --method overlay --pillow-curves` on the shipped bracket (examples/data/bracket.step):
the overlay path lays a sheet of wedges along each CAD edge, so that every boundary face of the mesh
lies on one CAD face, which is what FreeCAD's face constraints need (they take the mesh faces whose
nodes all lie on the CAD face). Without the flag the grid's staircase along a curved edge bends some
boundary quads across it. Oracles: FreeCAD's distToShape for each boundary node against each CAD
face (within 1e-6 of the part's diagonal), VTK's Verdict for the cells, meshio for the cell types."""

import subprocess
from pathlib import Path

import meshio
import numpy as np
import pytest

import hexdom_oracles as oracles

REPO = Path(__file__).resolve().parents[2]
STEP = REPO / "examples" / "data" / "bracket.step"


def _boundary_faces(m):
    """The faces of the mesh's cells used by one cell only (node tuples)."""
    face_nodes = {"hexahedron": [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)],
                  "wedge": [(0, 1, 2), (3, 5, 4), (0, 3, 4, 1), (1, 4, 5, 2), (2, 5, 3, 0)]}
    count = {}
    for block in m.cells:
        for row in block.data:
            for f in face_nodes[block.type]:
                key = tuple(sorted(int(row[i]) for i in f))
                count[key] = count.get(key, 0) + 1
    return [k for k, n in count.items() if n == 1]


def _crossing(freecad, m):
    """Boundary faces whose nodes lie on no common CAD face of the bracket, and the boundary faces."""
    FreeCAD, Part = freecad
    shape = Part.read(str(STEP))
    shape = shape.Solids[0] if shape.Solids else shape
    tol = 1e-6 * shape.BoundBox.DiagonalLength
    faces = _boundary_faces(m)
    on = {}
    for v in sorted({v for f in faces for v in f}):
        x = Part.Vertex(FreeCAD.Vector(*map(float, m.points[v])))
        on[v] = {i for i, face in enumerate(shape.Faces) if face.distToShape(x)[0] <= tol}
    assert all(on.values()), "a boundary node off every CAD face"
    return sum(1 for f in faces if not set.intersection(*(on[v] for v in f))), len(faces)


def _mesh(hexdom_bin, out, *extra):
    run = subprocess.run([str(hexdom_bin), "mesh", str(STEP), "-o", str(out), "--method", "overlay", *extra],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return run


def test_pillowed_curves_put_every_boundary_face_on_one_cad_face(hexdom_bin, freecad, tmp_path):
    plain = _mesh(hexdom_bin, tmp_path / "plain.vtu")
    pillowed = _mesh(hexdom_bin, tmp_path / "pillowed.vtu", "--pillow-curves")
    m0, m1 = meshio.read(tmp_path / "plain.vtu"), meshio.read(tmp_path / "pillowed.vtu")
    crossing0, _ = _crossing(freecad, m0)
    crossing1, faces1 = _crossing(freecad, m1)
    assert crossing0 > 0  # the oracle sees the plain mesh's quads bent across an edge
    assert "cross a CAD edge" in plain.stderr
    assert crossing1 == 0, f"{crossing1} of {faces1} boundary faces cross a CAD edge"
    assert "cross a CAD edge" not in pillowed.stderr
    assert "wedges along the curves" in pillowed.stderr
    types = {block.type for block in m1.cells}
    assert types == {"hexahedron", "wedge"}
    assert {block.type for block in m0.cells} == {"hexahedron"}
    g, sj, _ = oracles.vtu_sj_types(tmp_path / "pillowed.vtu")
    assert np.all(sj > 0.3), float(sj.min())
    brep = float(pillowed.stdout.split("B-rep volume")[1].split()[0])
    assert float(np.sum(oracles.signed_volumes(g))) == pytest.approx(brep, rel=0.01)
