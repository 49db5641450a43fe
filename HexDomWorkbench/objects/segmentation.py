"""HexDom Segmentation: a polycube label (+X -X +Y -Y +Z -Z) and a patch id per triangle of a
HexDom Surface.

Method picks where labels and patches come from:

- "Automatic": core.segment (CVT on normals, edge term weighted by EdgeWeight; on a CAD surface
  planar faces keep one label) when the build has it, with the user edits as fixed labels;
  patches are the connected regions of equal label.
- "Surface patches": the Surface's own face ids (CAD faces, or part ids of a .k file) are the
  patches; each patch gets the label of the axis nearest its mean normal.
- "Patch file": patches read from PatchFile (.k shells, part id = patch id, as the paper's patch
  files); a file with other triangles than the Surface transfers ids by nearest centroid.

Labels are numbered as in the core: 1 +X, 2 -X, 3 +Y, 4 -Y, 5 +Z, 6 -Z. User edits
(EditedTriangles[i] gets EditedLabels[i]) are applied after every recompute: the triangles keep
their new label, and join a neighbouring patch of that label. Patch edits (EditedPatchTriangles[i]
gets patch id EditedPatchIds[i], written by the Edit Patches panel for what labels cannot say: a
new patch beside one of the same label, a split, a merge) are applied after them. Labels, Patches
and the edits live in integer-list properties, so they are saved with the document. A Segmentation
Mesh Part's pipeline filled (FromPipeline) keeps its labels until one of its inputs is edited.
"""

import numpy as np

from .. import core
from ..logic.labels import apply_label_edits, labels_from_normals, transfer_patches
from ..logic.stages import check_patches, segment
from ..progress import Progress
from . import tessellation
from .base_object import BaseHexDomObject, is_of_type, set_read_only

TYPE = "HexDom::Segmentation"
METHODS = ["Automatic", "Surface patches", "Patch file"]
DEFAULT_EDGE_WEIGHT = 0.1  # core.segment's; documents older than EdgeWeight get it on restore

_RESULTS = [
    ("TriangleCount", "App::PropertyInteger", "Number of triangles"),
    ("PatchCount", "App::PropertyInteger", "Number of patches (distinct patch ids)"),
    ("EditCount", "App::PropertyInteger", "Number of edited triangles applied"),
]


class Segmentation(BaseHexDomObject):
    """Proxy of a HexDom Segmentation object (App::FeaturePython)."""

    Type = TYPE
    STAGE_INPUTS = ("Surface", "Method", "EdgeWeight", "Frame", "Stretch", "PatchFile", "EditedTriangles",
                    "EditedLabels", "EditedPatchTriangles", "EditedPatchIds")

    def add_properties(self, obj):
        super().add_properties(obj)
        self.add_pipeline_flag(obj)
        if not hasattr(obj, "Surface"):
            obj.addProperty("App::PropertyLink", "Surface", "Input",
                            "HexDom Surface whose triangles are labelled")
        if not hasattr(obj, "Method"):
            obj.addProperty("App::PropertyEnumeration", "Method", "Segmentation",
                            "Automatic (core), Surface patches (its face ids) or Patch file")
            obj.Method = METHODS
            obj.Method = "Automatic"
        if not hasattr(obj, "EdgeWeight"):
            obj.addProperty("App::PropertyFloat", "EdgeWeight", "Segmentation",
                            "Method Automatic: weight lambda of the CVT's edge term (larger: "
                            "smoother boundaries, fewer small charts); Mesh Part sets the one "
                            "its automatic polycube took (0.1, else 1, 0.3 or 3)")
            obj.EdgeWeight = DEFAULT_EDGE_WEIGHT
        if not hasattr(obj, "Frame"):
            obj.addProperty("App::PropertyRotation", "Frame", "Segmentation",
                            "The axes the labels name, turned from the model's by this "
                            "rotation (x in the frame = Frame applied to x); the identity: the "
                            "model's axes. Mesh Part sets the frame the faces fit best "
                            "(core.cube_frame) for a part lying at an angle")
        if not hasattr(obj, "FrameMatrix"):
            obj.addProperty("App::PropertyMatrix", "FrameMatrix", "Segmentation",
                            "The Frame as the pipeline gave it, to the last digit (the Frame "
                            "itself is kept as a quaternion); used while the Frame is that "
                            "rotation")
        obj.setEditorMode("FrameMatrix", 2)
        if not hasattr(obj, "Stretch"):
            obj.addProperty("App::PropertyVector", "Stretch", "Segmentation",
                            "Factors along the Frame's axes the surface is stretched by before "
                            "it is labelled, the polycube built and the mesh generated (each "
                            "mapped back); (1, 1, 1): none. Mesh Part sets the one the pipeline "
                            "took for a thin part (cells of a different length along each axis)")
            obj.Stretch = (1.0, 1.0, 1.0)
        if not hasattr(obj, "PatchFile"):
            obj.addProperty("App::PropertyFile", "PatchFile", "Segmentation",
                            "Segmented surface (.k shells, part id = patch id) for Method "
                            "'Patch file'")
        if not hasattr(obj, "EditedTriangles"):
            obj.addProperty("App::PropertyIntegerList", "EditedTriangles", "Edits",
                            "Triangles (0-based) whose label the user set; kept across "
                            "recomputes")
        if not hasattr(obj, "EditedLabels"):
            obj.addProperty("App::PropertyIntegerList", "EditedLabels", "Edits",
                            "Label (1 +X, 2 -X, 3 +Y, 4 -Y, 5 +Z, 6 -Z) of each edited triangle")
        if not hasattr(obj, "EditedPatchTriangles"):
            obj.addProperty("App::PropertyIntegerList", "EditedPatchTriangles", "Edits",
                            "Triangles (0-based) the user put into a given patch (Edit Patches); "
                            "applied after the label edits")
        if not hasattr(obj, "EditedPatchIds"):
            obj.addProperty("App::PropertyIntegerList", "EditedPatchIds", "Edits",
                            "Patch id of each triangle in EditedPatchTriangles")
        for name, prop_type, doc in _RESULTS:
            if not hasattr(obj, name):
                obj.addProperty(prop_type, name, "Result", doc)
        if not hasattr(obj, "Labels"):
            obj.addProperty("App::PropertyIntegerList", "Labels", "Result",
                            "Label per triangle: 1 +X, 2 -X, 3 +Y, 4 -Y, 5 +Z, 6 -Z")
        if not hasattr(obj, "Patches"):
            obj.addProperty("App::PropertyIntegerList", "Patches", "Result",
                            "Patch id per triangle")
        if not hasattr(obj, "Issues"):
            obj.addProperty("App::PropertyStringList", "Issues", "Result",
                            "Problems found in the patches (core.check_patches, edits ignored)")
        set_read_only(obj, [name for name, _, _ in _RESULTS] + ["Issues"])
        for name in ("Labels", "Patches"):
            obj.setEditorMode(name, 2)

    def execute(self, obj):
        if getattr(obj, "FromPipeline", False):
            return  # Mesh Part's pipeline fills it
        if obj.Surface is None or not tessellation.is_surface(obj.Surface):
            raise ValueError("{}: link a HexDom Surface (property Surface)".format(obj.Label))
        surface = tessellation.get_surface(obj.Surface)
        n = len(surface.F)
        issues = []
        with Progress("Segmenting " + obj.Surface.Label, 2) as bar:
            triangles, new_labels = valid_edits(obj, n, issues)
            labels, patches, keep = base_segmentation(obj, surface, triangles, new_labels,
                                                      run=bar.run)
            bar.step("labels")
            labels, patches = apply_label_edits(surface.F, labels, patches, triangles, new_labels,
                                                keep_patches=keep)
            patches = apply_patch_edits(obj, patches, issues)
            bar.step("edits")
        issues += check_patches(core.Surface(surface.V, surface.F, patches))
        store_segmentation(obj, labels, patches)
        if obj.EditCount != len(triangles):
            obj.EditCount = len(triangles)
        if list(obj.Issues) != issues:
            obj.Issues = issues


def base_segmentation(obj, surface, triangles=(), new_labels=(), run=None):
    """(labels, patches, keep_patches) of the method, before user edits (which the automatic
    method already takes as fixed labels). ``run(text, fn, *args, **kw)`` runs the core call
    (Progress.run: a worker thread under the GUI); default: a direct call."""
    method = obj.Method
    if method == "Automatic":
        edits = np.c_[np.asarray(triangles, np.int32), np.asarray(new_labels, np.int32)]
        run = run or (lambda text, fn, *args, **kw: fn(*args, **kw))
        weight = float(getattr(obj, "EdgeWeight", DEFAULT_EDGE_WEIGHT))
        if not weight >= 0:
            raise ValueError("{}: EdgeWeight must be 0 or more".format(obj.Label))
        result = run("segment", segment, surface, edits=edits if len(edits) else None,
                     edge_weight=weight, frame=frame_matrix(obj), stretch=stretch_factors(obj))
        return result.labels, result.patch, False
    if method == "Surface patches":
        patches = np.asarray(surface.patch, np.int32)
    elif method == "Patch file":
        if not obj.PatchFile:
            raise ValueError("{}: Method 'Patch file' needs PatchFile".format(obj.Label))
        source = core.read_surface(obj.PatchFile)
        same = (len(source.F) == len(surface.F) and source.V.shape == surface.V.shape
                and np.array_equal(source.F, surface.F)
                and np.allclose(source.V, surface.V, rtol=0,
                                atol=1e-9 * max(1.0, float(np.abs(surface.V).max()))))
        patches = np.asarray(source.patch if same else transfer_patches(source, surface),
                             np.int32)
    else:
        raise ValueError("{}: unknown Method '{}'".format(obj.Label, method))
    labels = labels_from_normals(surface.V, surface.F, patches, frame=frame_matrix(obj),
                                 stretch=stretch_factors(obj))
    return labels, patches, True


def valid_edits(obj, triangle_count, issues):
    """Edits that fit the current surface; the others are reported in ``issues`` (kept in the
    properties, in case the surface comes back)."""
    triangles = np.asarray(obj.EditedTriangles, np.int64)
    labels = np.asarray(obj.EditedLabels, np.int32)
    if len(triangles) != len(labels):
        raise ValueError("{}: {} edited triangles but {} edited labels".format(
            obj.Label, len(triangles), len(labels)))
    ok = (triangles >= 0) & (triangles < triangle_count) & (labels >= 1) & (labels <= 6)
    if not np.all(ok):
        issues.append("{} edits ignored: triangle beyond {} or label outside 1..6".format(
            int(np.count_nonzero(~ok)), triangle_count - 1))
    return triangles[ok], labels[ok]


def apply_patch_edits(obj, patches, issues):
    """``patches`` with the patch edits applied (EditedPatchTriangles[i] gets EditedPatchIds[i]);
    edits that do not fit the surface are reported in ``issues``."""
    triangles = np.asarray(getattr(obj, "EditedPatchTriangles", []), np.int64)
    ids = np.asarray(getattr(obj, "EditedPatchIds", []), np.int32)
    if len(triangles) == 0:
        return patches
    if len(triangles) != len(ids):
        raise ValueError("{}: {} triangles with patch edits but {} patch ids".format(
            obj.Label, len(triangles), len(ids)))
    ok = (triangles >= 0) & (triangles < len(patches)) & (ids > 0)
    if not np.all(ok):
        issues.append("{} patch edits ignored: triangle beyond {} or patch id below 1".format(
            int(np.count_nonzero(~ok)), len(patches) - 1))
    patches = np.array(patches, np.int32)
    patches[triangles[ok]] = ids[ok]
    return patches


def frame_matrix(obj):
    """The 3 x 3 rotation of the Segmentation's Frame (x_frame = R @ x), or None for the model's
    axes (the identity, or a document older than Frame). The Frame is a quaternion: the matrix the
    pipeline gave (FrameMatrix, set with it by set_frame) is returned while the Frame is still that
    rotation, so that the stages rebuild with the very numbers the pipeline used."""
    frame = getattr(obj, "Frame", None)
    if frame is None:
        return None
    R = _rotation_part(frame.toMatrix())
    if np.allclose(R, np.eye(3), rtol=0, atol=1e-12):
        return None
    exact = getattr(obj, "FrameMatrix", None)
    if exact is not None and np.allclose(_rotation_part(exact), R, rtol=0, atol=1e-9):
        return _rotation_part(exact)
    return R


def _rotation_part(m):
    """The upper-left 3 x 3 of a FreeCAD.Matrix, as a numpy array."""
    return np.array([[m.A11, m.A12, m.A13], [m.A21, m.A22, m.A23], [m.A31, m.A32, m.A33]], float)


def set_frame(obj, R):
    """Sets the Segmentation's Frame to the 3 x 3 rotation R (None: the model's axes), and
    FrameMatrix to R exactly; touches it only when the frame changes."""
    import FreeCAD
    R = np.eye(3) if R is None else np.asarray(R, float).reshape(3, 3)
    current = frame_matrix(obj)
    if np.array_equal(np.eye(3) if current is None else current, R):
        return
    matrix = FreeCAD.Matrix(R[0, 0], R[0, 1], R[0, 2], 0, R[1, 0], R[1, 1], R[1, 2], 0,
                            R[2, 0], R[2, 1], R[2, 2], 0, 0, 0, 0, 1)
    if hasattr(obj, "FrameMatrix"):
        obj.FrameMatrix = matrix
    obj.Frame = FreeCAD.Rotation(matrix)


def stretch_factors(obj):
    """The Segmentation's Stretch as three factors, or None for none ((1, 1, 1), or a document
    older than Stretch)."""
    stretch = getattr(obj, "Stretch", None)
    if stretch is None:
        return None
    factors = (float(stretch.x), float(stretch.y), float(stretch.z))
    return None if factors == (1.0, 1.0, 1.0) else factors


def set_stretch(obj, factors):
    """Sets the Segmentation's Stretch (None: none) when the document has it; touches it only when
    it changes."""
    if not hasattr(obj, "Stretch"):
        return
    factors = (1.0, 1.0, 1.0) if factors is None else tuple(float(f) for f in factors)
    if tuple(obj.Stretch) != factors:
        obj.Stretch = factors


def is_segmentation(obj):
    return is_of_type(obj, TYPE)


def store_segmentation(obj, labels, patches):
    labels = np.asarray(labels, np.int64).tolist()
    patches = np.asarray(patches, np.int64).tolist()
    obj.Patches = patches
    obj.Labels = labels
    counts = {"TriangleCount": len(labels), "PatchCount": len(set(patches))}
    for name, value in counts.items():
        if getattr(obj, name) != value:
            setattr(obj, name, value)


def get_labels(obj):
    return np.array(obj.Labels, np.int32)


def get_label_surface(obj):
    """core.Surface of the Surface's triangles with this segmentation's label (1..6) per
    triangle, as core.autopolycube takes it."""
    surface = get_surface(obj)
    labels = np.array(obj.Labels, np.int32)
    if len(labels) != len(surface.F):
        raise ValueError("{}: {} labels for {} triangles; recompute it".format(
            obj.Label, len(labels), len(surface.F)))
    return core.Surface(surface.V, surface.F, labels)


def get_surface(obj):
    """core.Surface for generation: the Surface's triangles with this segmentation's patch ids."""
    if not is_segmentation(obj):
        raise ValueError("{} is not a HexDom Segmentation".format(getattr(obj, "Label", obj)))
    if obj.Surface is None:
        raise ValueError("{}: no Surface linked".format(obj.Label))
    surface = tessellation.get_surface(obj.Surface)
    patches = np.array(obj.Patches, np.int32)
    if len(patches) != len(surface.F):
        raise ValueError("{}: {} patch ids for {} triangles; recompute it".format(
            obj.Label, len(patches), len(surface.F)))
    return core.Surface(surface.V, surface.F, patches)
