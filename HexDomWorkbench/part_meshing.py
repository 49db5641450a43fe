"""Mesh Part: a Part solid meshed with no manual step, as `hexdom mesh` meshes it, every stage kept
as an editable document object (Surface -> Segmentation -> Polycube -> Mesh). A FreeCAD mesh
object (an STL or OBJ opened in FreeCAD) is meshed as `hexdom mesh FILE` meshes the file: its
triangles checked (a shell turned around, several solids each meshed as a region, solids touching
warned), no snap; the Segmentation and the Polycube hold the run's stages for one solid.

One pipeline: the Mesh (Pipeline true) recomputes by running `hexdom mesh`'s pipeline once
(core.mesh_part on the Part the Surface tessellates, with the Mesh's Size, Level, Method, Improve
and SnapToCAD), keeps its mesh, and fills the Surface (the tessellation meshed), the Segmentation
(its labels, edge weight and frame), the Polycube (its blocks, patch surface, level, widths of
holes, tet blocks at apexes) with what the pipeline made (fill_mesh_part). These hold it
(FromPipeline) and are not computed again, so Mesh Part gives the mesh `hexdom mesh PART` gives,
meshing the part once; changing the Mesh's Size, Level, Method or Improve and recomputing gives
`hexdom mesh --size --level --method --no-improve`'s. When the overlay grid's mesh is kept, the
Segmentation and the Polycube hold the polycube path's attempt (possibly nothing) and the Mesh
does not link the Polycube; MeshingPath says which path made the mesh, PolycubeNote why the
overlay was tried.

Editing an input of the Surface, the Segmentation or the Polycube (a property, a patch or a block
edit) makes that object an ordinary stage again: it computes from its inputs, and the Mesh leaves
Pipeline (leave_pipeline) and is built from the stages (generate, improve, snap), so an edit
re-runs only the stages after it. Setting the Mesh's Pipeline back on runs the pipeline again.

FreeCAD is imported only inside the functions that need it."""

from . import core, make
from .document import RecomputeError
from .objects import hex_mesh, tessellation
from .objects.chain import chain_of, objects_of, stage_edited  # noqa: F401 (the api's)
from .objects.pipeline import (  # noqa: F401 (the api's)
    STAGE_OF_CORE, enter_pipeline, held_by_pipeline, leave_pipeline, part_size, pipeline_options)
from .objects import pipeline


MESH_PART_STAGES = (("surface", "tessellate"), ("segmentation", "segment"),
                    ("polycube", "automatic polycube"), ("mesh", "generate and improve"))


class MeshPartError(RecomputeError):
    """A stage of mesh_part failed: ``stage`` names it, ``objects`` holds the objects created
    (all kept in the document, the finished ones valid), the message is the core's."""

    def __init__(self, message, stage=None, objects=None):
        super().__init__(message)
        self.stage = stage
        self.objects = objects or {}


def make_mesh_part(doc, part, size=0.0, level=core.MESH_OPTIONS["level"], improve=True,
                   method="auto", polycube_seconds=None, max_size=0.0, min_size=0.0,
                   cells_across=None, order=1):
    """Adds the four objects of mesh_part to ``doc`` without recomputing; returns them as a dict
    (surface, segmentation, polycube, mesh; no polycube with method "overlay"). The Mesh runs the
    pipeline (Pipeline) with Size ``size`` (0: `hexdom mesh`'s default), Level ``level``, Improve
    ``improve``, Method ``method``, PolycubeSeconds ``polycube_seconds`` (None: the default),
    MaxSize ``max_size`` and MinSize ``min_size`` (0: no bound) and CellsAcross ``cells_across``
    (None: the default), ElementOrder "1st" or "2nd" for ``order`` 1 or 2; the three others wait
    to be filled by it (FromPipeline). ``part`` is a Part object with a solid or a FreeCAD mesh
    object (its triangles taken as they are). Raises ValueError for a ``part`` without a solid
    or triangles, a
    negative level, size, bound or budget, a min size above the max size, an unknown method or an
    order other than 1 and 2."""
    if method not in hex_mesh.METHODS:
        raise ValueError("method must be one of {}".format(", ".join(hex_mesh.METHODS)))
    if order not in (1, 2):
        raise ValueError("order must be 1 or 2, not {!r}".format(order))
    shape = getattr(part, "Shape", None)
    if tessellation.is_mesh_feature(part):
        if not part.Mesh.CountFacets:
            raise ValueError("{}: the mesh has no triangles".format(part.Label))
    elif shape is None or shape.isNull() or not shape.Solids:
        raise ValueError("{}: select a Part solid or a mesh to mesh".format(
            getattr(part, "Label", part)))
    if int(level) < 0:
        raise ValueError("level must be 0 or more")
    if size and size < 0:
        raise ValueError("size must be 0 (the default) or more")
    if polycube_seconds is not None and not polycube_seconds >= 0:
        raise ValueError("polycube_seconds must be 0 (no limit) or more")
    for name, value in (("max_size", max_size), ("min_size", min_size), ("cells_across", cells_across)):
        if value is not None and not value >= 0:
            raise ValueError("{} must be 0 or more".format(name))
    if max_size and min_size and min_size > max_size:
        raise ValueError("min_size {} is larger than max_size {}".format(min_size, max_size))
    label = part.Label
    objs = {}
    objs["surface"] = make.make_surface(doc, source=part, size=0.0, deflection=0.0, angle=30.0)
    objs["segmentation"] = make.make_segmentation(doc, objs["surface"], method="Automatic")
    if method != "overlay":  # (the overlay path makes no polycube)
        objs["polycube"] = make.make_polycube(doc, segmentation=objs["segmentation"], size=0.0,
                                              level=level)
    objs["mesh"] = make.make_hex_mesh(doc, segmentation=objs["segmentation"],
                                      polycube=objs.get("polycube"), level=level, improve=improve)
    mesh = objs["mesh"]
    mesh.Method = method
    mesh.Size = float(size or 0.0)
    if polycube_seconds is not None:
        mesh.PolycubeSeconds = float(polycube_seconds)
    mesh.MaxSize = float(max_size or 0.0)
    mesh.MinSize = float(min_size or 0.0)
    if cells_across is not None:
        mesh.CellsAcross = int(cells_across)
    mesh.ElementOrder = hex_mesh.ELEMENT_ORDERS[order - 1]
    for key, suffix in (("surface", "_surface"), ("segmentation", "_segmentation"),
                        ("polycube", "_polycube"), ("mesh", "_mesh")):
        if key in objs:
            objs[key].Label = label + suffix
    mesh.Pipeline = True  # (onChanged: the three others FromPipeline)
    return objs


def run_pipeline(objs, run=None):
    """Runs `hexdom mesh`'s pipeline for mesh_part's objects and fills all four from it
    (objects/pipeline.py's run_pipeline, the Mesh included); returns the core.MeshRun."""
    return pipeline.run_pipeline(objs, store_mesh=hex_mesh.store_mesh, run=run)


def fill_mesh_part(objs, result):
    """Puts the pipeline's core.MeshRun ``result`` into mesh_part's four objects (see
    objects/pipeline.py's fill_mesh_part)."""
    pipeline.fill_mesh_part(objs, result, store_mesh=hex_mesh.store_mesh)


def check_mesh_part(objs, allow_inverted=False):
    """Raises MeshPartError when mesh_part's Mesh failed (naming the core's message) or has
    inverted cells (unless ``allow_inverted``); a stage object that was edited and failed is named
    too. A Polycube the Mesh does not use (the overlay grid made the mesh) is not checked."""
    for key, stage in MESH_PART_STAGES:
        obj = objs.get(key)
        if obj is None or (key == "polycube"
                           and getattr(objs.get("mesh"), "Polycube", obj) != obj):
            continue
        state = obj.State
        if not ("Invalid" in state or "Error" in state or "Touched" in state):
            continue
        message = obj.getStatusString() if hasattr(obj, "getStatusString") else ""
        if not message or message == "Touched":
            message = "not computed"
        if key == "mesh":  # the pipeline's failure names the stage it stopped at
            stage = getattr(getattr(obj, "Proxy", None), "failed_stage", None) or stage
            if message.startswith(stage + ": "):
                message = message[len(stage) + 2:]
        raise MeshPartError("{} failed at {} ({}): {}".format(
            objs["mesh"].Label.rsplit("_mesh", 1)[0], stage, obj.Label, message), stage, objs)
    mesh = objs["mesh"]
    if mesh.InvertedCount and not allow_inverted:
        raise MeshPartError(
            "{}: {} inverted cells remain in the {} mesh (worst hex SJ {:.3f}); the objects are "
            "kept{}".format(mesh.Label, mesh.InvertedCount, getattr(mesh, "MeshingPath", "")
                            or "polycube", mesh.MinHexSJ,
                            "" if getattr(mesh, "MeshingPath", "") == "overlay" else
                            ": edit the Segmentation (Edit Patches) or switch the Polycube to "
                            "Manual and edit it (Build Polycube)"), "mesh", objs)
    return objs


def mesh_part(doc, part, size=0.0, level=core.MESH_OPTIONS["level"], improve=True, recompute=True,
              allow_inverted=False, method="auto", polycube_seconds=None, max_size=0.0,
              min_size=0.0, cells_across=None, order=1):
    """Meshes the Part solid ``part`` with no manual step, as `hexdom mesh` does (element size
    ``size``, 0: its default; ``level``; ``improve``; ``method`` "auto", "polycube" or "overlay";
    ``polycube_seconds``, None: the default budget; ``max_size``, ``min_size``: bounds on the
    size, 0: none; ``cells_across`` a thin part, None: the default; ``order`` 1 or 2, hex20 /
    wedge15 / tet10 as `hexdom mesh --order 2`),
    keeping every stage as an editable document object: HexDom Surface, Segmentation, Polycube
    and Mesh (see the module doc: the Mesh runs the pipeline once and fills the others).
    Returns a dict with keys surface, segmentation, polycube, mesh.

    With ``recompute`` the document is recomputed; a failure raises MeshPartError with the core's
    message, the objects kept in the document (``error.objects``); so do inverted cells left in
    the mesh, unless ``allow_inverted``."""
    objs = make_mesh_part(doc, part, size=size, level=level, improve=improve, method=method,
                          polycube_seconds=polycube_seconds, max_size=max_size, min_size=min_size,
                          cells_across=cells_across, order=order)
    if recompute:
        doc.recompute()
        check_mesh_part(objs, allow_inverted)
    return objs
