"""The only module that imports the compiled core ``_hexdom``. FreeCAD-free: numpy in, numpy out.

Cell arrays follow the core's convention: ``cells`` is #C x 8 (int32) with unused slots -1,
``types`` holds VTK cell-type numbers (5 triangle, 9 quad, 10 tet, 12 hex, 13 wedge) in VTK node
order, ``region`` a region (block, part) id per cell.
"""

import importlib
import os
import sys
from dataclasses import dataclass

import numpy as np


def _load_core():
    """Finds _hexdom: inside this package (installed), on sys.path, or in a build tree."""
    try:
        return importlib.import_module(__package__ + "._hexdom")
    except ImportError:
        pass
    try:
        return importlib.import_module("_hexdom")
    except ImportError:
        pass
    here = os.path.dirname(os.path.abspath(__file__))
    candidates = [os.environ.get("HEXDOM_BUILD_DIR", ""), os.path.join(here, "..", "build")]
    for build in candidates:
        path = os.path.join(build, "python")
        if build and os.path.isdir(path):
            sys.path.insert(0, os.path.abspath(path))
            try:
                return importlib.import_module("_hexdom")
            except ImportError:
                sys.path.pop(0)
    raise ImportError(
        "HexDom's compiled module _hexdom was not found: build it with 'make build' "
        "(or set HEXDOM_BUILD_DIR to the CMake build directory)")


_hexdom = _load_core()
Error = _hexdom.Error
InputError = _hexdom.InputError
GeometryError = _hexdom.GeometryError
MeshingError = _hexdom.MeshingError

TRIANGLE, QUAD, TET, HEX, WEDGE = 5, 9, 10, 12, 13
TYPE_NAMES = {TRIANGLE: "triangle", QUAD: "quad", TET: "tet", HEX: "hex", WEDGE: "prism"}
NODE_COUNT = {TRIANGLE: 3, QUAD: 4, TET: 4, HEX: 8, WEDGE: 6}


@dataclass
class Mesh:
    """Mixed hex / prism / tet (or surface) mesh in VTK node order."""

    V: np.ndarray  # (#V, 3) float64
    cells: np.ndarray  # (#C, 8) int32, -1 padded
    types: np.ndarray  # (#C,) int32 VTK cell types
    region: np.ndarray  # (#C,) int32

    def count(self, vtk_type):
        return int(np.count_nonzero(self.types == vtk_type))

    @property
    def counts(self):
        return {name: self.count(t) for t, name in TYPE_NAMES.items()}


@dataclass
class Surface:
    """Triangle surface with a patch id per triangle."""

    V: np.ndarray  # (#V, 3)
    F: np.ndarray  # (#F, 3)
    patch: np.ndarray  # (#F,)


def read_mesh(path):
    """Reads .k, .vtk, .stl or .obj into a Mesh."""
    return Mesh(*_hexdom.read_mesh(os.fspath(path)))


def write_mesh(path, mesh, binary=False):
    """Writes .k, .vtk, .vtu, .inp, .stl or .obj, chosen by extension; no file is left on error."""
    _hexdom.write_mesh(os.fspath(path), mesh.V, mesh.cells, mesh.types, mesh.region, binary)


def read_surface(path):
    """Reads a triangle surface (.k shells, .stl, .obj, .vtk) into a Surface."""
    return Surface(*_hexdom.read_surface(os.fspath(path)))


def write_surface(path, surface):
    _hexdom.write_surface(os.fspath(path), surface.V, surface.F, surface.patch)


def cell_metrics(mesh):
    """Per-cell (scaled_jacobian, edge_ratio, volume) arrays, Verdict's definitions."""
    return _hexdom.cell_metrics(mesh.V, mesh.cells, mesh.types)


def quality_report(mesh):
    """Dict with keys hex, prism, tet (count, sj_min, sj_mean, inverted, edge_ratio_min,
    edge_ratio_max, volume, histogram) and total_volume."""
    return _hexdom.quality_report(mesh.V, mesh.cells, mesh.types)


def generate(surface, structure, level=2, relax_sweeps=10, snap_tolerance=1e-4):
    """Hex-dominant mesh from a segmented Surface and a polycube structure Mesh (hex, prism and tet
    blocks): 8^level cells per block, conforming across blocks; region = 1-based block number."""
    return Mesh(*_hexdom.generate(surface.V, surface.F, surface.patch, structure.V, structure.cells,
                                  structure.types, level, relax_sweeps, snap_tolerance))


def improve(mesh, surface=None, pillow=False, smooth=0, optimize=0, feature_angle=35.0,
            sharp_nodes=()):
    """Pillowing, smoothing and Jacobian optimisation of a Mesh. With no stage set, runs the
    recommended sequence until the worst cell stops improving. Boundary nodes stay on `surface`
    (a Surface) or on the mesh's own boundary."""
    sv, sf = (surface.V, surface.F) if surface is not None else (None, None)
    return Mesh(*_hexdom.improve(mesh.V, mesh.cells, mesh.types, mesh.region, pillow, smooth,
                                 optimize, feature_angle, list(sharp_nodes), sv, sf))
