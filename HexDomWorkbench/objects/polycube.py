"""HexDom Polycube: the polycube structure, hex, prism and tet blocks, that generation fills.

The structure lives in properties: Points (block corners), Blocks (8 point indices per block,
VTK node order, -1 padded: 8 for a hex, 6 for a prism, 4 for a tet) and BlockTypes (VTK type per
block: 12 hex, 13 prism, 10 tet). SourceFile names the .k structure file it was imported from;
setting it to another file and recomputing reads that file (api.import_structure and
api.export_structure, from document.py, read and write the original program's .k files through
core).

Mode "Automatic" computes the structure on recompute with core.autopolycube from the labels of the
linked Segmentation, with blocks of Size * 2^Level (Size 0: bounding-box diagonal / 30), the
widths of holes kept (KeepWidths) and tet blocks at apexes (TetApexes) as asked. The
automatic structure comes with its own patch surface (the segmented surface cut along the grid,
one patch per boundary square: PatchPoints, PatchTriangles, PatchIds), which the HexDom Mesh then
generates from instead of the Segmentation's patches. Mode "Manual" keeps the stored blocks (and
that patch surface, if any) as they are: the Build Polycube panel switches an automatic Polycube
to Manual when its OK writes edited blocks, and setting Mode back to Automatic recomputes them.
A Polycube Mesh Part's pipeline filled (FromPipeline) keeps its blocks until one of its inputs is
edited.
"""

import os

import numpy as np

from .. import core
from ..logic.stages import read_structure
from ..progress import Progress
from . import segmentation
from .base_object import BaseHexDomObject, is_of_type, set_read_only

TYPE = "HexDom::Polycube"
BLOCK_TYPES = (core.HEX, core.WEDGE, core.TET)
MODES = ["Manual", "Automatic"]

# Figures of the last automatic build (read-only): (property, type, tooltip, AutoPolycube.info key)
_AUTO_RESULTS = [
    ("CellSize", "App::PropertyFloat", "Edge length h of the grid cells the blocks are made of",
     "cell"),
    ("Charts", "App::PropertyInteger", "Charts (connected regions of one label) flattened",
     "charts"),
    ("Relabelled", "App::PropertyInteger", "Charts whose label the repair changed", "relabelled"),
    ("MinBlockSJ", "App::PropertyFloat", "Smallest scaled Jacobian of the blocks",
     "min_block_quality"),
    ("InvertedBlocks", "App::PropertyInteger", "Blocks with scaled Jacobian <= 0",
     "inverted_blocks"),
]

_RESULTS = [
    ("HexBlocks", "Number of hex blocks"),
    ("PrismBlocks", "Number of prism blocks"),
    ("TetBlocks", "Number of tet blocks"),
    ("PointCount", "Number of block corners"),
]


class Polycube(BaseHexDomObject):
    """Proxy of a HexDom Polycube object (App::FeaturePython)."""

    Type = TYPE
    STAGE_INPUTS = ("SourceFile", "Points", "Blocks", "BlockTypes", "Mode", "Segmentation", "Size",
                    "Level", "KeepWidths", "TetApexes")

    def add_properties(self, obj):
        super().add_properties(obj)
        self.add_pipeline_flag(obj)
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
        if not hasattr(obj, "Mode"):
            obj.addProperty("App::PropertyEnumeration", "Mode", "Input",
                            "Manual: the stored blocks (hand-built, imported or edited); "
                            "Automatic: computed on recompute from Segmentation "
                            "(core.autopolycube)")
            obj.Mode = MODES
            obj.Mode = "Manual"
        if not hasattr(obj, "Segmentation"):
            obj.addProperty("App::PropertyLink", "Segmentation", "Automatic",
                            "HexDom Segmentation whose labels Mode Automatic builds the "
                            "polycube of")
        if not hasattr(obj, "Size"):
            obj.addProperty("App::PropertyLength", "Size", "Automatic",
                            "Target element size H; blocks are grid cells of H * 2^Level "
                            "(0: bounding-box diagonal / 30)")
        if not hasattr(obj, "Level"):
            obj.addProperty("App::PropertyInteger", "Level", "Automatic",
                            "Subdivision level the blocks are made for (the HexDom Mesh's Level): "
                            "2^Level cells per block edge")
            obj.Level = 1
        if not hasattr(obj, "KeepWidths"):
            obj.addProperty("App::PropertyBool", "KeepWidths", "Automatic",
                            "Walls of a hole or slot facing each other across the void stay as "
                            "many cells apart as in the part; false: least-squares plane offsets "
                            "(Mesh Part sets the one whose mesh is better)")
            obj.KeepWidths = True
        if not hasattr(obj, "TetApexes"):
            obj.addProperty("App::PropertyBool", "TetApexes", "Automatic",
                            "The blocks under the cap of an apex (cone or pyramid tip) become "
                            "tets and prisms; false: they stay hexes (Mesh Part sets the one "
                            "whose mesh is better)")
            obj.TetApexes = True
        for name, prop_type, doc, _ in _AUTO_RESULTS:
            if not hasattr(obj, name):
                obj.addProperty(prop_type, name, "Automatic", doc)
        for name, prop_type, doc in _PATCH_SURFACE:
            if not hasattr(obj, name):
                obj.addProperty(prop_type, name, "Structure", doc)
        set_read_only(obj, ["LoadedFile"] + [name for name, _ in _RESULTS]
                      + [name for name, _, _, _ in _AUTO_RESULTS])
        for name in ("Points", "Blocks", "BlockTypes", "LoadedFile") + PATCH_SURFACE_PROPERTIES:
            obj.setEditorMode(name, 2)

    def execute(self, obj):
        if getattr(obj, "FromPipeline", False):
            return  # Mesh Part's pipeline fills it
        if getattr(obj, "Mode", "Manual") == "Automatic":
            build_automatic(obj)
            return
        path = obj.SourceFile
        if path and os.path.abspath(path) != obj.LoadedFile:
            store_structure(obj, read_structure(path))
            store_patch_surface(obj, None)  # a file's blocks go with the Segmentation's patches
            obj.LoadedFile = os.path.abspath(path)
        else:
            structure = get_structure(obj)
            check_structure(structure)
            update_counts(obj, structure.types, len(structure.V))


_PATCH_SURFACE = [
    ("PatchPoints", "App::PropertyVectorList",
     "Points of the automatic structure's patch surface (empty: the Segmentation's patches)"),
    ("PatchTriangles", "App::PropertyIntegerList",
     "Point indices (0-based), three per triangle of the patch surface"),
    ("PatchIds", "App::PropertyIntegerList", "Patch id per triangle of the patch surface"),
]
PATCH_SURFACE_PROPERTIES = tuple(name for name, _, _ in _PATCH_SURFACE)


def build_automatic(obj):
    """Mode Automatic: the structure and patch surface of core.autopolycube on the labels of
    obj.Segmentation; raises core.GeometryError naming the charts when it cannot."""
    seg = obj.Segmentation
    if seg is None or not segmentation.is_segmentation(seg):
        raise ValueError("{}: Mode Automatic needs a HexDom Segmentation (property "
                         "Segmentation)".format(obj.Label))
    if obj.Level < 0:
        raise ValueError("{}: Level must be 0 or more".format(obj.Label))
    labels = segmentation.get_label_surface(seg)
    with Progress("Automatic polycube " + obj.Label, 1) as bar:
        result = bar.run("automatic polycube", core.autopolycube, labels,
                         size=float(obj.Size.Value), level=int(obj.Level),
                         keep_widths=bool(getattr(obj, "KeepWidths", True)),
                         collapse_apexes=bool(getattr(obj, "TetApexes", True)),
                         frame=segmentation.frame_matrix(seg),
                         stretch=segmentation.stretch_factors(seg))
        bar.step("{} blocks of {:g}".format(len(result.structure.types),
                                            float(result.info.get("cell", 0.0))))
    store_structure(obj, result.structure)
    store_patch_surface(obj, result.patches)
    for name, _, _, key in _AUTO_RESULTS:
        value = result.info.get(key)
        if value is not None:
            value = type(getattr(obj, name))(value)
            if getattr(obj, name) != value:
                setattr(obj, name, value)
    return result


def store_patch_surface(obj, surface):
    """Keeps the core.Surface ``surface`` (patch ids per triangle) as the patch surface the blocks
    go with; None clears it (the Segmentation's patches are used)."""
    if surface is None:
        if len(obj.PatchTriangles) or len(obj.PatchPoints):
            obj.PatchTriangles = []
            obj.PatchIds = []
            obj.PatchPoints = []
        return
    V = np.asarray(surface.V, float).reshape(-1, 3)
    F = np.asarray(surface.F, np.int64).reshape(-1, 3)
    ids = np.asarray(surface.patch, np.int64).reshape(-1)
    obj.PatchTriangles = []
    obj.PatchPoints = [tuple(p) for p in V.tolist()]
    obj.PatchIds = ids.tolist()
    obj.PatchTriangles = F.reshape(-1).tolist()


def has_patch_surface(obj):
    return is_polycube(obj) and len(getattr(obj, "PatchTriangles", ())) > 0


def get_patch_surface(obj):
    """core.Surface of the blocks' own patch surface (automatic structures), or None."""
    if not has_patch_surface(obj):
        return None
    V = np.array([tuple(p) for p in obj.PatchPoints], float).reshape(-1, 3)
    F = np.array(obj.PatchTriangles, np.int32).reshape(-1, 3)
    ids = np.array(obj.PatchIds, np.int32)
    if len(ids) != len(F):
        raise ValueError("{}: {} patch ids for {} patch triangles; recompute it".format(
            obj.Label, len(ids), len(F)))
    return core.Surface(V, F, ids)


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
