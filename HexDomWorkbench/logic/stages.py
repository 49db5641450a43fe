"""The core's stages as the workbench calls them: what the build offers, segmentation with user
edits, the polycube check as messages, and structure files. Thin dispatch to ``core`` (the
meshing is the compiled module's); FreeCAD-free."""

import os
from dataclasses import dataclass

import numpy as np

from .. import core
from .labels import patches_from_labels


@dataclass
class SegmentedSurface(core.Surface):
    """core.Surface whose ``patch`` holds patch ids, plus a polycube label (1..6) per triangle."""

    labels: np.ndarray = None


def core_has(name):
    """True if core offers ``name`` and the compiled module behind it does too (core.py may be
    newer than the _hexdom it loads)."""
    compiled = getattr(core, "_hexdom", None)
    return hasattr(core, name) and (compiled is None or hasattr(compiled, name))


def has_segmentation():
    """True if the compiled core provides automatic segmentation (core.segment)."""
    return core_has("segment")


def has_cad():
    """True if the compiled core tessellates CAD shapes itself (core.tessellate_brep)."""
    return core_has("tessellate_brep")


def check_patches(surface, **options):
    """Problems the core finds in a segmented surface (core.check_patches: the polycube
    conditions), as a list of messages; empty when the build has no such check."""
    if not core_has("check_patches"):
        return []
    try:
        result = core.check_patches(surface, **options)
    except core.Error as e:
        return [str(e)]
    return [str(v) for v in result]


def segment(surface, edits=None, **options):
    """Automatic polycube segmentation of a core.Surface (core.segment: CVT of the normals; when
    ``surface.patch`` holds several ids, e.g. CAD faces, planar faces keep one label). ``edits``:
    (triangle, label 1..6) rows the CVT must keep; ``options`` go to core.segment. Returns a
    SegmentedSurface: patch ids (connected regions of one label) and labels 1..6.

    Raises core.Error("segmentation not available in this build") without core.segment.
    """
    if not has_segmentation():
        raise core.Error("segmentation not available in this build")
    if edits is not None and len(edits):
        options["manual"] = np.asarray(edits, np.int32).reshape(-1, 2)
    result = core.segment(surface, **options)
    labels = np.asarray(result.patch, np.int32).reshape(-1)
    if len(labels) != len(np.asarray(surface.F)):
        raise core.Error("core.segment returned {} labels for {} triangles".format(
            len(labels), len(surface.F)))
    V, F = np.asarray(surface.V), np.asarray(surface.F)
    if core_has("number_patches"):
        patches = np.asarray(core.number_patches(core.Surface(V, F, labels)), np.int32)
    else:
        patches = patches_from_labels(F, labels)
    return SegmentedSurface(V, F, patches.reshape(-1), labels)


def read_structure(path):
    """Polycube structure (hex, prism and tet blocks) from a .k file (or any volume mesh)."""
    structure = core.read_mesh(os.fspath(path))
    bad = np.setdiff1d(np.unique(structure.types), [core.HEX, core.WEDGE, core.TET])
    if len(structure.types) == 0 or len(bad):
        raise core.InputError("{}: a polycube structure holds hex, prism and tet blocks only"
                              .format(os.fspath(path)))
    return structure
