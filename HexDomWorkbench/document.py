"""The workbench's document objects built from scripts: the pipeline from whatever is given
(make_document_objects), structure and patch files in and out, label edits on a Segmentation, the
improvement of a mesh object, and a recompute that names the object at fault. Objects are made by
``make`` (which attaches view providers when the GUI is up); FreeCAD is imported only inside the
functions that need it."""

import os

import numpy as np

from . import core, make
from .logic.labels import label_number
from .logic.stages import has_segmentation, read_structure
from .objects import hex_mesh, polycube


class RecomputeError(core.Error):
    """A HexDom document object failed to recompute; the message is the object's error."""


def recompute_document(doc, objects=()):
    """Recomputes ``doc``; raises RecomputeError naming the first HexDom object (of ``objects``,
    or of the document) that failed, with its error message."""
    doc.recompute()
    watch = list(objects) or [o for o in doc.Objects if hasattr(getattr(o, "Proxy", None), "Type")]
    for obj in watch:
        state = obj.State
        if "Invalid" in state or "Error" in state:
            message = obj.getStatusString() if hasattr(obj, "getStatusString") else ""
            raise RecomputeError("{}: {}".format(obj.Label, message or "recompute failed"))
    return doc


def import_structure(path, doc=None, name="HexDomPolycube"):
    """Reads a .k polycube structure into a new HexDom Polycube of ``doc`` (the active or a new
    document); recomputes and returns the object."""
    import FreeCAD

    structure = read_structure(path)
    doc = doc or FreeCAD.ActiveDocument or FreeCAD.newDocument()
    obj = make.make_polycube(doc, structure=structure, path=os.path.abspath(path), name=name)
    obj.Label = os.path.splitext(os.path.basename(path))[0]
    recompute_document(doc, [obj])
    return obj


def export_structure(obj, path):
    """Writes the structure of a HexDom Polycube (.k as the original program's files; also .vtk,
    .vtu, .inp)."""
    if not polycube.is_polycube(obj):
        raise ValueError("{} is not a HexDom Polycube".format(obj.Label))
    core.write_mesh(os.fspath(path), polycube.get_structure(obj))


def import_patches(path, doc=None):
    """Reads a segmented surface (.k shells, part id = patch id, as the paper's patch files) into
    a HexDom Surface plus a HexDom Segmentation (Method "Patch file"); returns the Segmentation."""
    import FreeCAD

    doc = doc or FreeCAD.ActiveDocument or FreeCAD.newDocument()
    seg = _make_patch_objects(doc, path)
    recompute_document(doc, [seg.Surface, seg])
    return seg


def _make_patch_objects(doc, path):
    path = os.path.abspath(path)
    if not os.path.isfile(path):
        raise core.InputError("{}: no such file".format(path))
    base = os.path.splitext(os.path.basename(path))[0]
    surface = make.make_surface(doc, path=path)
    surface.Label = base + "_surface"
    seg = make.make_segmentation(doc, surface, method="Patch file", patch_file=path)
    seg.Label = base
    return seg


def set_labels(segmentation, triangles, label):
    """Records user edits on a HexDom Segmentation: ``triangles`` (indices) get ``label`` (1..6
    or "+X", "-X", "+Y", "-Y", "+Z", "-Z"). Edits are kept across recomputes; recompute to apply
    them."""
    label = label_number(label)
    triangles = [int(t) for t in np.atleast_1d(triangles).tolist()]
    edits = dict(zip(segmentation.EditedTriangles, segmentation.EditedLabels))
    for t in triangles:
        edits.pop(t, None)
        edits[t] = int(label)
    segmentation.EditedTriangles = list(edits.keys())
    segmentation.EditedLabels = list(edits.values())


def clear_edits(segmentation):
    """Drops all user edits (labels and patch ids) of a HexDom Segmentation."""
    segmentation.EditedTriangles = []
    segmentation.EditedLabels = []
    if hasattr(segmentation, "EditedPatchTriangles"):
        segmentation.EditedPatchTriangles = []
        segmentation.EditedPatchIds = []


def improve_object(obj):
    """Quality improvement of a HexDom Mesh (HexDom_ImproveQuality): a generated mesh gets
    Improve = True; any other FEM mesh gets a new HexDom Mesh improving a copy of it (BaseMesh).
    Returns the object holding the improved mesh; recompute to run it."""
    if hex_mesh.is_hex_mesh(obj) and hex_mesh.has_inputs(obj):
        obj.Improve = True
        obj.touch()
        return obj
    if not obj.isDerivedFrom("Fem::FemMeshObject"):
        raise ValueError("{} is not a FEM mesh object".format(obj.Label))
    new = make.make_hex_mesh(obj.Document, name="HexDomMesh", base_mesh=obj, improve=True)
    new.Label = obj.Label + "_improved"
    return new


def make_document_objects(doc, shape=None, surface=None, patch_file=None, structure=None,
                          structure_file=None, segmentation="auto", level=2, improve=True,
                          size=0.0, recompute=True):
    """Builds the parametric pipeline in ``doc`` from whatever is given; returns a dict with the
    created objects under "surface", "segmentation", "polycube", "mesh" (missing stages absent).

    shape: a Part object (or a Part.Shape, added as a Part::Feature) -> HexDom Surface (size);
    surface: a core.Surface -> HexDom Surface holding it; patch_file: a segmented .k surface ->
    Surface + Segmentation from the file. segmentation: "auto" (from patch_file, else automatic
    when the core can, else none), "Automatic", "Surface patches" or None. structure (core.Mesh)
    or structure_file (.k) -> HexDom Polycube. With a Segmentation and a Polycube, a HexDom Mesh
    at ``level`` (improved if ``improve``). Recomputes when ``recompute`` is true and raises
    RecomputeError when an object fails.
    """
    objs = {}
    if patch_file is not None:
        seg = _make_patch_objects(doc, patch_file)
        objs["surface"], objs["segmentation"] = seg.Surface, seg
    elif shape is not None or surface is not None:
        if shape is not None and not hasattr(shape, "Document"):
            part = doc.addObject("Part::Feature", "Part")
            part.Shape = shape
            shape = part
        objs["surface"] = make.make_surface(doc, source=shape, surface=surface, size=size)
        method = segmentation
        if method == "auto":
            method = "Automatic" if has_segmentation() else None
        if method:
            objs["segmentation"] = make.make_segmentation(doc, objs["surface"], method=method)
    if structure is not None or structure_file is not None:
        if structure is None:
            structure = read_structure(structure_file)
        path = os.path.abspath(structure_file) if structure_file else ""
        objs["polycube"] = make.make_polycube(doc, structure=structure, path=path)
        if structure_file:
            objs["polycube"].Label = os.path.splitext(os.path.basename(structure_file))[0]
    if "segmentation" in objs and "polycube" in objs:
        objs["mesh"] = make.make_hex_mesh(doc, segmentation=objs["segmentation"],
                                          polycube=objs["polycube"], level=level,
                                          improve=improve)
    if recompute:
        recompute_document(doc, list(objs.values()))
    return objs
