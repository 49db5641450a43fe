"""Python API for macros and scripts: the whole pipeline, from a CAD part to a FEM mesh.

    import HexDomWorkbench as hexdom
    surface = hexdom.tessellate(shape, size=2.0)          # core.Surface, patch = CAD face number
    segmented = hexdom.segment(surface)                    # SegmentedSurface (labels, patches)
    mesh = hexdom.generate(segmented, structure, level=2)  # core.Mesh
    mesh = hexdom.improve(mesh, segmented)
    fem = hexdom.to_fem_mesh(mesh)                         # Fem.FemMesh
    objs = hexdom.make_document_objects(doc, patch_file=..., structure_file=...)

The package re-exports these names lazily, so ``import HexDomWorkbench`` never loads FreeCAD.
This module imports FreeCAD only inside the functions that need it: ``segment``, ``generate``,
``improve`` and the patch helpers work in a plain Python with numpy.

Optional stages of the core are used when the compiled module provides them (``core.segment``,
``core.check_patches``, ``core.tessellate_brep``); without them ``segment`` raises core.Error
("segmentation not available in this build") and ``tessellate`` uses FreeCAD's MeshPart.

Labels (polycube directions) are numbered as in the core: 1 +X, 2 -X, 3 +Y, 4 -Y, 5 +Z, 6 -Z;
patch ids are positive integers, one per connected region a polycube face maps to.
"""

import math
import os
from dataclasses import dataclass

import numpy as np

from . import core
from .core import generate, improve  # noqa: F401  (the same functions, FreeCAD-free)

LABEL_NAMES = {1: "+X", 2: "-X", 3: "+Y", 4: "-Y", 5: "+Z", 6: "-Z"}
# Direction of label l is AXES[l - 1].
AXES = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float)

# Refuse tessellations beyond this many triangles (a Size far too small for the part).
MAX_TRIANGLES = 2_000_000


class RecomputeError(core.Error):
    """A HexDom document object failed to recompute; the message is the object's error."""


@dataclass
class SegmentedSurface(core.Surface):
    """core.Surface whose ``patch`` holds patch ids, plus a polycube label (1..6) per triangle."""

    labels: np.ndarray = None


def _core_has(name):
    """True if core offers ``name`` and the compiled module behind it does too (core.py may be
    newer than the _hexdom it loads)."""
    compiled = getattr(core, "_hexdom", None)
    return hasattr(core, name) and (compiled is None or hasattr(compiled, name))


def has_segmentation():
    """True if the compiled core provides automatic segmentation (core.segment)."""
    return _core_has("segment")


def has_cad():
    """True if the compiled core tessellates CAD shapes itself (core.tessellate_brep)."""
    return _core_has("tessellate_brep")


# ------------------------------------------------------------------------------------------------
# Triangle-surface helpers (numpy only)

def triangle_normals(V, F):
    """Unit normals (#F x 3) and areas (#F) of the triangles F of V."""
    V = np.asarray(V, float)
    F = np.asarray(F, np.int64).reshape(-1, 3)
    n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    length = np.linalg.norm(n, axis=1)
    safe = np.where(length > 0, length, 1.0)
    return n / safe[:, None], 0.5 * length


def nearest_label(normals):
    """Label (1..6) of the axis nearest each row of ``normals``."""
    return (np.argmax(np.asarray(normals, float).reshape(-1, 3) @ AXES.T, axis=1) + 1).astype(
        np.int32)


def labels_from_normals(V, F, patch=None, frame=None):
    """Polycube label per triangle: the axis nearest its normal, or with ``patch`` the axis
    nearest the area-weighted mean normal of the triangle's patch (one label per patch). frame:
    a 3 x 3 rotation whose axes the labels name (None: the model's)."""
    normals, areas = triangle_normals(V, F)
    if frame is not None:
        normals = normals @ np.asarray(frame, float).reshape(3, 3).T
    if patch is None:
        return nearest_label(normals)
    patch = np.asarray(patch)
    ids, inverse = np.unique(patch, return_inverse=True)
    mean = np.zeros((len(ids), 3))
    np.add.at(mean, inverse, normals * areas[:, None])
    return nearest_label(mean)[inverse]


def triangle_adjacency(F):
    """Pairs (#P x 2) of triangles sharing an edge (on an edge with k > 2 triangles, consecutive
    ones are paired)."""
    F = np.asarray(F, np.int64).reshape(-1, 3)
    if len(F) == 0:
        return np.zeros((0, 2), np.int64)
    edges = np.sort(F[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    tri = np.repeat(np.arange(len(F)), 3)
    order = np.lexsort((edges[:, 1], edges[:, 0]))
    edges, tri = edges[order], tri[order]
    same = np.all(edges[1:] == edges[:-1], axis=1)
    return np.stack([tri[:-1][same], tri[1:][same]], axis=1)


def _union_find(n, pairs):
    parent = list(range(n))

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a, b in pairs:
        ra, rb = find(a), find(b)
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)
    return np.array([find(a) for a in range(n)], np.int64)


def connected_regions(F, key, adjacency=None):
    """Region number (0..R-1, in order of first triangle) per triangle: triangles sharing an edge
    and the same ``key`` value belong to one region."""
    key = np.asarray(key)
    pairs = triangle_adjacency(F) if adjacency is None else adjacency
    pairs = pairs[key[pairs[:, 0]] == key[pairs[:, 1]]] if len(pairs) else pairs
    roots = _union_find(len(key), pairs.tolist())
    _, first, inverse = np.unique(roots, return_index=True, return_inverse=True)
    rank = np.argsort(np.argsort(first))
    return rank[inverse].astype(np.int32)


def patches_from_labels(F, labels):
    """Patch id (1-based) per triangle: the connected regions of equal label."""
    return connected_regions(F, labels) + 1


def apply_label_edits(F, labels, patches, triangles, new_labels, keep_patches):
    """Applies user overrides (``triangles[i]`` gets ``new_labels[i]``; a later entry wins).

    Returns (labels, patches). With ``keep_patches`` (patches given by a file or the CAD faces)
    patch ids stay as they are, and each edited triangle joins the patch of a neighbour that has
    its new label (regions without such a neighbour get new ids); otherwise patches are the
    connected regions of equal label.
    """
    labels = np.array(labels, np.int32)
    patches = np.array(patches, np.int32)
    triangles = np.asarray(triangles, np.int64)
    new_labels = np.asarray(new_labels, np.int32)
    if len(triangles) == 0:
        return labels, patches
    labels[triangles] = new_labels
    if not keep_patches:
        return labels, patches_from_labels(F, labels)
    edited = np.zeros(len(labels), bool)
    edited[triangles] = True
    pairs = triangle_adjacency(F)
    pairs = pairs[labels[pairs[:, 0]] == labels[pairs[:, 1]]]
    neighbours = {}
    for a, b in pairs.tolist():
        neighbours.setdefault(a, []).append(b)
        neighbours.setdefault(b, []).append(a)
    resolved = ~edited
    frontier = [t for t in np.flatnonzero(edited).tolist()
                if any(resolved[n] for n in neighbours.get(t, ()))]
    while frontier:  # grow unedited patches into edited triangles of the same label
        nxt = []
        for t in frontier:
            if resolved[t]:
                continue
            for n in neighbours.get(t, ()):
                if resolved[n]:
                    patches[t] = patches[n]
                    resolved[t] = True
                    break
            if resolved[t]:
                nxt += [n for n in neighbours.get(t, ()) if not resolved[n]]
        frontier = nxt
    left = np.flatnonzero(~resolved)
    if len(left):  # edited regions touching no patch of their label: new patches
        region = connected_regions(F, np.where(resolved, -1, labels))
        next_id = int(patches.max()) + 1
        for r in np.unique(region[left]).tolist():
            patches[(region == r) & ~resolved] = next_id
            next_id += 1
    return labels, patches


def transfer_patches(source, target):
    """Patch id of the nearest ``source`` triangle (by centroid) for each ``target`` triangle: the
    paper's patch files are segmentations of slightly different triangulations."""
    cs = np.asarray(source.V)[np.asarray(source.F)].mean(axis=1)
    ct = np.asarray(target.V)[np.asarray(target.F)].mean(axis=1)
    try:
        from scipy.spatial import cKDTree
        nearest = cKDTree(cs).query(ct)[1]
    except ImportError:
        nearest = np.empty(len(ct), np.int64)
        cs2 = np.einsum("ij,ij->i", cs, cs)
        for start in range(0, len(ct), 512):
            block = ct[start:start + 512]
            d = cs2[None, :] - 2.0 * block @ cs.T
            nearest[start:start + 512] = np.argmin(d, axis=1)
    return np.asarray(source.patch)[nearest].astype(np.int32)


def check_patches(surface, **options):
    """Problems the core finds in a segmented surface (core.check_patches: the polycube
    conditions), as a list of messages; empty when the build has no such check."""
    if not _core_has("check_patches"):
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
    if _core_has("number_patches"):
        patches = np.asarray(core.number_patches(core.Surface(V, F, labels)), np.int32)
    else:
        patches = patches_from_labels(F, labels)
    return SegmentedSurface(V, F, patches.reshape(-1), labels)


# ------------------------------------------------------------------------------------------------
# Tessellation

def default_size(shape):
    """Size used when 0 is given: 1/25 of the bounding-box diagonal."""
    return shape.BoundBox.DiagonalLength / 25.0


def remesh_to_size(V, F, ids, size):
    """The closed triangle surface (V, F, face id per triangle) remeshed by the core onto itself:
    near-equilateral triangles of about ``size``, each vertex on the input triangles of its own face
    id, the curves between faces and their corners kept. Returns (V, F, ids)."""
    s = core.remesh_triangles(core.Surface(np.asarray(V, float), np.asarray(F, np.int32).reshape(-1, 3),
                                           np.asarray(ids, np.int32).reshape(-1)), size)
    return np.asarray(s.V, float), np.asarray(s.F, np.int32), np.asarray(s.patch, np.int32)


def curvature_length(shape, size, deflection, angle, samples=5):
    """Edge length for the MeshPart mesher: ``size``, shortened so that chords on the most curved
    face stay within ``deflection`` and turn by at most ``angle`` degrees, but not below size / 4.
    Curvature comes from face.curvatureAt on a grid of each face's parameter range (Part's
    OCCError is a RuntimeError)."""
    kmax = 0.0
    for face in shape.Faces:
        if face.Surface.TypeId == "Part::GeomPlane":
            continue
        u0, u1, v0, v1 = face.ParameterRange
        for u in np.linspace(u0, u1, samples).tolist():
            for v in np.linspace(v0, v1, samples).tolist():
                try:
                    k1, k2 = face.curvatureAt(u, v)
                except (RuntimeError, ValueError):
                    continue
                kmax = max(kmax, abs(k1), abs(k2))
    length = size
    if kmax > 0:
        r = 1.0 / kmax
        d = min(deflection, r)
        length = min(length, 2.0 * math.sqrt(max(2.0 * r * d - d * d, 0.0)),
                     2.0 * r * math.sin(math.radians(angle) / 2.0))
    return max(length, size / 4.0)


def _merge_points(V, tol):
    """Index of the representative point per row of V, merging points closer than ``tol``."""
    try:
        from scipy.spatial import cKDTree
        pairs = np.array(sorted(cKDTree(V).query_pairs(tol)), np.int64).reshape(-1, 2)
    except ImportError:
        key = np.round(V / tol).astype(np.int64)
        _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
        return first[inverse]
    return _union_find(len(V), pairs.tolist())


def _orient_like_faces(shape, V, F, face_id):
    """Flips the triangles of each face whose normals point against the CAD face's normal."""
    normals, areas = triangle_normals(V, F)
    for k, face in enumerate(shape.Faces, 1):
        rows = np.flatnonzero(face_id == k)
        if not len(rows):
            continue
        t = rows[np.argmax(areas[rows])]
        centre = V[F[t]].mean(axis=0)
        try:
            import FreeCAD
            u, v = face.Surface.parameter(FreeCAD.Vector(*centre.tolist()))
            n = face.normalAt(u, v)
        except (RuntimeError, ValueError):
            continue
        if normals[t] @ np.array([n.x, n.y, n.z]) < 0:
            F[rows] = F[rows][:, [0, 2, 1]]
    return F


def _tessellate_mefisto(shape, length):
    """Each face meshed alone by MeshPart's Mefisto mesher (near-equilateral triangles of edge
    ``length``); shared edges get the same points from both faces, merged afterwards."""
    import MeshPart

    Vs, Fs, ids, offset = [], [], [], 0
    for k, face in enumerate(shape.Faces, 1):
        mesh = MeshPart.meshFromShape(Shape=face, MaxLength=length)
        points, facets = mesh.Topology
        if not facets:
            raise ValueError("MeshPart's Mefisto mesher gave no triangles for Face{}".format(k))
        Vs.append(np.array([tuple(p) for p in points], float).reshape(-1, 3))
        Fs.append(np.array(facets, np.int64).reshape(-1, 3) + offset)
        ids.append(np.full(len(facets), k, np.int32))
        offset += len(points)
    V, F, face_id = np.vstack(Vs), np.vstack(Fs), np.concatenate(ids)
    rep = _merge_points(V, 1e-7 * max(shape.BoundBox.DiagonalLength, 1e-12))
    used, F = np.unique(rep[F], return_inverse=True)
    F = F.reshape(-1, 3)
    V = V[used]
    keep = (F[:, 0] != F[:, 1]) & (F[:, 1] != F[:, 2]) & (F[:, 2] != F[:, 0])
    F, face_id = F[keep], face_id[keep]
    F = _orient_like_faces(shape, V, F, face_id)
    return V, F.astype(np.int32), face_id


def _tessellate_standard(shape, size, deflection, angle):
    """MeshPart's standard (BRepMesh) mesher, one segment per face, then the core's remeshing to
    ``size`` (its triangles are needles along the edges)."""
    import MeshPart

    mesh = MeshPart.meshFromShape(Shape=shape, LinearDeflection=deflection,
                                  AngularDeflection=math.radians(angle), Relative=False,
                                  Segments=True)
    points, facets = mesh.Topology
    V = np.array([tuple(p) for p in points], float).reshape(-1, 3)
    F = np.array(facets, np.int32).reshape(-1, 3)
    face_id = np.zeros(len(F), np.int32)
    if mesh.countSegments() != len(shape.Faces):
        raise ValueError("MeshPart gave {} segments for {} faces".format(
            mesh.countSegments(), len(shape.Faces)))
    for i in range(mesh.countSegments()):
        face_id[np.asarray(mesh.getSegment(i), np.int64)] = i + 1
    return remesh_to_size(V, F, face_id, size)


def _tessellate_meshpart(shape, size, deflection, angle):
    """Mefisto per face (isotropic triangles); the standard mesher if Mefisto fails or does not
    give a closed conforming surface."""
    length = curvature_length(shape, size, deflection, angle)
    try:
        V, F, face_id = _tessellate_mefisto(shape, length)
        edges = np.sort(F[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
        _, uses = np.unique(edges, axis=0, return_counts=True)
        closed = shape.isClosed() if hasattr(shape, "isClosed") else True
        if not closed or np.all(uses == 2):
            return V, F, face_id, "MeshPart (Mefisto)"
        reason = "edges not shared by two triangles"
    except (ValueError, RuntimeError) as e:
        reason = str(e)
    try:
        import FreeCAD
        FreeCAD.Console.PrintLog("HexDom: Mefisto tessellation unusable ({}); using MeshPart's "
                                 "standard mesher\n".format(reason))
    except ImportError:
        pass
    V, F, face_id = _tessellate_standard(shape, size, deflection, angle)
    return V, F, face_id, "MeshPart (standard)"


def _tessellate_core(shape, size, deflection, angle, run=None):
    brep = shape.exportBrepToString()
    run = run or (lambda text, fn, *args, **kw: fn(*args, **kw))
    try:
        result = run("tessellate", core.tessellate_brep, brep, size=size, deflection=deflection,
                     angle=angle)
    except TypeError:  # a core wrapper that takes the size only
        result = run("tessellate", core.tessellate_brep, brep, size=size)
    if hasattr(result, "F"):
        V, F, face_id = result.V, result.F, result.patch
    else:
        V, F, face_id = result[:3]
    face_id = np.asarray(face_id, np.int32).reshape(-1)
    if len(face_id) and face_id.min() == 0:  # 0-based face index: make it FreeCAD's FaceN
        face_id = face_id + 1
    return np.asarray(V, float), np.asarray(F, np.int32).reshape(-1, 3), face_id


def tessellate(shape, size=0.0, deflection=0.0, angle=20.0, method="auto", run=None):
    """Triangulates a Part shape (its faces) into a core.Surface whose ``patch`` is the CAD face
    number per triangle (1-based: triangle t lies on shape.Faces[patch[t] - 1], FreeCAD's
    Face<patch[t]>).

    size: target triangle edge length (0: 1/25 of the bounding-box diagonal); deflection:
    largest chord distance to the CAD surface (0: size / 10); angle: largest turn in degrees
    between neighbouring chords on curved faces. method "auto" uses the core's OCCT tessellation
    (core.tessellate_brep) when the build has it, else FreeCAD's MeshPart (each face meshed by
    Mefisto at one edge length, shortened for the curvature, shared edges merged; the standard
    mesher remeshed by the core if that fails); "core" or "meshpart" force one. Returns a closed
    core.Surface for a solid; ``tessellate.last_method`` tells which mesher ran. ``run``
    (Progress.run) runs the core's call, in a worker thread under the GUI; MeshPart runs in the
    calling thread.
    """
    if shape is None or shape.isNull() or not shape.Faces:
        raise ValueError("the shape has no faces to tessellate")
    size = float(size) if size and size > 0 else default_size(shape)
    deflection = float(deflection) if deflection and deflection > 0 else size / 10.0
    angle = float(angle) if angle and angle > 0 else 20.0
    # Near-equilateral triangles of edge size / 4 (the shortest MeshPart uses) cover
    # 0.108 size^2 each.
    estimate = shape.Area / (0.108 * size * size)
    if estimate > MAX_TRIANGLES:
        raise ValueError("Size {:g} is too small for this part: about {:.3g} triangles (at most "
                         "{})".format(size, estimate, MAX_TRIANGLES))
    use_core = method == "core" or (method == "auto" and has_cad())
    if method not in ("auto", "core", "meshpart"):
        raise ValueError("unknown tessellation method '{}'".format(method))
    if use_core:
        if not has_cad():
            raise core.Error("CAD tessellation not available in this build")
        V, F, face_id = _tessellate_core(shape, size, deflection, angle, run)
        tessellate.last_method = "core"
    else:
        V, F, face_id, tessellate.last_method = _tessellate_meshpart(shape, size, deflection,
                                                                      angle)
    return core.Surface(V, F, face_id)


tessellate.last_method = None


# ------------------------------------------------------------------------------------------------
# FEM meshes

def to_fem_mesh(mesh):
    """Fem.FemMesh holding a core.Mesh (SMDS node order; node and cell ids are rows + 1)."""
    from .convert import femmesh
    return femmesh.to_femmesh(mesh)


def from_fem_mesh(fem):
    """core.Mesh of a Fem.FemMesh (VTK node order; region ids 0)."""
    from .convert import femmesh
    return femmesh.from_femmesh(fem)


def read_structure(path):
    """Polycube structure (hex, prism and tet blocks) from a .k file (or any volume mesh)."""
    structure = core.read_mesh(os.fspath(path))
    bad = np.setdiff1d(np.unique(structure.types), [core.HEX, core.WEDGE, core.TET])
    if len(structure.types) == 0 or len(bad):
        raise core.InputError("{}: a polycube structure holds hex, prism and tet blocks only"
                              .format(os.fspath(path)))
    return structure


# ------------------------------------------------------------------------------------------------
# Progress (FreeCAD's progress bar, a Cancel button and a responsive GUI for long core calls):
# see progress.py.

from .progress import Cancelled, Progress  # noqa: E402,F401


# ------------------------------------------------------------------------------------------------
# Document objects

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

    from . import make
    structure = read_structure(path)
    doc = doc or FreeCAD.ActiveDocument or FreeCAD.newDocument()
    obj = make.make_polycube(doc, structure=structure, path=os.path.abspath(path), name=name)
    obj.Label = os.path.splitext(os.path.basename(path))[0]
    recompute_document(doc, [obj])
    return obj


def export_structure(obj, path):
    """Writes the structure of a HexDom Polycube (.k as the original program's files; also .vtk,
    .vtu, .inp)."""
    from .objects import polycube
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
    from . import make
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
    if isinstance(label, str):
        by_name = {name: number for number, name in LABEL_NAMES.items()}
        if label.upper() not in by_name:
            raise ValueError("label '{}' is not one of +X -X +Y -Y +Z -Z".format(label))
        label = by_name[label.upper()]
    if not 1 <= int(label) <= 6:
        raise ValueError("label {} is not one of 1..6 (+X -X +Y -Y +Z -Z)".format(label))
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
    from . import make
    from .objects import hex_mesh
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
    from . import make
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


# ------------------------------------------------------------------------------------------------
# One-command meshing of a CAD part (issue 9): Surface -> Segmentation -> automatic Polycube ->
# Mesh, every intermediate object kept in the document and editable.

MESH_PART_STAGES = (("surface", "tessellate"), ("segmentation", "segment"),
                    ("polycube", "automatic polycube"), ("mesh", "generate and improve"))


class MeshPartError(RecomputeError):
    """A stage of mesh_part failed: ``stage`` names it, ``objects`` holds the objects created
    (all kept in the document, the finished ones valid), the message is the core's."""

    def __init__(self, message, stage=None, objects=None):
        super().__init__(message)
        self.stage = stage
        self.objects = objects or {}


def part_size(shape):
    """Target element size mesh_part uses when given 0, as `hexdom mesh`: the bounding-box
    diagonal / 30; for a part lying at an angle (its faces fit axes turned from the model's,
    core.cube_frame on a first tessellation), the diagonal of the box square to those axes / 30."""
    size = shape.BoundBox.DiagonalLength / 30.0
    if has_cad() and _core_has("cube_frame"):
        try:
            V, F, face = core.tessellate_brep(shape.exportBrepToString(), size=size)
        except core.Error:
            return size
        frame = core.cube_frame(core.Surface(V, F, face))
        if frame["turned"]:
            W = np.asarray(V) @ np.asarray(frame["rotation"]).T
            size = float(np.linalg.norm(W.max(axis=0) - W.min(axis=0))) / 30.0
    return size


def make_mesh_part(doc, part, size=0.0, level=1, improve=True):
    """Adds the four objects of mesh_part to ``doc`` without recomputing; returns them as a dict
    (surface, segmentation, polycube, mesh)."""
    from . import make
    shape = getattr(part, "Shape", None)
    if shape is None or shape.isNull() or not shape.Solids:
        raise ValueError("{}: select a Part solid to mesh".format(getattr(part, "Label", part)))
    size = float(size) if size and size > 0 else part_size(shape)
    if int(level) < 0:
        raise ValueError("level must be 0 or more")
    label = part.Label
    objs = {}
    # The tessellation of `hexdom mesh`: triangles of the element size, chords within size / 50.
    objs["surface"] = make.make_surface(doc, source=part, size=size, deflection=size / 50.0,
                                        angle=30.0)
    objs["segmentation"] = make.make_segmentation(doc, objs["surface"], method="Automatic")
    objs["polycube"] = make.make_polycube(doc, segmentation=objs["segmentation"], size=size,
                                          level=level)
    objs["mesh"] = make.make_hex_mesh(doc, segmentation=objs["segmentation"],
                                      polycube=objs["polycube"], level=level, improve=improve)
    try:  # one Level for both: the blocks are made for the mesh's subdivision
        objs["mesh"].setExpression("Level", objs["polycube"].Name + ".Level")
    except (AttributeError, RuntimeError, ValueError):
        pass
    for key, suffix in (("surface", "_surface"), ("segmentation", "_segmentation"),
                        ("polycube", "_polycube"), ("mesh", "_mesh")):
        objs[key].Label = label + suffix
    return objs


def choose_mesh_part(objs, run=None):
    """The candidate choice of `hexdom mesh` for mesh_part's objects: recomputes the Surface, runs
    core.mesh_surface on its triangles (the Polycube's Size and Level, the Mesh's Improve;
    segmentation edge weight, widths of holes, tet or hex blocks at apexes and the level drop
    chosen by measuring the meshes) and sets what it kept on the objects:
    Segmentation.EdgeWeight, Polycube.KeepWidths, .TetApexes and .Level (the Mesh's Level follows
    it), after putting the frame the faces fit (core.cube_frame) on Segmentation.Frame; when the
    mesh came from another tessellation (core.mesh_part tessellates again when the first one's
    labelling defeats the polycube or cells stay inverted after the snap), the Surface's Size and
    Deflection become that tessellation's. The rest is left to recompute, which rebuilds the kept
    candidate with ordinary, editable objects. The core call runs in a Progress (a worker thread
    under the GUI), or in ``run`` when given. Returns the core.MeshRun of the choice (core.mesh_part's,
    snapped; with a build without it, core.mesh_surface's on the Surface's triangles, not snapped),
    or None when the Surface or the choice failed or was cancelled: the objects keep their
    settings, and recomputing them reports the stage at fault (or cancelled)."""
    surface_obj, seg, poly = objs["surface"], objs["segmentation"], objs["polycube"]
    from .objects import tessellation
    surface_obj.Document.recompute([surface_obj])  # (obj.recompute() would leave it touched)
    state = surface_obj.State
    if "Invalid" in state or "Error" in state or not len(surface_obj.Triangles):
        return None
    surface = tessellation.get_surface(surface_obj)
    mesh = objs.get("mesh")
    # The frame the faces fit goes on the Segmentation first, and the choice is made in the frame
    # the objects will read back from it (a Rotation property: the same matrix to the last bit).
    from .objects import segmentation
    if hasattr(seg, "Frame"):
        fit = core.cube_frame(surface)
        segmentation.set_frame(seg, fit["rotation"] if fit["turned"] else None)
    frame = segmentation.frame_matrix(seg)
    # `hexdom mesh`'s own path on the Surface's shape when the build has it (the snap, and another
    # tessellation when this one's labelling defeats the polycube or cells stay inverted after the
    # snap); else the choice among the candidates on the Surface's triangles.
    source = getattr(surface_obj, "Source", None)
    shape = getattr(source, "Shape", None)
    whole = (hasattr(getattr(core, "_hexdom", None), "mesh_cad") and has_cad()
             and shape is not None and not shape.isNull()
             and abs(float(surface_obj.Size.Value) - float(poly.Size.Value)) <= 1e-12 * float(poly.Size.Value))
    options = dict(size=float(poly.Size.Value), level=int(poly.Level),
                   improve=bool(getattr(mesh, "Improve", True)), allow_inverted=True, align=False,
                   frame=frame)
    try:
        with Progress("Choosing the polycube of " + surface_obj.Label, 1) as bar:
            if whole:
                chosen = (run or bar.run)("choose the polycube", core.mesh_part,
                                          shape.exportBrepToString(), **options)
            else:
                chosen = (run or bar.run)("choose the polycube", core.mesh_surface, surface,
                                          **options)
            bar.step(chosen.choice)
    except Cancelled as e:  # the recompute then marks the next stage cancelled, keeping the objects
        import FreeCAD
        FreeCAD.Console.PrintLog("HexDom: {}: {}\n".format(poly.Label, e))
        return None
    except core.Error as e:
        import FreeCAD
        FreeCAD.Console.PrintLog("HexDom: {}: no choice of polycube ({}); recomputing with the "
                                 "defaults\n".format(poly.Label, e))
        return None
    factor = getattr(chosen, "tessellation_factor", 1.0)
    if factor != 1.0:  # the mesh is the one of another tessellation: the Surface makes that one
        surface_obj.Size = factor * float(surface_obj.Size.Value)
        surface_obj.Deflection = factor * float(surface_obj.Deflection.Value)
    if seg.EdgeWeight != chosen.edge_weight:
        seg.EdgeWeight = chosen.edge_weight
    for name, value in (("KeepWidths", chosen.keep_widths),
                        ("TetApexes", chosen.collapse_apexes), ("Level", chosen.level)):
        if getattr(poly, name) != value:
            setattr(poly, name, value)
    return chosen


def check_mesh_part(objs, allow_inverted=False):
    """Raises MeshPartError for the first of mesh_part's objects that failed (naming its stage
    and the core's message), or when the mesh has inverted cells (unless ``allow_inverted``)."""
    for key, stage in MESH_PART_STAGES:
        obj = objs.get(key)
        if obj is None:
            continue
        state = obj.State
        if "Invalid" in state or "Error" in state or "Touched" in state:
            message = obj.getStatusString() if hasattr(obj, "getStatusString") else ""
            if not message or message == "Touched":
                message = "not computed"
            raise MeshPartError("{} failed at {} ({}): {}".format(
                objs["mesh"].Label.rsplit("_mesh", 1)[0], stage, obj.Label, message),
                stage, objs)
    mesh = objs["mesh"]
    if mesh.InvertedCount and not allow_inverted:
        raise MeshPartError(
            "{}: {} inverted cells remain after improvement (worst hex SJ {:.3f}); the "
            "objects are kept: edit the Segmentation (Edit Patches) or switch the Polycube to "
            "Manual and edit it (Build Polycube)".format(mesh.Label, mesh.InvertedCount,
                                                         mesh.MinHexSJ), "mesh", objs)
    return objs


def mesh_part(doc, part, size=0.0, level=1, improve=True, recompute=True, allow_inverted=False):
    """Meshes the Part solid ``part`` with no manual step, as `hexdom mesh` does, keeping every
    stage as an editable document object: HexDom Surface (tessellation at ``size``, 0: bounding-box
    diagonal / 30), Segmentation (automatic), Polycube (Mode Automatic: blocks of size * 2^level)
    and Mesh (generated at ``level`` and improved if ``improve``; its Level follows the Polycube's).
    Before the recompute, choose_mesh_part makes `hexdom mesh`'s choice on the Surface's triangles
    (edge weight, widths of holes, tet or hex blocks at apexes, level ``level`` or one less) and
    sets it on the Segmentation and the Polycube, so that the Mesh is the one it kept.
    Returns a dict with keys surface, segmentation, polycube, mesh.

    With ``recompute`` the document is recomputed; a stage that fails raises MeshPartError naming
    the stage and the core's message (which names the charts or corners at fault), with the
    objects kept in the document (``error.objects``); so do inverted cells left in the mesh,
    unless ``allow_inverted``.
    """
    objs = make_mesh_part(doc, part, size=size, level=level, improve=improve)
    if recompute:
        with Progress("Meshing " + part.Label, 2) as bar:
            chosen = choose_mesh_part(objs)
            bar.step("chosen: " + (chosen.choice if chosen else "none"))
            doc.recompute()
            bar.step("recomputed")
        check_mesh_part(objs, allow_inverted)
        if chosen is not None:
            check_choice(objs, chosen)
    return objs


def check_choice(objs, chosen):
    """Warns (FreeCAD's report view) when the recomputed Mesh of mesh_part is not the mesh the
    choice produced (other element counts): the objects did not rebuild the kept candidate."""
    mesh = objs["mesh"]
    got = (mesh.HexCount, mesh.PrismCount, mesh.TetCount)
    want = tuple(chosen.mesh.count(t) for t in (core.HEX, core.WEDGE, core.TET))
    if got != want:
        import FreeCAD
        FreeCAD.Console.PrintWarning(
            "HexDom: {}: {} hex, {} prism, {} tet, but the choice ({}) gave {} hex, {} prism, "
            "{} tet\n".format(mesh.Label, *got, chosen.choice, *want))
    return got == want
