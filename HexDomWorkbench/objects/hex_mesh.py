"""HexDom Mesh: a hex-dominant volume mesh held in a Fem::FemMeshObjectPython.

The cells live in the FemMesh property (SMDS order, cell id = row + 1) and their region (block)
ids in the Region integer list; quality figures are read-only properties refreshed on every
recompute. Meshing stages plug in through ``HexMesh.generate``, which returns a new core.Mesh
that ``execute`` stores:

- with Segmentation and Polycube linked: the pipeline's generation at Level (2^Level cells per
  block edge) and, when Improve is true, its improvement (boundary nodes kept on the segmented
  surface), one core call with `hexdom mesh`'s options (core.mesh_structure); an automatic
  Polycube brings its own patch surface (the segmentation cut along its grid), which both stages
  then use instead of the Segmentation's patches;
- when the Segmentation's Surface tessellates a Part and the core has snap_to_brep (SnapToCAD
  true), the final boundary nodes are moved onto the CAD faces, so that FEM constraints on those
  faces find them (BrepDistance reports the largest distance left);
- Method chooses the path: "polycube" the above; "overlay" a grid laid over the Segmentation's
  Surface (core.mesh_surface(method="overlay"): no polycube needed; the Mesh's Size as element
  size, 0 the pipeline's default), snapped as above; "auto" (the default) the polycube when a Polycube
  is linked, else the overlay when the last run made the mesh with it (MeshingPath: Mesh Part's
  choice unlinks the Polycube when it keeps the overlay mesh), else the polycube (which then asks
  for the missing link). MeshingPath says which path made the mesh, PolycubeNote why the core's
  automatic choice tried the overlay (set by Mesh Part);
- Pipeline (Mesh Part): recompute runs `hexdom mesh`'s pipeline once (core.mesh_part on the
  Part the Surface tessellates, core.mesh_surface on the triangles of a mesh object or a file it reads, with Size, Level, Method, Improve, SnapToCAD and PolycubeSeconds:
  the options of `hexdom mesh --size --level --method --no-improve --no-snap --polycube-seconds`) and fills the Surface, the
  Segmentation and the Polycube with what it made (part_meshing.fill_mesh_part; they hold it,
  FromPipeline). Once one of them is edited (an input property, a patch or block edit) the Mesh
  leaves Pipeline and is built from them stage by stage, as above;
- with BaseMesh linked (another FEM mesh): a copy of it, improved when Improve is true;
- with no input (an imported mesh): None, the stored mesh stays.
"""

import math

import numpy as np

from .. import core
from ..convert import fem_setup, femmesh
from ..logic.stages import core_has
from ..progress import Progress
from . import chain, pipeline, polycube, segmentation, tessellation
from .base_object import BaseHexDomObject, is_of_type, set_read_only

TYPE = "HexDom::Mesh"
METHODS = ["auto", "polycube", "overlay"]
ELEMENT_ORDERS = ["1st", "2nd"]

# (property, type, group, tooltip); quality figures are read-only.
_QUALITY = [
    ("HexCount", "App::PropertyInteger", "Number of hexahedra"),
    ("PrismCount", "App::PropertyInteger", "Number of prisms (wedges)"),
    ("TetCount", "App::PropertyInteger", "Number of tetrahedra"),
    ("InvertedCount", "App::PropertyInteger",
     "Number of cells with scaled Jacobian <= 0 or degenerate, all types (second order: the curved "
     "cells, at their nodes and Gauss points)"),
    ("MinHexSJ", "App::PropertyFloat", "Minimum scaled Jacobian of the hexahedra (0 if none)"),
    ("MeanHexSJ", "App::PropertyFloat", "Mean scaled Jacobian of the hexahedra (0 if none)"),
    ("MinPrismSJ", "App::PropertyFloat", "Minimum scaled Jacobian of the prisms (0 if none)"),
    ("MeanPrismSJ", "App::PropertyFloat", "Mean scaled Jacobian of the prisms (0 if none)"),
    ("MinTetSJ", "App::PropertyFloat", "Minimum scaled Jacobian of the tetrahedra (0 if none)"),
    ("MeanTetSJ", "App::PropertyFloat", "Mean scaled Jacobian of the tetrahedra (0 if none)"),
    ("MaxEdgeRatio", "App::PropertyFloat", "Largest edge ratio (longest / shortest edge)"),
    ("MeshVolume", "App::PropertyFloat", "Sum of the cell volumes (second order: the curved cells')"),
]
QUALITY_PROPERTIES = [name for name, _, _ in _QUALITY]


def overlay_face_sizes(obj, surface_obj):
    """The Mesh ``obj``'s mesh regions as face_sizes for the Surface ``surface_obj`` (its
    triangles carry the face numbers of the Part it tessellates; none without a Part). Regions on
    edges need the pipeline (the B-rep's edges): ValueError saying so."""
    part = getattr(surface_obj, "Source", None)
    shape = getattr(part, "Shape", None)
    if not getattr(obj, "MeshRegionList", None) or shape is None or shape.isNull() or not shape.Solids:
        return None
    sizes = pipeline.region_sizes(obj, shape)
    if "edge_sizes" in sizes:
        raise ValueError("{}: mesh regions on edges are met by the pipeline (set Pipeline)".format(
            obj.Label))
    return sizes.get("face_sizes")


class HexMesh(BaseHexDomObject):
    """Proxy of a HexDom Mesh object."""

    Type = TYPE

    def add_properties(self, obj):
        super().add_properties(obj)
        if not hasattr(obj, "Level"):
            obj.addProperty("App::PropertyInteger", "Level", "HexDom",
                            "Subdivision level of the generation stage: 2^Level cells per "
                            "block edge")
            obj.Level = 2
        if not hasattr(obj, "SourceFile"):
            obj.addProperty("App::PropertyString", "SourceFile", "HexDom",
                            "File the mesh was imported from, if any")
        if not hasattr(obj, "Segmentation"):
            obj.addProperty("App::PropertyLink", "Segmentation", "Input",
                            "HexDom Segmentation: the surface and its patches")
        if not hasattr(obj, "Polycube"):
            obj.addProperty("App::PropertyLink", "Polycube", "Input",
                            "HexDom Polycube: the hex / prism / tet block structure")
        if not hasattr(obj, "BaseMesh"):
            obj.addProperty("App::PropertyLink", "BaseMesh", "Input",
                            "FEM mesh to copy (and improve) when there is no Segmentation and "
                            "Polycube")
        if not hasattr(obj, "Improve"):
            obj.addProperty("App::PropertyBool", "Improve", "HexDom",
                            "Improve quality after generation: pillowing, smoothing and "
                            "Jacobian optimisation, the core's recommended sequence")
            obj.Improve = True
        if not hasattr(obj, "SnapToCAD"):
            obj.addProperty("App::PropertyBool", "SnapToCAD", "HexDom",
                            "Move the boundary nodes onto the CAD faces of the Part the Surface "
                            "tessellates (when the core has snap_to_brep)")
            obj.SnapToCAD = True
        if not hasattr(obj, "BrepDistance"):
            obj.addProperty("App::PropertyFloat", "BrepDistance", "Quality",
                            "Largest distance of a boundary node from the CAD faces after "
                            "snapping; -1 when the nodes were not snapped")
            obj.BrepDistance = -1.0
        if not hasattr(obj, "Method"):
            obj.addProperty("App::PropertyEnumeration", "Method", "HexDom",
                            "Meshing path: polycube (Segmentation and Polycube: generate, improve), "
                            "overlay (a grid laid over the Segmentation's Surface, no polycube "
                            "needed) or auto (the polycube when a Polycube is linked, else the path "
                            "that made the mesh last: Mesh Part unlinks the Polycube when the "
                            "core's choice keeps the overlay mesh)")
            obj.Method = METHODS
            obj.Method = "auto"
        if not hasattr(obj, "MeshingPath"):
            obj.addProperty("App::PropertyString", "MeshingPath", "HexDom",
                            "The path that made the mesh: polycube or overlay (empty: imported or "
                            "copied)")
        if not hasattr(obj, "PolycubeNote"):
            obj.addProperty("App::PropertyString", "PolycubeNote", "HexDom",
                            "Why the core's automatic choice (Mesh Part, Method auto) tried the "
                            "overlay grid: the polycube path failed or its mesh missed a target; "
                            "empty when it did not")
        if not hasattr(obj, "Pipeline"):
            obj.addProperty("App::PropertyBool", "Pipeline", "HexDom",
                            "Mesh Part: recompute runs `hexdom mesh` (the core's pipeline) on the "
                            "Part the Surface tessellates, with Size, Level, Method, Improve and "
                            "SnapToCAD, and fills the Surface, Segmentation and Polycube from it; "
                            "false once one of them is edited: the mesh is built from them")
        if not hasattr(obj, "Size"):
            obj.addProperty("App::PropertyLength", "Size", "HexDom",
                            "Pipeline: the target element size (`hexdom mesh --size`); 0: the "
                            "bounding-box diagonal / 30 (of the box square to the axes the faces "
                            "fit)")
        if not hasattr(obj, "MaxSize"):
            obj.addProperty("App::PropertyLength", "MaxSize", "HexDom",
                            "Pipeline and overlay: the largest element size (`hexdom mesh "
                            "--max-size`); the Size, given or default, is at most this; 0: no bound")
        if not hasattr(obj, "MinSize"):
            obj.addProperty("App::PropertyLength", "MinSize", "HexDom",
                            "Pipeline and overlay: the smallest element size (`hexdom mesh "
                            "--min-size`): the Size is at least this, and cells made thinner for a "
                            "thin part are not shorter (it then gets fewer cells across); 0: no bound")
        if not hasattr(obj, "CellsAcross"):
            obj.addProperty("App::PropertyInteger", "CellsAcross", "HexDom",
                            "Pipeline and overlay: cells across a part thin along an axis, a plate "
                            "or a rod (`hexdom mesh --cells-across`); 0: cubic cells of the Size")
            obj.CellsAcross = int(core.MESH_OPTIONS.get("cells_across", 2))
        if not hasattr(obj, "PolycubeSeconds"):
            obj.addProperty("App::PropertyFloat", "PolycubeSeconds", "HexDom",
                            "Pipeline, Method auto: the polycube path's time budget in seconds "
                            "(`hexdom mesh --polycube-seconds`; 0: no limit), after which the "
                            "overlay grid's mesh is taken if the polycube has none that meets the "
                            "targets")
            obj.PolycubeSeconds = float(core.MESH_OPTIONS["polycube_seconds"])
        if not hasattr(obj, "TimeLimit"):
            obj.addProperty("App::PropertyFloat", "TimeLimit", "HexDom",
                            "Pipeline: seconds the whole meshing may take (`hexdom mesh "
                            "--time-limit`; 0: no limit); past it the run stops with an error "
                            "naming the step it was in, and the mesh stays as it was")
            obj.TimeLimit = float(core.MESH_OPTIONS.get("time_limit", 1800.0))
        if not hasattr(obj, "MeshRegionList"):
            obj.addProperty("App::PropertyLinkList", "MeshRegionList", "HexDom",
                            "Pipeline: FreeCAD FEM mesh regions (ObjectsFem.makeMeshRegion(doc, "
                            "this mesh, length), as for Gmsh): cells of their CharacteristicLength "
                            "on the faces they reference (`hexdom mesh --face-size`); both paths "
                            "refine by thirds near those faces, auto keeps the mesh nearer the lengths")
        if not hasattr(obj, "GrowthRate"):
            obj.addProperty("App::PropertyFloat", "GrowthRate", "HexDom",
                            "With mesh regions: how fast cells grow from a region's length back to "
                            "the element size, per cell, in (1, 3] (`hexdom mesh --growth-rate`); "
                            "the band of small cells around the faces is wider the smaller it is")
            obj.GrowthRate = float(core.MESH_OPTIONS.get("growth_rate", 3 ** 0.25))
        if not hasattr(obj, "PillowCurves"):
            obj.addProperty("App::PropertyBool", "PillowCurves", "HexDom",
                            "Overlay grid: a sheet of wedges along each CAD edge, so that every "
                            "boundary face lies on one CAD face and FreeCAD's face loads and "
                            "constraints take them all (`hexdom mesh --pillow-curves`); more cells, "
                            "and on some parts a lower worst scaled Jacobian")
            obj.PillowCurves = bool(core.MESH_OPTIONS.get("pillow_curves", False))
        if not hasattr(obj, "ElementOrder"):
            obj.addProperty("App::PropertyEnumeration", "ElementOrder", "HexDom",
                            "1st: hex8, wedge6, tet4; 2nd: hex20, wedge15, tet10 (as FreeCAD's Gmsh "
                            "mesh), a node on every cell edge, those of the boundary on the CAD "
                            "faces and edges (`hexdom mesh --order 2`)")
            obj.ElementOrder = ELEMENT_ORDERS
            obj.ElementOrder = "1st"
        if not hasattr(obj, "LocalSizes"):
            obj.addProperty("App::PropertyStringList", "LocalSizes", "HexDom",
                            "Per face or edge of the mesh regions (MeshRegionList): how near their "
                            "length the cells there are, the median cell over the length "
                            "(\"Face10: cells 0.84 of 1 (within 20%)\"); empty without regions")
        if not hasattr(obj, "Region"):
            obj.addProperty("App::PropertyIntegerList", "Region", "HexDom",
                            "Region (block) id of each cell, in cell-id order")
        for name, prop_type, doc in _QUALITY:
            if not hasattr(obj, name):
                obj.addProperty(prop_type, name, "Quality", doc)
        set_read_only(obj, ["SourceFile", "BrepDistance", "MeshingPath", "PolycubeNote", "LocalSizes"]
                      + QUALITY_PROPERTIES)
        obj.setEditorMode("Region", 2)  # hidden: one entry per cell

    def generate(self, obj):
        """New core.Mesh from the inputs (see the module doc), or None to keep the stored one."""
        seg = getattr(obj, "Segmentation", None)
        poly = getattr(obj, "Polycube", None)
        base = getattr(obj, "BaseMesh", None)
        if seg is None and poly is None:
            if base is None:
                return None
            if base == obj:
                raise ValueError("{}: BaseMesh links the mesh itself".format(obj.Label))
            mesh = get_mesh(base)
            if obj.Improve:
                with Progress("Improving " + obj.Label, 1) as bar:
                    mesh = bar.run("improve", core.improve, mesh, max_edge_ratio=core.TARGET_EDGE_RATIO)
                    bar.step("improved")
            return mesh
        if getattr(obj, "Pipeline", False):
            objs = chain.objects_of(obj)
            if pipeline.held_by_pipeline(objs):
                run = pipeline.run_pipeline(objs)
                self.path = run.method
                if run.snap:
                    self.brep_distance = float(run.snap["max_distance"])
                    self.node_faces = run.snap.get("faces")
                return run.mesh
            pipeline.leave_pipeline(objs)
        self.path = meshing_path(obj)
        self.local_sizes = []  # the stages' polycube mesh has no regions; the overlay's says below
        if self.path == "overlay":
            return self.overlay(obj)
        if getattr(obj, "MeshRegionList", None):
            import FreeCAD
            FreeCAD.Console.PrintWarning(
                "HexDom: {}: its mesh regions are met by the pipeline and the overlay grid; the "
                "polycube stages build the mesh without them\n".format(obj.Label))
        if seg is None or poly is None:
            hint = ""
            if seg is not None and poly is None:
                found = polycubes_of(seg)
                if found:
                    hint = " ({} goes with {})".format(found[0].Label, seg.Label)
            raise ValueError("{}: link both a Segmentation and a Polycube (or neither){}".format(
                obj.Label, hint))
        surface = polycube.get_patch_surface(poly)
        if surface is None:
            surface = segmentation.get_surface(seg)
        structure = polycube.get_structure(poly)
        if obj.Level < 0:
            raise ValueError("{}: Level must be 0 or more".format(obj.Label))
        snap = snap_source(obj)
        second = element_order(obj) == 2
        with Progress("Meshing " + obj.Label, 1 + bool(snap) + second) as bar:
            # The pipeline's own stage (generate, then improve), with its options.
            run = bar.run("generate and improve" if obj.Improve else "generate", core.mesh_structure,
                          surface, structure, level=obj.Level, improve=bool(obj.Improve),
                          frame=segmentation.frame_matrix(seg),
                          stretch=segmentation.stretch_factors(seg))
            mesh = run.mesh
            bar.step("{hex} hex, {prism} prism, {tet} tet".format(**mesh.counts))
            info = None
            if snap:
                brep, cad_surface = snap
                mesh, info = bar.run("snap to CAD", core.snap_to_brep, mesh, brep, cad_surface,
                                     max_edge_ratio=core.TARGET_EDGE_RATIO)
                self.brep_distance = float(info["max_distance"])
                self.node_faces = info.get("faces")
                bar.step("snapped to the CAD faces: {:.3g}".format(self.brep_distance))
            if second:
                mesh = self.second_order(bar, mesh, surface, snap, info)
        return mesh

    @staticmethod
    def second_order(bar, mesh, surface, snap, info):
        """The stage-built ``mesh`` made second order: the boundary's mid-edge nodes on the B-rep
        when it was snapped (``snap``: (BREP text, its tessellation), ``info`` the snap's report),
        else on ``surface``."""
        if snap:
            brep, cad_surface = snap
            mesh, report = bar.run("second order", core.second_order, mesh, cad_surface, brep, info)
        else:
            mesh, report = bar.run("second order", core.second_order, mesh, surface)
        bar.step("second order: {} boundary mid-edge nodes, {} kept off the geometry".format(
            report["boundary_mid_nodes"], report["shortened"] + report["straight"]))
        return mesh

    def onChanged(self, obj, prop):
        # Pipeline set by the user: the stage objects are to be filled by the pipeline again;
        # cleared: they compute as stages from now on.
        if prop != "Pipeline" or chain.restoring(obj) or chain.filling.active():
            return
        if getattr(obj, "Pipeline", False):
            pipeline.enter_pipeline(chain.objects_of(obj))
        else:
            chain.stage_edited(obj)

    def overlay(self, obj):
        """The overlay path: core.mesh_surface(method="overlay") on the Segmentation's Surface,
        then snapped onto the CAD faces as the polycube path's mesh is."""
        seg = getattr(obj, "Segmentation", None)
        surface_obj = getattr(seg, "Surface", None)
        if seg is None or surface_obj is None:
            raise ValueError("{}: Method overlay meshes the Surface of a Segmentation: link "
                             "one".format(obj.Label))
        surface = tessellation.get_surface(surface_obj)
        poly = getattr(obj, "Polycube", None)
        if hasattr(obj, "Size"):  # the element size the pipeline takes (0: its default)
            size = float(obj.Size.Value)
        else:  # a document older than Size
            size = float(poly.Size.Value) if poly is not None else float(surface_obj.Size.Value)
        # Laid in the frame the faces fit when the Segmentation has one (as Mesh Part's choice).
        align = segmentation.frame_matrix(seg) is not None
        snap = snap_source(obj)
        second = element_order(obj) == 2
        face_sizes = overlay_face_sizes(obj, surface_obj)
        with Progress("Meshing " + obj.Label + " (overlay grid)", 1 + bool(snap) + second) as bar:
            run = bar.run("overlay grid", core.mesh_surface, surface, size=size, method="overlay",
                          align=align, improve=bool(obj.Improve), allow_inverted=True,
                          face_sizes=face_sizes,
                          pillow_curves=bool(getattr(obj, "PillowCurves", False)), **pipeline.size_bounds(obj))
            mesh = run.mesh
            self.local_sizes = pipeline.local_size_lines({"face_sizes": face_sizes or {}}, run)
            bar.step("overlay grid: {hex} hex, {prism} prism, {tet} tet".format(**mesh.counts))
            if snap:
                brep, cad_surface = snap
                # The overlay's nodes on smooth regions go onto their CAD faces only, as
                # `hexdom mesh` snaps them (run.face_only).
                mesh, info = bar.run("snap to CAD", core.snap_to_brep, mesh, brep, cad_surface,
                                     max_edge_ratio=core.TARGET_EDGE_RATIO,
                                     face_only=getattr(run, "face_only", None) or None)
                self.brep_distance = float(info["max_distance"])
                self.node_faces = info.get("faces")
                bar.step("snapped to the CAD faces: {:.3g}".format(self.brep_distance))
            if second:
                mesh = self.second_order(bar, mesh, surface, snap, info if snap else None)
        return mesh

    def execute(self, obj):
        self.brep_distance = -1.0
        self.path = None
        self.local_sizes = None  # the stages' LocalSizes (the pipeline sets its own)
        self.node_faces = None  # the snap's CAD faces of each node, when it ran
        mesh = self.generate(obj)
        if mesh is not None:
            store_mesh(obj, mesh, cad_face_surface(obj) if core_has("face_sets") else None,
                       self.node_faces)
            if hasattr(obj, "BrepDistance") and obj.BrepDistance != self.brep_distance:
                obj.BrepDistance = self.brep_distance
            if self.path is not None and hasattr(obj, "MeshingPath"):
                if obj.MeshingPath != self.path:
                    obj.MeshingPath = self.path
                # The note is the automatic choice's: a forced path has none.
                if getattr(obj, "Method", "auto") != "auto" and obj.PolycubeNote:
                    obj.PolycubeNote = ""
            lines = self.local_sizes
            if lines is not None and hasattr(obj, "LocalSizes") and list(obj.LocalSizes) != lines:
                obj.LocalSizes = lines
        else:
            update_quality(obj)


def element_order(obj):
    """1 or 2: the HexDom Mesh ``obj``'s ElementOrder ("1st" for a document older than it)."""
    return 2 if getattr(obj, "ElementOrder", "1st") == "2nd" else 1


def meshing_path(obj):
    """The path recomputing HexDom Mesh ``obj`` takes: "polycube" or "overlay" (see Method)."""
    method = getattr(obj, "Method", "auto")
    if method in ("polycube", "overlay"):
        return method
    if getattr(obj, "Polycube", None) is None and getattr(obj, "MeshingPath", "") == "overlay":
        return "overlay"
    return "polycube"


polycubes_of = chain.polycubes_of  # The HexDom Polycubes built on a Segmentation


def _part_shape(obj):
    """(Shape, Surface object) of the Part behind HexDom Mesh ``obj``'s Segmentation, or None."""
    seg = getattr(obj, "Segmentation", None)
    surface_obj = getattr(seg, "Surface", None)
    shape = getattr(fem_setup.meshed_part(obj), "Shape", None)
    if shape is None or shape.isNull() or not shape.Faces:
        return None
    return shape, surface_obj


def cad_face_surface(obj):
    """The tessellation, with the Part's face numbers, that HexDom Mesh ``obj`` was made from, or
    None when no Part is behind its Segmentation."""
    found = _part_shape(obj)
    return None if found is None else tessellation.get_surface(found[1])


def snap_source(obj):
    """(BREP text, core.Surface with CAD face ids) to snap the mesh of HexDom Mesh ``obj`` to, or
    None: SnapToCAD off, the core without snap_to_brep, or no Part behind the Segmentation."""
    if not getattr(obj, "SnapToCAD", False) or not core_has("snap_to_brep"):
        return None
    found = _part_shape(obj)
    if found is None:
        return None
    return found[0].exportBrepToString(), tessellation.get_surface(found[1])


def is_hex_mesh(obj):
    return is_of_type(obj, TYPE)


def has_inputs(obj):
    """True if the HexDom Mesh is generated from a Segmentation and a Polycube, or from a
    Segmentation's Surface by the overlay grid."""
    if getattr(obj, "Segmentation", None) is None:
        return False
    return getattr(obj, "Polycube", None) is not None or meshing_path(obj) == "overlay"


def get_mesh(obj):
    """core.Mesh of a FEM mesh object; region ids from obj.Region when it fits."""
    mesh = femmesh.from_femmesh(obj.FemMesh)
    region = list(getattr(obj, "Region", []))
    if len(region) == len(mesh.types):
        mesh.region = np.asarray(region, dtype=np.int32)
    return mesh


def store_mesh(obj, mesh, surface=None, node_faces=None):
    """Puts ``mesh`` into obj (FemMesh, Region) and refreshes the quality properties. With
    ``surface`` (the tessellation it was made from, CAD face ids), the FemMesh gets a node group
    Face<k> per CAD face (core.face_sets, with ``node_faces``, the snap's CAD faces of each node,
    when it was snapped), and one per constraint of the analyses holding obj
    (fem_setup.add_constraint_groups)."""
    fem = femmesh.to_femmesh(mesh)
    if surface is not None:
        faces = {fem_setup.FACE_GROUP.format(k): nodes
                 for k, nodes in core.face_sets(mesh, surface, node_faces).items()}
        groups = dict(faces)
        part = fem_setup.meshed_part(obj)
        for analysis in getattr(obj, "InList", []):
            if analysis.isDerivedFrom("Fem::FemAnalysis"):
                groups.update(fem_setup.constraint_groups(analysis, part, faces))
        femmesh.set_node_groups(fem, groups)
    obj.FemMesh = fem  # one assignment, the groups with it
    obj.Region = [int(r) for r in np.asarray(mesh.region).tolist()]
    update_quality(obj, mesh)


def _finite(value):
    return float(value) if value is not None and math.isfinite(value) else 0.0


def update_quality(obj, mesh=None):
    """Sets the read-only quality properties from core.quality_report."""
    if mesh is None:
        mesh = get_mesh(obj)
    report = core.quality_report(mesh)
    values = {"InvertedCount": 0, "MaxEdgeRatio": 0.0,
              "MeshVolume": _finite(report.get("total_volume"))}
    for key, stem in (("hex", "Hex"), ("prism", "Prism"), ("tet", "Tet")):
        stats = report[key]
        values[stem + "Count"] = int(stats["count"])
        values["Min{}SJ".format(stem)] = _finite(stats["sj_min"])
        values["Mean{}SJ".format(stem)] = _finite(stats["sj_mean"])
        if report.get("order", 1) == 1:
            values["InvertedCount"] += int(stats["inverted"])
        if stats["count"]:
            values["MaxEdgeRatio"] = max(values["MaxEdgeRatio"], _finite(stats["edge_ratio_max"]))
    if report.get("order", 1) == 2:  # the curved cells' (nodes and Gauss points)
        values["InvertedCount"] = sum(int(report[k]["inverted"]) for k in ("hex20", "wedge15", "tet10"))
    for name, value in values.items():
        if getattr(obj, name) != value:
            setattr(obj, name, value)
    return report
