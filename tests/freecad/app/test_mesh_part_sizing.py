"""Mesh Part's element size bounds (issue "element size that FEM users can steer"): the HexDom Mesh
object's MaxSize, MinSize and CellsAcross (as FreeCAD's Gmsh mesh object's CharacteristicLengthMax
/ Min) reach the core's pipeline, give the mesh `hexdom mesh --max-size / --min-size /
--cells-across` gives, and a recompute after editing them gives the mesh of the new values.

Oracles: `_hexdom`'s own pipeline on the shape FreeCAD holds (core.mesh_part on its BREP text, what
`hexdom mesh` runs), FreeCAD's FemMesh (its own node coordinates and volume count),
OpenCASCADE's volume."""

import numpy as np
import pytest

import FreeCAD  # noqa: F401  (the document fixture's)

import HexDomWorkbench as hexdom
from HexDomWorkbench import api, core

needs_cad = pytest.mark.skipif(not api.has_cad(), reason="_hexdom built without OpenCASCADE")


def _box(doc, L, W, H):
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = L, W, H
    doc.recompute()
    return box


def _fem_points(mesh):
    nodes = mesh.FemMesh.Nodes
    return np.array([[nodes[n].x, nodes[n].y, nodes[n].z] for n in sorted(nodes)])


def _same_mesh(mesh, run):
    """The Mesh object's FemMesh holds run's cells and nodes (same count, same coordinates as sets)."""
    assert mesh.FemMesh.VolumeCount == len(run.mesh.types)
    P = _fem_points(mesh)
    assert P.shape == run.mesh.V.shape
    key = lambda A: A[np.lexsort(np.round(A, 9).T)]  # noqa: E731
    assert np.abs(key(P) - key(run.mesh.V)).max() < 1e-9


@needs_cad
def test_max_size_and_its_edit_give_the_program_s_meshes(doc):
    box = _box(doc, 40.0, 20.0, 10.0)  # default size 1.53 (diagonal / 30)
    brep = box.Shape.exportBrepToString()
    objs = hexdom.mesh_part(doc, box, max_size=1.0)
    mesh = objs["mesh"]
    assert mesh.MaxSize.Value == 1.0 and mesh.MinSize.Value == 0.0
    assert mesh.CellsAcross == core.MESH_OPTIONS["cells_across"] == 2
    bounded = core.mesh_part(brep, max_size=1.0)
    _same_mesh(mesh, bounded)
    default = core.mesh_part(brep)
    assert len(bounded.mesh.types) > 2 * len(default.mesh.types)
    # Editing MaxSize back to 0 (no bound): the default mesh.
    mesh.MaxSize = 0.0
    api.recompute_document(doc, [mesh])
    _same_mesh(mesh, default)


@needs_cad
def test_cells_across_and_min_size_on_a_thin_plate(doc):
    # 40 x 40 x 0.4: two cells across by default; CellsAcross 4 gives four; a MinSize of 0.4 one
    # (node heights to 0.01: the improvement moves inner nodes by less).
    plate = _box(doc, 40.0, 40.0, 0.4)
    brep = plate.Shape.exportBrepToString()
    objs = hexdom.mesh_part(doc, plate, cells_across=4)
    mesh = objs["mesh"]
    assert mesh.CellsAcross == 4
    run = core.mesh_part(brep, cells_across=4)
    _same_mesh(mesh, run)
    assert len(np.unique(np.round(_fem_points(mesh)[:, 2], 2))) == 5
    mesh.CellsAcross = 2
    mesh.MinSize = 0.4
    api.recompute_document(doc, [mesh])
    _same_mesh(mesh, core.mesh_part(brep, min_size=0.4))
    assert len(np.unique(np.round(_fem_points(mesh)[:, 2], 2))) == 2
    assert mesh.InvertedCount == 0


def test_bad_bounds_are_refused_before_any_object_is_made(doc):
    plate = _box(doc, 10.0, 10.0, 1.0)
    before = len(doc.Objects)
    with pytest.raises(ValueError, match="min_size 2.0 is larger than max_size 1.0"):
        hexdom.mesh_part(doc, plate, max_size=1.0, min_size=2.0)
    with pytest.raises(ValueError, match="cells_across must be 0 or more"):
        hexdom.mesh_part(doc, plate, cells_across=-1)
    assert len(doc.Objects) == before
