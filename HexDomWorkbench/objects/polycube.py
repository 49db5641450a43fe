"""HexDom Polycube: the polycube structure, hex, prism and tet blocks, that generation fills.

The structure lives in properties: Points (block corners), Blocks (8 point indices per block,
VTK node order, -1 padded: 8 for a hex, 6 for a prism, 4 for a tet) and BlockTypes (VTK type per
block: 12 hex, 13 prism, 10 tet). SourceFile names the .k structure file it was imported from;
setting it to another file and recomputing reads that file (api.import_structure and
api.export_structure read and write the original program's .k files through core).
"""

import os

import numpy as np

from .. import core
from .base_object import BaseHexDomObject, is_of_type, set_read_only

TYPE = "HexDom::Polycube"
BLOCK_TYPES = (core.HEX, core.WEDGE, core.TET)

_RESULTS = [
    ("HexBlocks", "Number of hex blocks"),
    ("PrismBlocks", "Number of prism blocks"),
    ("TetBlocks", "Number of tet blocks"),
    ("PointCount", "Number of block corners"),
]


class Polycube(BaseHexDomObject):
    """Proxy of a HexDom Polycube object (App::FeaturePython)."""

    Type = TYPE

    def add_properties(self, obj):
        super().add_properties(obj)
        if not hasattr(obj, "SourceFile"):
            obj.addProperty("App::PropertyFile", "SourceFile", "Input",
                            "Structure file (.k, LS-DYNA *ELEMENT_SOLID blocks) the blocks "
                            "come from; another file is read on recompute")
        if not hasattr(obj, "LoadedFile"):
            obj.addProperty("App::PropertyString", "LoadedFile", "Input",
                            "File the stored blocks were read from")
        for name, doc in _RESULTS:
            if not hasattr(obj, name):
                obj.addProperty("App::PropertyInteger", name, "Result", doc)
        if not hasattr(obj, "Points"):
            obj.addProperty("App::PropertyVectorList", "Points", "Structure", "Block corners")
        if not hasattr(obj, "Blocks"):
            obj.addProperty("App::PropertyIntegerList", "Blocks", "Structure",
                            "Corner indices (0-based), 8 per block in VTK order, -1 padded")
        if not hasattr(obj, "BlockTypes"):
            obj.addProperty("App::PropertyIntegerList", "BlockTypes", "Structure",
                            "VTK cell type per block: 12 hex, 13 prism, 10 tet")
        set_read_only(obj, ["LoadedFile"] + [name for name, _ in _RESULTS])
        for name in ("Points", "Blocks", "BlockTypes", "LoadedFile"):
            obj.setEditorMode(name, 2)

    def execute(self, obj):
        path = obj.SourceFile
        if path and os.path.abspath(path) != obj.LoadedFile:
            from .. import api
            store_structure(obj, api.read_structure(path))
            obj.LoadedFile = os.path.abspath(path)
        else:
            structure = get_structure(obj)
            check_structure(structure)
            update_counts(obj, structure.types, len(structure.V))


def is_polycube(obj):
    return is_of_type(obj, TYPE)


def check_structure(structure):
    """Raises ValueError unless ``structure`` holds only well-formed hex, prism and tet blocks."""
    V = np.asarray(structure.V).reshape(-1, 3)
    cells = np.asarray(structure.cells, np.int64).reshape(-1, 8)
    types = np.asarray(structure.types, np.int64).reshape(-1)
    if len(types) != len(cells):
        raise ValueError("{} block types for {} blocks".format(len(types), len(cells)))
    bad = np.setdiff1d(np.unique(types), BLOCK_TYPES)
    if len(bad):
        raise ValueError("a polycube structure holds hex, prism and tet blocks only (VTK types "
                         "12, 13, 10); found type {}".format(int(bad[0])))
    for t in BLOCK_TYPES:
        n = core.NODE_COUNT[t]
        wrong = (types == t) & (np.any(cells[:, :n] < 0, axis=1)
                                | np.any(cells[:, :n] >= len(V), axis=1)
                                | np.any(cells[:, n:] != -1, axis=1))
        if np.any(wrong):
            raise ValueError("block {} ({}) has corner indices outside 0..{}".format(
                int(np.flatnonzero(wrong)[0]) + 1, core.TYPE_NAMES[t], len(V) - 1))


def update_counts(obj, types, point_count):
    types = np.asarray(types)
    counts = {"HexBlocks": int(np.count_nonzero(types == core.HEX)),
              "PrismBlocks": int(np.count_nonzero(types == core.WEDGE)),
              "TetBlocks": int(np.count_nonzero(types == core.TET)),
              "PointCount": int(point_count)}
    for name, value in counts.items():
        if getattr(obj, name) != value:
            setattr(obj, name, value)


def store_structure(obj, structure):
    """Puts a structure core.Mesh (hex, prism and tet blocks) into obj's properties."""
    check_structure(structure)
    V = np.asarray(structure.V, float).reshape(-1, 3)
    # Clear the blocks first so that the view never sees indices beyond the points.
    obj.Blocks = []
    obj.BlockTypes = np.asarray(structure.types, np.int64).tolist()
    obj.Points = [tuple(p) for p in V.tolist()]
    obj.Blocks = np.asarray(structure.cells, np.int64).reshape(-1).tolist()
    update_counts(obj, structure.types, len(V))


def get_structure(obj):
    """Structure core.Mesh of a HexDom Polycube (region = 1-based block number)."""
    if not is_polycube(obj):
        raise ValueError("{} is not a HexDom Polycube".format(getattr(obj, "Label", obj)))
    V = np.array([tuple(p) for p in obj.Points], float).reshape(-1, 3)
    cells = np.array(obj.Blocks, np.int32).reshape(-1, 8)
    types = np.array(obj.BlockTypes, np.int32)
    if len(types) != len(cells):
        raise ValueError("{}: {} block types for {} blocks".format(obj.Label, len(types),
                                                                   len(cells)))
    return core.Mesh(V, cells, types, np.arange(1, len(types) + 1, dtype=np.int32))
