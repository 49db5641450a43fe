"""HexDom Surface: the triangle surface of a Part solid with the CAD face number per triangle.

Holds the triangles in properties (Points, Triangles as a flat list of point indices, FaceId per
triangle: 1-based, triangle t lies on Face<FaceId[t]> of the source shape), so the document keeps
them and the segmentation reads them back as a core.Surface. The source is a Part object
(Source, tessellated with Size / Deflection / Angle by shape_tessellation.tessellate), a FreeCAD
mesh object (Source: an STL or OBJ opened in FreeCAD, its triangles taken as they are, FaceId 1)
or, when Source is empty, a triangle file (SourceFile: .k shells with part id per triangle, .stl,
.obj, .vtk; the part ids become FaceId). Triangles from a mesh or a file are checked as every
meshing path checks its input (core.check_surface). With neither, the object keeps the triangles it was given; so does a
Surface Mesh Part's pipeline filled (FromPipeline, see base_object.BaseHexDomObject).
"""

import os

import numpy as np

from .. import core
from ..progress import Progress
from ..shape_tessellation import tessellate
from .base_object import BaseHexDomObject, is_of_type, set_read_only

TYPE = "HexDom::Surface"

_RESULTS = [
    ("TriangleCount", "Number of triangles"),
    ("PointCount", "Number of points"),
    ("FaceCount", "Number of distinct face (patch) ids"),
]


class Surface(BaseHexDomObject):
    """Proxy of a HexDom Surface object (App::FeaturePython)."""

    Type = TYPE
    STAGE_INPUTS = ("Source", "SourceFile", "Size", "Deflection", "Angle")

    def add_properties(self, obj):
        super().add_properties(obj)
        self.add_pipeline_flag(obj)
        if not hasattr(obj, "Source"):
            obj.addProperty("App::PropertyLink", "Source", "Input",
                            "Part object (a solid) whose faces are tessellated, or a mesh object "
                            "(an STL or OBJ opened in FreeCAD) whose triangles are taken")
        if not hasattr(obj, "SourceFile"):
            obj.addProperty("App::PropertyFile", "SourceFile", "Input",
                            "Triangle surface file (.k, .stl, .obj, .vtk) read when Source is "
                            "empty; .k part ids become face ids")
        if not hasattr(obj, "Size"):
            obj.addProperty("App::PropertyLength", "Size", "Tessellation",
                            "Target triangle edge length; 0 chooses 1/25 of the bounding-box "
                            "diagonal")
        if not hasattr(obj, "Deflection"):
            obj.addProperty("App::PropertyLength", "Deflection", "Tessellation",
                            "Largest chord distance between the triangles and the CAD surface; "
                            "0 chooses Size / 10")
        if not hasattr(obj, "Angle"):
            obj.addProperty("App::PropertyAngle", "Angle", "Tessellation",
                            "Largest turn between neighbouring chords on curved faces")
            obj.Angle = 20.0
        if not hasattr(obj, "Method"):
            obj.addProperty("App::PropertyString", "Method", "Tessellation",
                            "What made the triangles: core (OCCT in HexDom), MeshPart "
                            "(FreeCAD: Mefisto, or standard), file or stored")
        for name, doc in _RESULTS:
            if not hasattr(obj, name):
                obj.addProperty("App::PropertyInteger", name, "Result", doc)
        if not hasattr(obj, "Points"):
            obj.addProperty("App::PropertyVectorList", "Points", "Result",
                            "Triangle corner points")
        if not hasattr(obj, "Triangles"):
            obj.addProperty("App::PropertyIntegerList", "Triangles", "Result",
                            "Point indices (0-based), three per triangle")
        if not hasattr(obj, "FaceId"):
            obj.addProperty("App::PropertyIntegerList", "FaceId", "Result",
                            "CAD face number (1-based, FreeCAD's FaceN) or file part id per "
                            "triangle")
        set_read_only(obj, ["Method"] + [name for name, _ in _RESULTS])
        for name in ("Points", "Triangles", "FaceId"):
            obj.setEditorMode(name, 2)  # hidden: one entry per point / triangle

    def execute(self, obj):
        if getattr(obj, "FromPipeline", False):
            return  # Mesh Part's pipeline fills it
        surface = compute_surface(obj)
        if surface is not None:
            store_surface(obj, surface)


def compute_surface(obj):
    """core.Surface from the object's input (Source, else SourceFile), or None when it has
    neither (the stored triangles stay)."""
    found = triangle_input(obj)
    if found is not None:
        surface, name, method = found
        if hasattr(getattr(core, "_hexdom", None), "check_surface"):
            # Checked as every meshing path checks its input: an inside-out shell turned around
            # (with a warning), a surface that crosses itself refused naming two triangles.
            import FreeCAD
            surface, warnings = core.check_surface(surface, name)
            for w in warnings:
                FreeCAD.Console.PrintWarning("HexDom: {}: {}\n".format(obj.Label, w))
        obj.Method = method
        return surface
    if obj.Source is not None:
        shape = getattr(obj.Source, "Shape", None)
        if shape is None or shape.isNull() or not shape.Faces:
            raise ValueError("{}: source {} has no faces".format(obj.Label, obj.Source.Label))
        with Progress("Tessellating " + obj.Source.Label, 1) as bar:
            surface = tessellate(shape, size=obj.Size.Value, deflection=obj.Deflection.Value,
                                     angle=obj.Angle.Value, run=bar.run)
            bar.step("tessellated")
        obj.Method = tessellate.last_method or ""
        return surface
    if not obj.Method:
        obj.Method = "stored"
    return None


def is_mesh_feature(obj):
    """True for a FreeCAD mesh object (Mesh::Feature and the like: an STL or OBJ opened in FreeCAD)."""
    return (obj is not None and str(getattr(obj, "TypeId", "")).startswith("Mesh::")
            and hasattr(obj, "Mesh"))


def mesh_feature_surface(obj):
    """core.Surface of the FreeCAD mesh object ``obj``'s triangles as they are (patch 1 each, as a
    file read gives an STL's); ValueError when it has none."""
    points, facets = obj.Mesh.Topology
    if not facets:
        raise ValueError("{}: the mesh has no triangles".format(obj.Label))
    V = np.array([[p.x, p.y, p.z] for p in points], float).reshape(-1, 3)
    F = np.array(facets, np.int32).reshape(-1, 3)
    return core.Surface(V, F, np.ones(len(F), np.int32))


def takes_triangles(obj):
    """True when the HexDom Surface ``obj`` takes triangles as they are (its Source a mesh object,
    or no Source and a SourceFile) rather than tessellating a Part."""
    return is_mesh_feature(obj.Source) if obj.Source is not None else bool(obj.SourceFile)


def triangle_input(obj):
    """(core.Surface, name for messages, Method) of the triangles the HexDom Surface ``obj`` takes
    as they are, before any check: its Source's when that is a mesh object, else its SourceFile's;
    None when it tessellates a Part or has neither."""
    if not takes_triangles(obj):
        return None
    if obj.Source is not None:
        return mesh_feature_surface(obj.Source), obj.Source.Label, "mesh"
    return core.read_surface(obj.SourceFile), os.path.basename(obj.SourceFile), "file"


def is_surface(obj):
    return is_of_type(obj, TYPE)


def store_surface(obj, surface):
    """Puts a core.Surface (patch = face id per triangle) into obj's properties."""
    V = np.asarray(surface.V, float).reshape(-1, 3)
    F = np.asarray(surface.F, np.int64).reshape(-1, 3)
    ids = np.asarray(surface.patch, np.int64).reshape(-1)
    if len(ids) != len(F):
        raise ValueError("{} face ids for {} triangles".format(len(ids), len(F)))
    if len(F) and (F.min() < 0 or F.max() >= len(V)):
        raise ValueError("triangle corner index out of range (0..{})".format(len(V) - 1))
    # Clear the triangles first so that the view never sees indices beyond the points.
    obj.Triangles = []
    obj.Points = [tuple(p) for p in V.tolist()]
    obj.FaceId = ids.tolist()
    obj.Triangles = F.reshape(-1).tolist()
    counts = {"TriangleCount": len(F), "PointCount": len(V),
              "FaceCount": len(np.unique(ids)) if len(ids) else 0}
    for name, value in counts.items():
        if getattr(obj, name) != value:
            setattr(obj, name, value)


def get_surface(obj):
    """core.Surface held by a HexDom Surface (patch = face id per triangle)."""
    if not is_surface(obj):
        raise ValueError("{} is not a HexDom Surface".format(getattr(obj, "Label", obj)))
    V = np.array([tuple(p) for p in obj.Points], float).reshape(-1, 3)
    F = np.array(obj.Triangles, np.int32).reshape(-1, 3)
    ids = np.array(obj.FaceId, np.int32)
    if len(ids) != len(F):
        raise ValueError("{}: {} face ids for {} triangles; recompute it".format(
            obj.Label, len(ids), len(F)))
    return core.Surface(V, F, ids)
