"""Mesh Part's pipeline in the document objects: the HexDom Mesh with Pipeline on runs `hexdom
mesh`'s pipeline once (run_pipeline: core.mesh_part with the Mesh's options) and fill_mesh_part
puts what it made into the Surface, Segmentation and Polycube, which hold it (FromPipeline; see
chain.py for what an edit does). See part_meshing for Mesh Part itself."""

import numpy as np

from .. import core
from ..logic.labels import patches_from_labels
from ..logic.stages import core_has, has_cad
from ..progress import Cancelled, Progress
from ..shape_tessellation import tessellate
from . import polycube, segmentation, tessellation
from .chain import filling, follow_level, stages


def part_size(shape):
    """Target element size `hexdom mesh` takes for ``shape`` when given 0: the bounding-box
    diagonal / 30; for a part lying at an angle (its faces fit axes turned from the model's,
    core.cube_frame on a first tessellation), the diagonal of the box square to those axes / 30.
    (The pipeline computes it itself; this is for a build without OpenCASCADE.)"""
    size = shape.BoundBox.DiagonalLength / 30.0
    if has_cad() and core_has("cube_frame"):
        try:
            V, F, face = core.tessellate_brep(shape.exportBrepToString(), size=size)
        except core.Error:
            return size
        frame = core.cube_frame(core.Surface(V, F, face))
        if frame["turned"]:
            size = core.frame_diagonal(core.Surface(V, F, face), frame["rotation"]) / 30.0
    return size


def held_by_pipeline(objs):
    """True when the Mesh's Surface, Segmentation and Polycube all hold what the pipeline put
    there (FromPipeline) and the Surface tessellates a Part or takes the triangles of a mesh
    object or a file: the Mesh may run the pipeline."""
    surface = objs.get("surface")
    part = getattr(surface, "Source", None)
    return (surface is not None and objs.get("segmentation") is not None
            and (getattr(part, "Shape", None) is not None or tessellation.takes_triangles(surface))
            and all(getattr(o, "FromPipeline", False) for o in stages(objs)))


def enter_pipeline(objs):
    """The stage objects are to be filled by the Mesh's pipeline (FromPipeline set)."""
    with filling():
        follow_level(objs["mesh"], None)
        for o in stages(objs):
            if hasattr(o, "FromPipeline") and not o.FromPipeline:
                o.FromPipeline = True


def leave_pipeline(objs):
    """An input of a stage object was edited: the Mesh is built from the stages from now on
    (Pipeline off, the stage objects compute again, the Mesh's Level the Polycube's, for which
    its blocks are made). Says so in the report view."""
    import FreeCAD
    mesh, poly = objs["mesh"], objs.get("polycube")
    with filling():
        for o in stages(objs):
            if getattr(o, "FromPipeline", False):
                o.FromPipeline = False
                o.purgeTouched()
        if getattr(mesh, "Pipeline", False):
            mesh.Pipeline = False
        if poly is not None and getattr(mesh, "Polycube", None) is poly:
            if mesh.Level != poly.Level:
                mesh.Level = poly.Level
            follow_level(mesh, poly)
    FreeCAD.Console.PrintMessage(
        "HexDom: {}: a stage was edited; the mesh is now built from the Segmentation and the "
        "Polycube (set Pipeline to run `hexdom mesh` again)\n".format(mesh.Label))


def size_bounds(mesh):
    """The HexDom Mesh ``mesh``'s MaxSize, MinSize, CellsAcross and GrowthRate as the core's
    keywords max_size, min_size, cells_across and growth_rate (those a document older than them
    lacks left out)."""
    bounds = {}
    for prop, key in (("MaxSize", "max_size"), ("MinSize", "min_size")):
        if hasattr(mesh, prop):
            bounds[key] = float(getattr(mesh, prop).Value)
    if hasattr(mesh, "CellsAcross"):
        bounds["cells_across"] = float(mesh.CellsAcross)
    if hasattr(mesh, "GrowthRate"):
        bounds["growth_rate"] = float(mesh.GrowthRate)
    return bounds


def region_sizes(mesh, shape):
    """{"face_sizes": {face number: size}, "edge_sizes": {edge number: size}} (the empty ones left
    out) of ``shape``'s first solid (the one meshed) from the HexDom Mesh ``mesh``'s MeshRegionList:
    FreeCAD's FEM mesh regions (or any object with References and a CharacteristicLength), each
    face or edge taking the smallest length that names it. Raises ValueError (the Mesh's recompute
    error) naming the region for a length that is not positive, a reference that is neither a face
    nor an edge, or one that is not the solid's."""
    regions = getattr(mesh, "MeshRegionList", None) or []
    solid = shape.Solids[0]
    sizes = {"Face": {}, "Edge": {}}
    for region in regions:
        length = getattr(region, "CharacteristicLength", 0.0)
        length = float(getattr(length, "Value", length))
        if not length > 0:
            raise ValueError("mesh region {}: its CharacteristicLength must be positive".format(
                region.Label))
        for obj, subs in getattr(region, "References", []):
            for sub in subs:
                kind = "Face" if sub.startswith("Face") else "Edge" if sub.startswith("Edge") else None
                if kind is None:
                    raise ValueError("mesh region {}: {} of {}: HexDom takes sizes on faces and "
                                     "edges only".format(region.Label, sub, obj.Label))
                element = obj.Shape.getElement(sub)
                items = solid.Faces if kind == "Face" else solid.Edges
                number = next((i for i, f in enumerate(items, 1) if f.isSame(element)), None)
                if number is None:
                    raise ValueError("mesh region {}: {} of {} is not a {} of the part "
                                     "meshed".format(region.Label, sub, obj.Label, kind.lower()))
                found = sizes[kind]
                found[number] = min(found.get(number, length), length)
    return {key: sizes[kind] for key, kind in (("face_sizes", "Face"), ("edge_sizes", "Edge"))
            if sizes[kind]}


def local_size_lines(options, run):
    """The HexDom Mesh's LocalSizes: one line per face or edge size of ``options`` (face_sizes, then
    edge_sizes, each by number, the order the core measures them in) with the core.MeshRun
    ``run``'s local_size_ratios and whether the core counts each as met, "Face10: cells 0.84 of 1
    (within 20%)"; empty when the run measured none."""
    named = [("Face{}".format(k), s) for k, s in sorted(options.get("face_sizes", {}).items())]
    named += [("Edge{}".format(k), s) for k, s in sorted(options.get("edge_sizes", {}).items())]
    ratios, met = run.local_size_ratios or [], run.local_size_met or []
    if not ratios or len(ratios) != len(named) or len(met) != len(named):
        return []
    return ["{}: cells {:.2f} of {:g} ({})".format(name, r, size, "within 20%" if ok else "not within 20%")
            for (name, size), r, ok in zip(named, ratios, met)]


def pipeline_options(mesh, shape=None):
    """The options of `hexdom mesh` the HexDom Mesh ``mesh`` runs the pipeline with (with
    ``shape``, the part's, also its mesh regions' face_sizes and edge_sizes)."""
    method = getattr(mesh, "Method", "auto")
    options = dict(size=float(mesh.Size.Value), level=int(mesh.Level), improve=bool(mesh.Improve),
                   method=method,
                   snap=bool(getattr(mesh, "SnapToCAD", True)) and core_has("snap_to_brep"),
                   **size_bounds(mesh))
    if getattr(mesh, "ElementOrder", "1st") == "2nd":
        options["order"] = 2
    if method == "auto" and hasattr(mesh, "PolycubeSeconds"):  # (polycube: no limit, as the CLI)
        options["polycube_seconds"] = float(mesh.PolycubeSeconds)
    if hasattr(mesh, "TimeLimit"):
        options["time_limit"] = float(mesh.TimeLimit)
    if getattr(mesh, "PillowCurves", False):
        options["pillow_curves"] = True
    if shape is not None:
        options.update(region_sizes(mesh, shape))
    return options


def run_pipeline(objs, store_mesh=None, run=None):
    """Runs `hexdom mesh`'s pipeline for mesh_part's objects (the Mesh's options,
    pipeline_options) on the Part the Surface tessellates and fills the objects from it
    (fill_mesh_part; the Mesh itself only with ``store_mesh``: its execute stores the mesh).
    core.mesh_part (tessellate, mesh, snap) when the build has OpenCASCADE, else core.mesh_surface
    on FreeCAD's tessellation (no snap). The core call runs in a Progress (a worker thread under
    the GUI; Cancel raises progress.Cancelled), or in ``run``. Inverted cells left are kept and
    counted (the Mesh's InvertedCount). Returns the core.MeshRun."""
    mesh, surface_obj = objs["mesh"], objs["surface"]
    if tessellation.takes_triangles(surface_obj):
        return run_surface_pipeline(objs, tessellation.triangle_input(surface_obj), store_mesh, run)
    part = surface_obj.Source
    shape = part.Shape
    if shape is None or shape.isNull() or not shape.Solids:
        raise ValueError("{}: {} has no solid to mesh".format(mesh.Label, part.Label))
    options = pipeline_options(mesh, shape)
    snap = options.pop("snap")
    mesh.Proxy.failed_stage = None
    surface, size = None, 0.0
    try:
        with Progress("Meshing " + part.Label, 1) as bar:
            call = run or bar.run
            if hasattr(getattr(core, "_hexdom", None), "mesh_cad") and has_cad():
                result = call("hexdom mesh", core.mesh_part, shape.exportBrepToString(),
                              snap=snap, allow_inverted=True, **options)
            else:  # no OpenCASCADE in the core: FreeCAD's tessellation, not snapped
                if options.pop("edge_sizes", None):
                    raise ValueError("{}: mesh regions on edges need _hexdom built with "
                                     "OpenCASCADE".format(mesh.Label))
                size = options["size"] or part_size(shape)
                if options.get("max_size"):  # the triangles within the bounds, as the core's
                    size = min(size, options["max_size"])
                if options.get("min_size"):
                    size = max(size, options["min_size"])
                surface = tessellate(shape, size=size, deflection=size / 50.0, angle=30.0)
                result = call("hexdom mesh", core.mesh_surface, surface, allow_inverted=True,
                              **dict(options, size=size))
            bar.step(result.method + ": " + result.choice)
    except Cancelled:
        raise
    except core.Error as e:
        raise failed(objs, e, surface, size, "tessellate") from e
    if surface is not None:
        result.surface, result.tessellation_size = surface, size
    say_warnings(mesh, result)
    fill_mesh_part(objs, result, store_mesh=store_mesh)
    lines = local_size_lines(options, result)
    if hasattr(mesh, "LocalSizes") and list(mesh.LocalSizes) != lines:
        mesh.LocalSizes = lines
    return result


def run_surface_pipeline(objs, triangles, store_mesh=None, run=None):
    """run_pipeline for a Surface that takes triangles as they are (``triangles``: what
    tessellation.triangle_input gives): `hexdom mesh FILE`'s pipeline, core.mesh_surface with the
    Mesh's options (its input checks: a shell turned around, several solids each meshed as a region,
    solids touching; no snap: there is no B-rep). The Surface gets the triangles; the Segmentation
    and the Polycube the run's when it meshed one solid, nothing for several (they hold one solid).
    Mesh regions need a Part's faces: ValueError."""
    mesh = objs["mesh"]
    surface, name, _ = triangles
    if getattr(mesh, "MeshRegionList", None):
        raise ValueError("{}: mesh regions name a Part's faces or edges; {} is triangles".format(
            mesh.Label, name))
    options = pipeline_options(mesh)
    options.pop("snap")
    mesh.Proxy.failed_stage = None
    try:
        with Progress("Meshing " + name, 1) as bar:
            result = (run or bar.run)("hexdom mesh", core.mesh_surface, surface, allow_inverted=True,
                                      **options)
            bar.step(result.method + ": " + result.choice)
    except Cancelled:
        raise
    except core.Error as e:
        raise failed(objs, e, surface, 0.0, "check the input") from e
    result.surface = surface
    if result.solids > 1:
        result.labels = None  # (the solids' labels, solid by solid: not the Surface's order)
    say_warnings(mesh, result)
    fill_mesh_part(objs, result, store_mesh=store_mesh)
    return result


def failed(objs, error, surface, size, first_stage):
    """The core.Error ``error`` of a pipeline run, prefixed with the stage it stopped at, for the
    Mesh to raise: the stages that finished are filled (fill_mesh_part, the Mesh left alone) and
    the Mesh marked failed at that stage (Proxy.failed_stage); ``first_stage`` names it when no
    stage finished or the input checks refused the triangles (shown in the Surface then).
    ``surface`` (and its ``size``): the triangles meshed, when the run does not carry them
    (FreeCAD's tessellation, a mesh object's triangles)."""
    partial = getattr(error, "run", None)
    core_stage = getattr(error, "stage", "")
    stage = STAGE_OF_CORE.get(core_stage, "generate and improve")
    if partial is not None and surface is not None:
        partial.surface, partial.tessellation_size = surface, size
    if partial is not None and partial.surface is not None and len(partial.surface.F):
        fill_mesh_part(objs, partial, stages_only=True)  # (refused by the checks: the triangles shown)
    else:
        stage = first_stage
    if core_stage == "check":
        stage = first_stage
    objs["mesh"].Proxy.failed_stage = stage
    return type(error)("{}: {}".format(stage, error))


def say_warnings(mesh, result):
    """Prints the pipeline's warnings (core.MeshRun.warnings) in the report view."""
    import FreeCAD
    for w in result.warnings or []:
        FreeCAD.Console.PrintWarning("HexDom: {}: {}\n".format(mesh.Label, w))

# The stage of mesh_part's objects where each stage of the core's pipeline (MeshRun.stage) runs.
STAGE_OF_CORE = {"": "tessellate", "segment": "segment", "autopolycube": "automatic polycube",
                 "generate": "generate and improve", "improve": "generate and improve",
                 "overlay": "generate and improve", "done": "generate and improve"}


def fill_mesh_part(objs, result, store_mesh=None, stages_only=False):
    """Puts what the pipeline's core.MeshRun ``result`` made into mesh_part's objects, which then
    hold it (FromPipeline, not touched): the Surface gets the tessellation meshed (Size and
    Deflection its own), the Segmentation its labels (EdgeWeight, Frame), the Polycube its
    blocks and patch surface (Size, Level, KeepWidths, TetApexes); an attempt that made none
    (the overlay's mesh kept after the polycube failed early) leaves them empty. With
    ``store_mesh`` (hex_mesh.store_mesh) the Mesh gets the mesh, BrepDistance and MeshingPath; its
    PolycubeNote and Polycube link (none when the overlay's mesh was kept) always, unless
    ``stages_only`` (what the stages of a failed run made: the Mesh is left alone)."""
    surface_obj, seg, poly, mesh = (objs["surface"], objs["segmentation"], objs.get("polycube"),
                                    objs["mesh"])
    with filling():
        tsize = float(getattr(result, "tessellation_size", 0.0) or 0.0)
        if result.surface is not None:
            tessellation.store_surface(surface_obj, result.surface)
            if tsize > 0:
                surface_obj.Size = tsize
                surface_obj.Deflection = tsize / 50.0
                surface_obj.Angle = 30.0
            surface_obj.Method = "pipeline"
        labels = result.labels
        n = len(result.surface.F) if result.surface is not None else -1
        if labels is not None and len(labels.F) == n and n > 0:
            segmentation.store_segmentation(seg, labels.patch,
                                            patches_from_labels(labels.F, labels.patch))
        else:
            segmentation.store_segmentation(seg, [], [])
        seg.EdgeWeight = float(result.edge_weight)
        if hasattr(seg, "Frame") and result.frame is not None:
            segmentation.set_frame(seg, result.frame["rotation"] if result.frame["turned"]
                                   else None)
        segmentation.set_stretch(seg, result.stretch)
        if list(seg.Issues):
            seg.Issues = []
        if poly is not None:
            fill_polycube(poly, result, mesh)
        if store_mesh is not None:
            store_mesh(mesh, result.mesh, result.surface if core_has("face_sets") else None,
                       result.snap.get("faces") if result.snap else None)
            mesh.BrepDistance = float(result.snap["max_distance"]) if result.snap else -1.0
            mesh.MeshingPath = result.method
        if not stages_only:
            if mesh.PolycubeNote != result.polycube_note:
                mesh.PolycubeNote = result.polycube_note
            linked = None if result.method == "overlay" else poly
            if mesh.Polycube is not linked:
                mesh.Polycube = linked
        for o in stages(objs):
            if hasattr(o, "FromPipeline") and not o.FromPipeline:
                o.FromPipeline = True
            o.purgeTouched()
        if store_mesh is not None:
            mesh.purgeTouched()


def fill_polycube(poly, result, mesh):
    """The Polycube part of fill_mesh_part: the kept candidate's (or the polycube path's attempt's)
    blocks, patch surface and options, Mode Automatic; no blocks when the attempt made none."""
    structure = result.polycube.structure if result.polycube is not None else None
    if poly.Mode != "Automatic":
        poly.Mode = "Automatic"
    if structure is not None and len(structure.types):
        polycube.store_structure(poly, structure)
        polycube.store_patch_surface(poly, result.polycube.patches)
        info = result.polycube.info
        for name, _, _, key in polycube._AUTO_RESULTS:
            value = info.get(key)
            if value is not None:
                value = type(getattr(poly, name))(value)
                if getattr(poly, name) != value:
                    setattr(poly, name, value)
        level = int(result.level)
        cell = float(info.get("cell", 0.0) or 0.0)
        if cell > 0:
            poly.Size = cell / 2 ** level
    else:
        polycube.store_structure(poly, core.Mesh(np.zeros((0, 3)), np.zeros((0, 8), np.int32),
                                                 np.zeros(0, np.int32), np.zeros(0, np.int32)))
        polycube.store_patch_surface(poly, None)
        level = int(mesh.Level)
    poly.Level = level
    poly.KeepWidths = bool(result.keep_widths)
    poly.TetApexes = bool(result.collapse_apexes)
