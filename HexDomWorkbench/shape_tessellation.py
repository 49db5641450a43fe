"""Tessellation of a Part shape into a core.Surface with the CAD face number per triangle: the
core's OCCT tessellation (core.tessellate_brep) when the build has it, else FreeCAD's MeshPart
(Mefisto per face, or the standard mesher remeshed by the core). FreeCAD and MeshPart are imported
inside the functions that use them, so that importing this module stays FreeCAD-free."""

import math

import numpy as np

from . import core
from .logic.stages import has_cad
from .logic.triangles import edge_uses, merge_points, triangle_normals

# Refuse tessellations beyond this many triangles (a Size far too small for the part).
MAX_TRIANGLES = 2_000_000


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
    rep = merge_points(V, 1e-7 * max(shape.BoundBox.DiagonalLength, 1e-12))
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
        _, uses = edge_uses(F)
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
