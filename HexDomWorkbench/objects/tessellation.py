"""HexDom Surface: the triangle surface of a Part solid with the CAD face number per triangle.

Holds the triangles in properties (Points, Triangles as a flat list of point indices, FaceId per
triangle: 1-based, triangle t lies on Face<FaceId[t]> of the source shape), so the document keeps
them and the segmentation reads them back as a core.Surface. The source is a Part object
(Source, tessellated with Size / Deflection / Angle by shape_tessellation.tessellate) or, when Source is
empty, a triangle file (SourceFile: .k shells with part id per triangle, .stl, .obj, .vtk; the
part ids become FaceId). With neither, the object keeps the triangles it was given; so does a
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
                            "Part object (a solid) whose faces are tessellated")
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
    if obj.SourceFile:
        surface = core.read_surface(obj.SourceFile)
        if hasattr(getattr(core, "_hexdom", None), "check_surface"):
            # Checked as every meshing path checks its input: an inside-out shell turned around
            # (with a warning), a surface that crosses itself refused naming two triangles.
            import FreeCAD
            surface, warnings = core.check_surface(surface, os.path.basename(obj.SourceFile))
            for w in warnings:
                FreeCAD.Console.PrintWarning("HexDom: {}: {}\n".format(obj.Label, w))
        obj.Method = "file"
        return surface
    if not obj.Method:
        obj.Method = "stored"
    return None


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
