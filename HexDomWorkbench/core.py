"""The only module that imports the compiled core ``_hexdom``. FreeCAD-free: numpy in, numpy out.

Cell arrays follow the core's convention: ``cells`` is #C x 8 (int32) with unused slots -1,
``types`` holds VTK cell-type numbers (5 triangle, 9 quad, 10 tet, 12 hex, 13 wedge) in VTK node
order, ``region`` a region (block, part) id per cell.
"""

import importlib
import os
import sys
from dataclasses import dataclass

import numpy as np


def _load_core():
    """Finds _hexdom: inside this package (installed), on sys.path, or in a build tree."""
    try:
        return importlib.import_module(__package__ + "._hexdom")
    except ImportError:
        pass
    try:
        return importlib.import_module("_hexdom")
    except ImportError:
        pass
    here = os.path.dirname(os.path.abspath(__file__))
    candidates = [os.environ.get("HEXDOM_BUILD_DIR", ""), os.path.join(here, "..", "build")]
    for build in candidates:
        path = os.path.join(build, "python")
        if build and os.path.isdir(path):
            sys.path.insert(0, os.path.abspath(path))
            try:
                return importlib.import_module("_hexdom")
            except ImportError:
                sys.path.pop(0)
    raise ImportError(
        "HexDom's compiled module _hexdom was not found: build it with 'make build' "
        "(or set HEXDOM_BUILD_DIR to the CMake build directory)")


_hexdom = _load_core()
Error = _hexdom.Error
InputError = _hexdom.InputError
GeometryError = _hexdom.GeometryError
MeshingError = _hexdom.MeshingError
# A stop flag for core calls (``with interrupt:`` on the calling thread, ``interrupt.cancel()`` from
# another), and what an interrupted call raises (not an Error).
Interrupt = _hexdom.Interrupt
Interrupted = _hexdom.Interrupted

TRIANGLE, QUAD, TET, HEX, WEDGE = 5, 9, 10, 12, 13
TET10, HEX20, WEDGE15 = 24, 25, 26  # second order: corners, then a node per edge (VTK's order)
TYPE_NAMES = {TRIANGLE: "triangle", QUAD: "quad", TET: "tet", HEX: "hex", WEDGE: "prism",
              TET10: "tet10", HEX20: "hex20", WEDGE15: "wedge15"}
NODE_COUNT = {TRIANGLE: 3, QUAD: 4, TET: 4, HEX: 8, WEDGE: 6, TET10: 10, HEX20: 20, WEDGE15: 15}
ORDERS = (1, 2)


@dataclass
class Mesh:
    """Mixed hex / prism / tet (or surface) mesh in VTK node order."""

    V: np.ndarray  # (#V, 3) float64
    cells: np.ndarray  # (#C, 8) int32, -1 padded; (#C, 20) for a second-order mesh
    types: np.ndarray  # (#C,) int32 VTK cell types
    region: np.ndarray  # (#C,) int32

    def count(self, vtk_type):
        return int(np.count_nonzero(self.types == vtk_type))

    @property
    def order(self):
        """2 for a mesh of hex20 / wedge15 / tet10 cells, else 1."""
        return 2 if np.isin(self.types, (TET10, HEX20, WEDGE15)).any() else 1

    @property
    def counts(self):
        return {name: self.count(t) for t, name in TYPE_NAMES.items()}


@dataclass
class Surface:
    """Triangle surface with a patch id per triangle."""

    V: np.ndarray  # (#V, 3)
    F: np.ndarray  # (#F, 3)
    patch: np.ndarray  # (#F,)


def read_mesh(path):
    """Reads .k, .vtk, .vtu, .inp, .msh (Gmsh), .stl or .obj into a Mesh."""
    return Mesh(*_hexdom.read_mesh(os.fspath(path)))


def write_mesh(path, mesh, binary=False):
    """Writes .k, .vtk, .vtu, .inp, .stl or .obj, chosen by extension; no file is left on error."""
    _hexdom.write_mesh(os.fspath(path), mesh.V, mesh.cells, mesh.types, mesh.region, binary)


def read_surface(path):
    """Reads a triangle surface (.k shells, .stl, .obj, .vtk) into a Surface."""
    return Surface(*_hexdom.read_surface(os.fspath(path)))


def write_surface(path, surface):
    _hexdom.write_surface(os.fspath(path), surface.V, surface.F, surface.patch)


def remesh_triangles(surface, size=0.0, iterations=10):
    """The closed Surface remeshed onto itself (near-equilateral triangles of about ``size``, 0:
    bounding-box diagonal / 30); ``patch`` holds the face id each new triangle lies on."""
    return Surface(*_hexdom.remesh_triangles(surface.V, surface.F, surface.patch, float(size), int(iterations)))


def cell_metrics(mesh):
    """Per-cell (scaled_jacobian, edge_ratio, volume) arrays, Verdict's definitions."""
    return _hexdom.cell_metrics(mesh.V, mesh.cells, mesh.types)


def quality_report(mesh):
    """Dict with keys hex, prism, tet (count, sj_min, sj_mean, inverted, edge_ratio_min,
    edge_ratio_max, volume, histogram) and total_volume."""
    return _hexdom.quality_report(mesh.V, mesh.cells, mesh.types)


def face_sets(mesh, surface, node_faces=None):
    """{CAD face id: 0-based node indices, sorted} of the volume ``mesh``'s boundary: the nodes of
    the boundary faces lying on each CAD face (mid-edge nodes included for a second-order mesh),
    each face's CAD face being the face id of the triangle of ``surface`` (the tessellation the
    mesh was made from, ids as FreeCAD's Face<k>) nearest its centre. ``node_faces`` (the snap
    report's "faces": per node the CAD faces it was snapped onto, -1 padded): a face takes the CAD
    face its corners share, and a node snapped onto other faces only is left out of a face's
    nodes (a boundary quad the overlay lets straddle a sharp curve). Empty without triangles."""
    if surface is None or not len(surface.F):
        return {}
    args = {}
    if node_faces is not None and len(node_faces):
        args["node_faces"] = np.asarray(node_faces, np.int32)
    out = _hexdom.face_sets(mesh.V, mesh.cells, mesh.types, surface.V, np.asarray(surface.F, np.int32),
                            np.asarray(surface.patch, np.int32), **args)
    return {int(k): np.asarray(v) for k, v in out[4].items()}


def generate(surface, structure, level=2, relax_sweeps=10, snap_tolerance=1e-4, untangle=True, threads=0):
    """Hex-dominant mesh from a segmented Surface and a polycube structure Mesh (hex, prism and tet
    blocks): 8^level cells per block, conforming across blocks; region = 1-based block number.
    untangle: after the plain relaxation, untangle the cells it leaves inverted (boundary nodes may
    slide within the surface). threads: 0 = one per hardware thread; the result is the same."""
    return Mesh(*_hexdom.generate(surface.V, surface.F, surface.patch, structure.V, structure.cells,
                                  structure.types, level, relax_sweeps, snap_tolerance, untangle, threads))


def mesh_structure(surface, structure, level=None, improve=True, threads=0, frame=None, stretch=None):
    """The polycube path's generation and improvement on a polycube ``structure`` (a Mesh of hex,
    prism and tet blocks) over its patch Surface ``surface`` at ``level`` (None: `hexdom mesh`'s),
    as `hexdom mesh` runs them after building the polycube (pipeline::generate_and_improve): the
    same options, one call. stretch (with frame: MeshRun.stretch and frame["rotation"]): both
    meshed stretched so, as the pipeline meshes a thin part, the mesh mapped back. Returns a
    MeshRun (mesh, generated, quality, generated_quality, seconds, level; no labels nor
    polycube)."""
    extra = {} if level is None else {"level": int(level)}
    return _mesh_run(_hexdom.mesh_structure(surface.V, surface.F, surface.patch, structure.V,
                                            structure.cells, structure.types, improve=bool(improve),
                                            threads=int(threads), frame=_frame_arg(frame),
                                            stretch=_stretch_arg(stretch), **extra))


def check_surface(surface, name="the surface", self_intersection=True):
    """The checks every meshing path makes on its input first: closed and 2-manifold, consistently
    oriented, no two triangles crossing or lying on each other, one solid (cavities nested one
    deep). Returns (Surface with every shell facing out of the solid, list of warnings: one per
    shell turned around, e.g. an inside-out export); raises GeometryError naming an edge, two
    crossing triangles and a point, or the separate solids (``name`` prefixes the messages)."""
    r = _hexdom.check_surface(surface.V, surface.F, surface.patch, str(name), bool(self_intersection))
    return Surface(*r["surface"]), list(r["warnings"])


def mesh_options():
    """The defaults of `hexdom mesh`'s options, from the core's header (pipeline::MeshCadOptions,
    the CLI's defaults too), by the keyword names of mesh_part and mesh_surface: size, level,
    method, improve, align, snap, polycube_seconds, time_limit, edge_weight, max_relabels,
    relax_sweeps, threads, target_sj, target_volume, target_edge_ratio."""
    return dict(_hexdom.mesh_options())


MESH_OPTIONS = mesh_options()

# The largest edge ratio the pipeline aims at (pipeline::MeshSurfaceOptions::target_edge_ratio): its
# improvement and snap pass it as max_edge_ratio (the Mesh object does the same through improve and
# snap_to_brep, which by themselves, as `hexdom improve`, leave edge ratios alone).
TARGET_EDGE_RATIO = float(MESH_OPTIONS["target_edge_ratio"])


def improve(mesh, surface=None, pillow=False, smooth=0, optimize=0, feature_angle=35.0,
            sharp_nodes=(), max_edge_ratio=0.0):
    """Pillowing, smoothing and Jacobian optimisation of a Mesh. With no stage set, runs the
    recommended sequence until the worst cell stops improving, then raises the mean scaled Jacobian
    without lowering the worst hex, prism or tet; then, for cells whose edge ratio is above
    max_edge_ratio (0: none), moves their nodes to lower it: no cell at or above 0.3 taken below
    it, each type's worst scaled Jacobian kept, then lowered in two steps towards 0.3 while cells
    stay above max_edge_ratio.
    Boundary nodes stay on `surface` (a Surface) or on the mesh's own boundary."""
    sv, sf = (surface.V, surface.F) if surface is not None else (None, None)
    return Mesh(*_hexdom.improve(mesh.V, mesh.cells, mesh.types, mesh.region, pillow, smooth,
                                 optimize, feature_angle, list(sharp_nodes), sv, sf,
                                 float(max_edge_ratio)))


# ------------------------------------------------------------------------------------------------
# Segmentation: CVT labelling, the polycube check, the polycube boundary, patch editing.
# Labels are 1..6 (+X, -X, +Y, -Y, +Z, -Z), as `hexdom segment` writes them as part ids; patch
# numbers are 1-based (order of each patch's first triangle); vertex and triangle indices 0-based.

LABEL_NAMES = {1: "+X", 2: "-X", 3: "+Y", 4: "-Y", 5: "+Z", 6: "-Z"}


@dataclass
class Segmentation(Surface):
    """A labelled Surface: ``patch`` holds the label 1..6 of each triangle (write it with
    write_surface to get what `hexdom segment` writes). ``classical`` holds the labels after the
    classical CVT pass, ``generators`` (6 x 3) its generator normals, ``info`` the sweep counts and
    what was done with CAD faces."""

    classical: np.ndarray = None
    generators: np.ndarray = None
    info: dict = None


def segment(surface, edge_weight=0.1, respect_faces=None, manual=None, classical_sweeps=50,
            edge_sweeps=200, min_moves=3, max_drift=10.0, ring=2, planar_angle=1.0,
            face_majority=0.9, frame=None, stretch=None):
    """Polycube segmentation of a closed Surface: CVT of the triangle normals with the generators
    +-X, +-Y, +-Z, classical energy first, then the edge-weighted energy (lambda = edge_weight)
    that removes zig-zag boundaries. respect_faces: None = when surface.patch has more than one id
    (CAD faces, e.g. from tessellation): planar faces keep one label and boundaries follow CAD edges
    where they can. manual: a path to the original's override file ("triangle label", 0-based) or
    (triangle, label 1..6) rows. frame: a 3 x 3 rotation (cube_frame()["rotation"], MeshRun.frame):
    the labels name its axes. stretch: factors along the frame's axes (MeshRun.stretch): the surface
    is segmented stretched so, as the pipeline segments a thin part. Returns a Segmentation."""
    if isinstance(manual, (str, os.PathLike)):
        manual = read_manual_labels(manual)
    if manual is not None:
        manual = np.asarray(manual, np.int32).reshape(-1, 2)
    r = _hexdom.segment(surface.V, surface.F, surface.patch, edge_weight, classical_sweeps,
                        edge_sweeps, min_moves, max_drift, ring, respect_faces, planar_angle,
                        face_majority, manual, _frame_arg(frame), _stretch_arg(stretch))
    info = {k: v for k, v in r.items() if k not in ("label", "classical", "generators")}
    return Segmentation(surface.V, surface.F, r["label"], r["classical"], r["generators"], info)


def cube_frame(surface, min_gain=0.02):
    """The frame the triangle normals of a Surface fit best (a part lying at an angle): a dict with
    rotation (3 x 3, x_frame = rotation @ x), fit, fit_identity, angle (degrees), axis and turned
    (False: the model's own axes fit within min_gain, rotation is the identity)."""
    return _hexdom.cube_frame(surface.V, surface.F, float(min_gain))


def cell_faces(vtk_type):
    """The faces of a hex (12), wedge (13) or tet (10): tuples of local node indices in VTK order,
    each outward (the core's one face table)."""
    return [tuple(f) for f in _hexdom.cell_faces(int(vtk_type))]


def nearest_label(normals):
    """Label 1..6 of the axis nearest each row of ``normals`` (#N x 3, or one vector: an array of
    one label); ties and zero rows go to the lower label."""
    return _hexdom.nearest_label(np.asarray(normals, np.float64).reshape(-1, 3)).astype(np.int32)


def _frame_arg(frame):
    return None if frame is None else np.asarray(frame, np.float64).reshape(3, 3)


def _stretch_arg(stretch):
    return None if stretch is None else np.asarray(stretch, np.float64).reshape(3)


def labels_from_normals(V, F, patch=None, frame=None, stretch=None):
    """Label 1..6 per triangle: the axis nearest its normal, or with ``patch`` the axis nearest the
    area-weighted normal of the triangle's patch (one label per patch). frame: a 3 x 3 rotation whose
    axes the labels name (x_frame = frame @ x); None: the model's. stretch: factors along the
    frame's axes (MeshRun.stretch): the normals of the surface stretched so."""
    return _hexdom.labels_from_normals(
        np.asarray(V, np.float64), np.asarray(F, np.int32).reshape(-1, 3),
        None if patch is None else np.asarray(patch, np.int32), _frame_arg(frame),
        _stretch_arg(stretch)).astype(np.int32)


def frame_diagonal(surface, rotation):
    """Diagonal of the bounding box of a Surface turned into a frame (x_frame = rotation @ x): the
    default element size is this / 30."""
    return float(_hexdom.frame_diagonal(surface.V, surface.F, np.asarray(rotation, np.float64).reshape(3, 3)))


def read_manual_labels(path):
    """The original's manual override file as (triangle 0-based, label 1..6) rows."""
    return _hexdom.read_manual_labels(os.fspath(path))


def segmentation_stats(surface, max_angle=55.0):
    """Figures of the labelling surface.patch (1..6): patches, small_patches, boundary_length,
    teeth (zig-zag triangles), axis_fraction (area share within max_angle of its label's axis),
    label_axis_fraction and label_area per label."""
    return _hexdom.segmentation_stats(surface.V, surface.F, surface.patch, max_angle)


@dataclass
class Violation:
    """One violated polycube condition: kind ("opposite_orientations", "two_patch_corner",
    "curve_count", "not_disk"), the 1-based patches, a 0-based vertex and its location."""

    kind: str
    patches: list
    vertex: int
    location: np.ndarray
    message: str

    def __str__(self):
        return self.message


@dataclass
class PatchCheck:
    """Result of check_patches. Iterating over it yields its violations (str() = message)."""

    valid: bool
    patches: list  # dicts: patch, id, orientation, orientation_name, normal, area, triangles,
    #                type, curves, loops, euler, corners, neighbours
    corners: list
    curves: int
    violations: list

    def __iter__(self):
        return iter(self.violations)

    def __len__(self):
        return len(self.violations)


def check_patches(surface, opposite_angle=135.0, corner_defect=70.0, corner_angle=0.0,
                  turn_window=3.0, triangular_ids=()):
    """The polycube conditions on a segmented Surface (patch = connected region of one id):
    opposite orientations sharing a boundary, corners shared by fewer than three patches,
    quadrilateral patches without 4 boundary curves and triangular ones without 3, patches that
    are not disks. Returns a PatchCheck (falsy ``valid`` and a list of violations)."""
    r = _hexdom.check_patches(surface.V, surface.F, surface.patch, opposite_angle, corner_defect,
                              corner_angle, turn_window, list(triangular_ids))
    violations = [Violation(v["kind"], list(v["patches"]), v["vertex"], v["location"], v["message"])
                  for v in r["violations"]]
    return PatchCheck(r["valid"], r["patches"], list(r["corners"]), r["curves"], violations)


@dataclass
class PolycubeBoundary:
    """Corners, edges and faces of the polycube a segmentation asks for; ``shells`` is the Mesh of
    the original's initial polycube file (one quad or triangle per patch over its corners)."""

    corner_vertices: np.ndarray  # (#C,) 0-based surface vertices, ascending
    corners: np.ndarray  # (#C, 3)
    edges: list  # dicts: corners (2 corner indices), patches (2), path (surface vertices)
    faces: list  # dicts: patch, id, corners (3 or 4 corner indices, counter-clockwise)
    shells: Mesh


def polycube_boundary(surface):
    """Polycube boundary of a segmented Surface; raises GeometryError when a patch is not a disk
    with 3 or 4 corners."""
    r = _hexdom.polycube_boundary(surface.V, surface.F, surface.patch)
    return PolycubeBoundary(np.asarray(r["corner_vertices"], np.int32), r["corners"], r["edges"],
                            r["faces"], Mesh(*r["shells"]))


def match_faces_to_patches(faces, patch_corners):
    """Matches the faces of a structure's blocks to the patches by their corners (the core's
    polycube::match_faces_to_patches). faces: (block, vertices) pairs, every face of every block;
    patch_corners: each patch's corner vertices. Returns (problems, face_of_patch,
    patch_of_face): problems as dicts (kind: "patches_share_corners", "face_in_many_blocks",
    "face_on_no_patch", "patch_on_no_face" or "patch_on_many_faces"; patches: 0-based; faces:
    indices into ``faces``, every use of the face; vertices: sorted; message), then per patch
    the index of its boundary face and per face its patch (-1: none)."""
    r = _hexdom.match_faces_to_patches([(int(b), [int(v) for v in vs]) for b, vs in faces],
                                       [[int(v) for v in c] for c in patch_corners])
    return r["problems"], r["face_of_patch"], r["patch_of_face"]


def number_patches(surface):
    """Patch map with one id per connected region, 1..R (order of first triangle)."""
    return _hexdom.number_patches(surface.V, surface.F, surface.patch)


def reassign_triangles(surface, triangles, patch_id=0):
    """New patch map: ``triangles`` take ``patch_id`` (0: a new id, the largest + 1)."""
    return _hexdom.reassign_triangles(surface.V, surface.F, surface.patch,
                                      [int(t) for t in np.asarray(triangles).reshape(-1)], int(patch_id))


def merge_patches(surface, a, b):
    """New patch map: patch id ``b`` joins patch id ``a`` (they must share an edge)."""
    return _hexdom.merge_patches(surface.V, surface.F, surface.patch, int(a), int(b))


def split_patch(surface, patch_id, path):
    """New patch map: patch ``patch_id`` cut along a path of vertices (consecutive ones joined by
    the shortest chain of its interior edges); the part without its first triangle gets a new id."""
    return _hexdom.split_patch(surface.V, surface.F, surface.patch, int(patch_id),
                               [int(v) for v in np.asarray(path).reshape(-1)])


# CAD stage (hexdom_cad, OpenCASCADE): present when _hexdom was built with it. tessellate_* return
# (V, F, face_id) with 1-based CAD face ids (FreeCAD's FaceN); project_* keep nodes on the B-rep.
has_opencascade = getattr(_hexdom, "has_opencascade", lambda: False)
if has_opencascade():
    tessellate_file = _hexdom.tessellate_file
    tessellate_brep = _hexdom.tessellate_brep
    cad_volume = _hexdom.cad_volume
    cad_info = _hexdom.cad_info
    project_to_face = _hexdom.project_to_face
    project_to_edge = _hexdom.project_to_edge
    project_to_shape = _hexdom.project_to_shape


SNAP_KINDS = {0: "interior", 1: "face", 2: "edge", 3: "vertex"}


def snap_to_brep(mesh, source, surface, solid=0, edge_tolerance=0.25, smooth=3, optimize=20,
                 max_edge_ratio=0.0, face_only=None):
    """Puts the boundary nodes of ``mesh`` (a Mesh of hex / prism / tet cells) exactly on the B-rep of
    ``source`` (a .step/.iges/.brep path or BREP text), using the CAD face ids of ``surface`` (its
    tessellation, e.g. Surface(*tessellate_file(...)), patch = 1-based CAD face) to decide which node
    goes onto a CAD face, edge (within edge_tolerance x its shortest boundary edge) or vertex; then
    untangles and optimises the interior with the boundary held (and lowers edge ratios above
    max_edge_ratio, 0: none, as improve does). ``face_only`` (one flag per node, or None): nodes that
    go onto their nearest CAD face only, never an edge or vertex; an overlay run's
    MeshRun.face_only, so that its mesh is snapped as `hexdom mesh` snaps it. Returns (Mesh, report dict:
    boundary_nodes, face_nodes, edge_nodes, vertex_nodes, max_before / mean_before / max_after /
    mean_after B-rep distances (max_distance = max_after), max_move, diagonal, inverted_snapped, inverted, worst_sj_before,
    worst_sj_snapped, worst_sj, seconds_project, seconds_restore, quality, kind and entity per node
    (see SNAP_KINDS), faces: #V x k, the CAD faces each node lies on, -1 padded). Inverted cells are
    reported, not raised."""
    if not has_opencascade():
        raise Error("built without OpenCASCADE: cannot snap a mesh to the B-rep")
    text = os.fspath(source) if isinstance(source, os.PathLike) else source
    m, report = _hexdom.snap_to_brep(text, mesh.V, mesh.cells, mesh.types, mesh.region, surface.V,
                                     surface.F, surface.patch, solid=int(solid),
                                     edge_tolerance=float(edge_tolerance), smooth=int(smooth),
                                     optimize=int(optimize), max_edge_ratio=float(max_edge_ratio),
                                     face_only=[int(bool(x)) for x in (face_only if face_only is not None else [])])
    report = dict(report)
    report["max_distance"] = report["max_after"]
    return Mesh(*m), report


def second_order(mesh, surface, source=None, snap=None, solid=0, min_sj=None):
    """The first-order ``mesh`` made second order (hex20 / wedge15 / tet10, `hexdom mesh --order 2`):
    a node on every cell edge, those of the boundary on the B-rep of ``source`` (path or BREP text;
    ``snap`` the report snap_to_brep gave for this mesh, whose kind and entity say which CAD edge or
    vertex each boundary node is on, and ``surface`` the tessellation it used) or, without a source,
    on the triangle Surface ``surface``; each pulled back towards its edge's midpoint only where a
    cell would fall below min(min_sj, its straight value). Returns (Mesh, report dict:
    boundary_mid_nodes, edge_targets, face_targets, max_offset, diagonal, placed, shortened,
    straight, max_gap, worst_sj, inverted, seconds)."""
    args = {}
    if source is not None:
        if not has_opencascade():
            raise Error("built without OpenCASCADE: cannot put mid-edge nodes on a B-rep")
        if snap is None:
            raise InputError("second_order: a B-rep source needs the snap report of the mesh (its kind and entity)")
        args = dict(source=os.fspath(source) if isinstance(source, os.PathLike) else source,
                    kind=[int(k) for k in snap["kind"]], entity=[int(e) for e in snap["entity"]], solid=int(solid))
    if min_sj is not None:
        args["min_sj"] = float(min_sj)
    m, report = _hexdom.second_order(mesh.V, mesh.cells, mesh.types, mesh.region, surface.V, surface.F,
                                     surface.patch, **args)
    return Mesh(*m), dict(report)


# ------------------------------------------------------------------------------------------------
# Automatic path (issue 9): autopolycube builds a polycube structure and the patch surface that goes
# with it from a labelled surface; mesh_surface runs segment -> autopolycube -> generate -> improve.


@dataclass
class AutoPolycube:
    """Result of autopolycube: ``structure`` (hex blocks over the grid cells; prisms under a strip
    chart along a knife edge), ``patches`` (the input geometry re-split along the grid, one patch per
    boundary block face: give both to generate), ``labels`` (the repaired labelling on the surface the
    map used), ``polycube`` (that surface at its polycube positions) and ``info`` (cell, charts,
    relabelled, chords, planes, pushed, squares, blocks, boundary_vertices, interior_vertices,
    slivers, prism_blocks, tet_blocks, oblique_faces, apexes, apexes_collapsed, widened,
    min_block_quality, inverted_blocks: the core's AutoPolycube figures, as its for_each_figure
    names them)."""

    structure: Mesh
    patches: Surface
    labels: Surface
    polycube: Surface
    info: dict


def _auto_polycube(r):
    info = {k: v for k, v in r.items() if k not in ("structure", "patches", "labels", "polycube")}
    return AutoPolycube(Mesh(*r["structure"]), Surface(*r["patches"]), Surface(*r["labels"]),
                        Surface(*r["polycube"]), info)


def autopolycube(labels, size=0.0, level=1, max_relabels=200, max_attempts=20,
                 max_relabel_area=0.03, untangle_rounds=50, keep_widths=True,
                 collapse_apexes=True, frame=None, stretch=None, max_same_problem=3):
    """Polycube structure of a labelled Surface (patch = label 1..6 per triangle, e.g. from
    segment()) with no manual step: blocks are the grid cells of spacing h = size * 2^level
    (size 0: bounding-box diagonal / 30) inside the polycube the charts are flattened onto (prism
    blocks where a strip chart runs along a knife edge); the surface is cut along the grid lines
    into one patch per boundary block face, so that
    generate(result.patches, result.structure, level) takes the pair unchanged. keep_widths: the
    walls of a hole keep their distance in cells (False: least-squares plane offsets);
    collapse_apexes: the blocks under an apex cap become tets and prisms (False: hexes). The two
    are the candidates mesh_surface chooses between (MeshRun.keep_widths, .collapse_apexes).
    frame: the rotation the labels refer to (segment's frame); every result is in the input's
    coordinates. stretch: factors along the frame's axes (MeshRun.stretch): the polycube is built
    on the labels stretched so (``size`` in that space), every result mapped back. Raises
    GeometryError naming the charts when the labelling cannot be repaired, also when
    max_same_problem rounds in a row end in the very same problem (the repair is not converging).
    Returns an AutoPolycube."""
    return _auto_polycube(_hexdom.autopolycube(labels.V, labels.F, labels.patch, float(size),
                                               int(level), int(max_relabels), int(max_attempts),
                                               float(max_relabel_area), int(untangle_rounds),
                                               bool(keep_widths), bool(collapse_apexes),
                                               _frame_arg(frame), _stretch_arg(stretch),
                                               int(max_same_problem)))


MESH_STAGES = ("segment", "autopolycube", "generate", "improve")


@dataclass
class MeshRun:
    """Result of mesh_surface / mesh_part: the final ``mesh``, the ``generated`` one before
    improvement, the segmentation ``labels``, the ``polycube`` (an AutoPolycube), the quality reports
    (dicts as quality_report gives) and ``seconds`` per stage (segment, autopolycube, generate,
    improve; tessellate and snap too for mesh_part), the ``level`` of the result (one less than
    asked when inverted cells remained and the finer grid did better) and the segmentation's
    ``edge_weight`` that autopolycube took (the next of 1, 0.3, 3 when the asked one defeated
    it). ``keep_widths`` and ``collapse_apexes`` are the polycube options of the candidate kept
    (see autopolycube): segment(edge_weight=edge_weight) then autopolycube(level=level,
    keep_widths=..., collapse_apexes=..., both with frame=frame["rotation"]) rebuild its polycube;
    ``frame`` is the cube_frame dict of the axes the labels refer to; ``stretch`` the factors along
    its axes a thin part was stretched by for segmenting, the polycube and generation (ones: not
    stretched; pass it with the frame to segment, autopolycube and mesh_structure to rebuild
    them); ``choice`` says it in words.
    ``snap`` holds snap_to_brep's report for mesh_part (None otherwise). ``method`` names the path
    that made the mesh: "polycube" or "overlay" (a grid laid over the part; its run has no labels
    nor polycube, and level, edge_weight and the polycube options mean nothing then);
    ``polycube_note`` says why the overlay was tried in auto mode (empty otherwise). ``solids``:
    the solids the surface bounds (separate closed shells, each with its cavities), each meshed on
    its own; with more than one, the mesh's region is the solid (1, 2, ...), ``polycube`` is
    empty and the options are the first solid's."""

    mesh: Mesh
    generated: Mesh
    labels: Surface
    polycube: AutoPolycube
    quality: dict
    generated_quality: dict
    seconds: dict
    level: int = 1
    edge_weight: float = 0.1
    snap: dict = None
    keep_widths: bool = True
    collapse_apexes: bool = True
    choice: str = ""
    frame: dict = None
    stretch: tuple = (1.0, 1.0, 1.0)  # factors along the frame's axes (see above)
    surface: Surface = None  # mesh_part: the tessellation meshed
    tessellations: int = 1   # mesh_part: tessellations made (see cad::MeshCadOptions::retessellate)
    tessellation_factor: float = 1.0  # mesh_part: the kept one's triangle size over the first's
    tessellation_size: float = 0.0   # mesh_part: the kept one's target triangle size (its chords within size / 50)
    method: str = "polycube"  # the path that made the mesh: "polycube" or "overlay"
    polycube_note: str = ""   # auto mode: why the overlay was tried (the polycube failed or missed a target)
    face_only: list = None    # overlay mesh: per node, 1 when it goes onto a CAD face only (snap_to_brep's face_only)
    solids: int = 1           # solids meshed (each its own region when more than one)
    touching: list = None     # several solids: the pairs (1-based) that touch (meshes not conforming there)
    warnings: list = None     # what the run warned of (`hexdom mesh`'s warning lines: shells turned, solids touching)
    second_order: dict = None  # order 2: how the mid-edge nodes were placed (_hexdom.mesh_surface's)
    # face_sizes / edge_sizes: per size (faces first, then edges, each by number), the median cell
    # size there over the size asked (0: no cell there); auto prefers the path within 20% on more
    local_size_ratios: list = None
    local_size_met: list = None  # per size, whether the core counts it as met (within 20%)

    @property
    def inverted(self):
        """Inverted cells: of the curved cells for a second-order mesh."""
        types = ("hex20", "wedge15", "tet10") if self.quality.get("order", 1) == 2 else ("hex", "prism", "tet")
        return sum(self.quality[t]["inverted"] for t in types)


def _mesh_run(r):
    """A MeshRun of the dict _hexdom.mesh_surface returns."""
    return MeshRun(Mesh(*r["mesh"]), Mesh(*r["generated"]), Surface(*r["labels"]),
                   _auto_polycube(r["polycube"]), r["quality"], r["generated_quality"],
                   dict(zip(MESH_STAGES, r["seconds"])), int(r["level"]), float(r["edge_weight"]),
                   keep_widths=bool(r["keep_widths"]), collapse_apexes=bool(r["collapse_apexes"]),
                   choice=str(r["choice"]), frame=dict(r["frame"]),
                   stretch=tuple(float(f) for f in r.get("stretch", (1.0, 1.0, 1.0))),
                   method=str(r.get("method", "polycube")), polycube_note=str(r.get("polycube_note", "")),
                   face_only=list(r.get("face_only", [])), solids=int(r.get("solids", 1)),
                   touching=[tuple(int(k) for k in pair) for pair in r.get("touching", [])],
                   warnings=[str(w) for w in r.get("warnings", [])],
                   second_order=None if r.get("second_order") is None else dict(r["second_order"]),
                   local_size_ratios=[float(x) for x in r.get("local_size_ratios", [])],
                   local_size_met=[bool(x) for x in r.get("local_size_met", [])])


def _cad_run(r):
    """A MeshRun of the dict _hexdom.mesh_cad returns."""
    run = _mesh_run(r["run"])
    run.surface = Surface(*r["surface"])
    run.seconds = {"tessellate": float(r["tessellate_seconds"]), **run.seconds}
    run.tessellations = int(r["tessellations"])
    run.tessellation_factor = float(r["tessellation_factor"])
    run.tessellation_size = float(r.get("tessellation_size", 0.0))
    run.touching = [tuple(int(k) for k in pair) for pair in r.get("touching", [])]
    run.warnings = [str(w) for w in r.get("warnings", [])]
    if r.get("snap") is not None:
        run.snap = dict(r["snap"])
        run.snap["max_distance"] = run.snap["max_after"]
        if run.second_order is None:  # the same report (the run's is after the snap too)
            run.quality = run.snap["quality"]
        run.seconds["snap"] = float(r["snap_seconds"])
    return run


def _attach_partial(error, convert):
    """Sets ``error.run`` (a MeshRun of what the finished stages made, from the dict the core put
    on the error as ``partial``; None without one) and ``error.stage`` (the stage that failed,
    "" if unknown)."""
    partial = getattr(error, "partial", None)
    error.run, error.stage = None, ""
    if isinstance(partial, dict):
        try:
            error.run = convert(partial)
        except (KeyError, TypeError, ValueError):
            error.run = None
        error.stage = str(partial.get("stage", ""))


MESH_METHODS = ("auto", "polycube", "overlay")


def _method_args(method, polycube_seconds=None):
    """The method= and polycube_seconds= keywords for _hexdom (none for "auto" and None, so that a
    build without them still runs)."""
    if method not in MESH_METHODS:
        raise InputError("unknown meshing method '{}': auto, polycube or overlay".format(method))
    args = {} if method == "auto" else {"method": method}
    if polycube_seconds is not None:
        args["polycube_seconds"] = float(polycube_seconds)
    return args


def _order_args(order):
    """The order= keyword for _hexdom (none for 1); InputError for an order other than 1 or 2."""
    if order not in ORDERS:
        raise InputError("element order {!r}: the order is 1 or 2".format(order))
    return {} if int(order) == 1 else {"order": int(order)}


def _time_args(time_limit):
    """The time_limit= keyword for _hexdom (none for None: the core's default); InputError when
    negative."""
    if time_limit is None:
        return {}
    if not float(time_limit) >= 0:
        raise InputError("time_limit must be 0 (no limit) or positive, not {}".format(time_limit))
    return {"time_limit": float(time_limit)}


SIZE_BOUNDS = ("max_size", "min_size", "cells_across", "growth_rate")


def _size_args(**bounds):
    """The max_size=, min_size=, cells_across= and growth_rate= keywords for _hexdom that differ
    from the core's defaults (MESH_OPTIONS); a negative one raises InputError (the core checks the
    rest)."""
    args = {}
    for name in SIZE_BOUNDS:
        value = bounds.get(name)
        if value is None:
            continue
        if not float(value) >= 0:
            raise InputError("{} must be 0 or more, not {}".format(name, value))
        if float(value) != MESH_OPTIONS.get(name, 0.0):
            args[name] = float(value)
    return args


def _face_size_args(face_sizes, keyword="face_sizes", what="face"):
    """The face_sizes= (or edge_sizes=) keyword for _hexdom: {number: size} from a dict or pairs,
    as int and float (the core refuses numbers below 1 and sizes not positive); empty or None:
    none. InputError naming an entry that is not a whole number and a number."""
    if not face_sizes:
        return {}
    sizes = {}
    for number, size in dict(face_sizes).items():
        try:
            n, value = int(number), float(size)
        except (TypeError, ValueError):
            n, value = None, None
        if n is None or n != number:
            raise InputError("{} {{{!r}: {!r}}}: a {} number and a size".format(keyword, number, size, what))
        sizes[n] = value
    return {keyword: sizes}


def mesh_surface(surface, size=MESH_OPTIONS["size"], level=MESH_OPTIONS["level"],
                 edge_weight=MESH_OPTIONS["edge_weight"], max_relabels=MESH_OPTIONS["max_relabels"],
                 relax_sweeps=MESH_OPTIONS["relax_sweeps"], improve=MESH_OPTIONS["improve"],
                 allow_inverted=False, align=MESH_OPTIONS["align"], frame=None,
                 method=MESH_OPTIONS["method"], polycube_seconds=None, max_size=None, min_size=None,
                 cells_across=None, face_sizes=None, growth_rate=None, order=1, time_limit=None,
                 pillow_curves=MESH_OPTIONS["pillow_curves"]):
    """Hex mesh of a closed Surface with no manual step: segment -> autopolycube -> generate ->
    improve. ``size`` is the target element size (0: bounding-box diagonal / 30), blocks are cells
    of size * 2^level. align: segment and build the polycube in the frame the faces fit
    (cube_frame; a part lying at an angle), False: in the model's axes; frame: in the frame of this
    3 x 3 rotation (x_frame = frame @ x) instead. method: "polycube" (the path above), "overlay"
    (a grid laid over the part: any closed surface; size and align only) or "auto" (the polycube,
    and the overlay too when the polycube fails or misses a target, the better kept: MeshRun.method,
    .polycube_note). polycube_seconds: the polycube path's time budget (None: the core's default,
    5 s under "auto", no limit under "polycube"; 0: no limit; see _hexdom.mesh_surface); with
    "polycube", _hexdom.TimeoutError (an Error) when it passes before there is a mesh.
    max_size, min_size: bounds on the element size (None or 0: none; `hexdom mesh --max-size /
    --min-size`); cells_across: cells across a thin part (None: the core's 2); face_sizes:
    {patch id: size}, cell sizes on those patches (`hexdom mesh --face-size`; either path refines
    there, MeshRun.local_size_ratios says how near the sizes its cells are); growth_rate: how fast cells grow from those sizes back (None: the
    core's 3^(1/4); `hexdom mesh --growth-rate`); order: 1 or 2 (hex20 / wedge15 / tet10, the
    boundary's mid-edge nodes on the surface; `hexdom mesh --order`); time_limit: seconds the
    whole call may take (None: the core's MESH_OPTIONS["time_limit"]; 0: no limit; `hexdom mesh
    --time-limit`): past it
    _hexdom.TimeoutError (an Error) naming the step it was in. pillow_curves: the overlay path lays
    a sheet of wedges along each curve, every boundary face then on one face of the surface
    (`hexdom mesh --pillow-curves`). Raises
    MeshingError when inverted cells remain, unless allow_inverted (then MeshRun.inverted counts
    them). Returns a MeshRun. An Error raised carries ``run`` (a MeshRun of what the finished
    stages made, or None) and ``stage`` (the stage that failed)."""
    try:
        r = _hexdom.mesh_surface(surface.V, surface.F, surface.patch, float(size), int(level),
                                 float(edge_weight), int(max_relabels), int(relax_sweeps),
                                 bool(improve), bool(align),
                                 None if frame is None else np.asarray(frame, np.float64).reshape(3, 3),
                                 **_method_args(method, polycube_seconds),
                                 **_size_args(max_size=max_size, min_size=min_size,
                                              cells_across=cells_across, growth_rate=growth_rate),
                                 **_face_size_args(face_sizes), **_order_args(order), **_time_args(time_limit),
                                 pillow_curves=bool(pillow_curves))
    except Error as e:
        _attach_partial(e, _mesh_run)
        raise
    run = _mesh_run(r)
    if run.inverted and not allow_inverted:
        raise MeshingError(f"{run.inverted} inverted cells remain after improvement "
                           "(allow_inverted=True returns the mesh anyway)")
    return run


def mesh_part(source, size=MESH_OPTIONS["size"], level=MESH_OPTIONS["level"], solid=0,
              snap=MESH_OPTIONS["snap"], allow_inverted=False, **kwargs):
    """The CAD part's mesh as `hexdom mesh` makes it: a .step/.stp, .iges/.igs or .brep/.brp path or
    BREP text (FreeCAD: shape.exportBrepToString()) is tessellated with triangles of ``size`` (CAD
    faces kept for the segmentation), meshed (mesh_surface; keyword arguments edge_weight,
    max_relabels, relax_sweeps, improve, align, frame, method, polycube_seconds, max_size,
    min_size, cells_across, growth_rate, order (2: hex20 / wedge15 / tet10 with the boundary's
    mid-edge nodes on the B-rep), time_limit (seconds for the whole call), pillow_curves (the overlay
    path's wedges along the CAD edges: every boundary face on one CAD face, so that a face load in
    FreeCAD takes them all) go to it, and face_sizes, {FreeCAD face number of the
    source's shape: size}, cell sizes on those faces (`hexdom mesh --face-size`: either path), and edge_sizes
    likewise along edges (Edge<number>, `--edge-size`); the time
    budget covers every tessellation's polycube), and (``snap``) its boundary nodes
    are put exactly on the B-rep; when that tessellation's labelling defeats the automatic polycube
    or cells stay inverted, the B-rep is tessellated again with slightly smaller or larger triangles
    (``tessellations``, ``tessellation_factor`` of the MeshRun). Needs _hexdom built with
    OpenCASCADE. Raises MeshingError when inverted cells remain, unless allow_inverted. Returns a
    MeshRun whose seconds include "tessellate" and "snap", ``snap`` the snap report and
    ``surface`` the tessellation meshed. An Error raised carries ``run`` (a MeshRun of what the
    finished stages made, or None) and ``stage`` (the stage that failed).
    A source with several solids (a compound) has every solid meshed, solid k's cells in region k
    (``solid``: 1-based, one solid only), as `hexdom mesh`: ``surface`` and ``snap`` are then the
    whole part's, their face, edge and vertex numbers FreeCAD's for the whole shape, ``solids`` the
    count and ``touching`` the pairs of solids that touch (their meshes do not conform there)."""
    if not getattr(_hexdom, "has_opencascade", lambda: False)():
        raise Error("built without OpenCASCADE: cannot mesh a CAD part")
    unknown = set(kwargs) - {"edge_weight", "max_relabels", "relax_sweeps", "improve", "align", "frame",
                             "method", "polycube_seconds", "face_sizes", "edge_sizes", "order",
                             "time_limit", "pillow_curves"} - set(SIZE_BOUNDS)
    if unknown:
        raise TypeError("mesh_part() got unexpected keyword arguments: " + ", ".join(sorted(unknown)))
    text = os.fspath(source) if isinstance(source, os.PathLike) else source
    frame = kwargs.pop("frame", None)
    kwargs.update(_method_args(kwargs.pop("method", "auto"), kwargs.pop("polycube_seconds", None)))
    kwargs.update(_size_args(**{name: kwargs.pop(name, None) for name in SIZE_BOUNDS}))
    kwargs.update(_face_size_args(kwargs.pop("face_sizes", None)))
    kwargs.update(_face_size_args(kwargs.pop("edge_sizes", None), "edge_sizes", "edge"))
    kwargs.update(_order_args(kwargs.pop("order", 1)))
    kwargs.update(_time_args(kwargs.pop("time_limit", None)))
    kwargs["pillow_curves"] = bool(kwargs.pop("pillow_curves", MESH_OPTIONS["pillow_curves"]))
    try:
        r = _hexdom.mesh_cad(text, size=float(size), solid=int(solid), snap=bool(snap),
                             level=int(level),
                             frame=None if frame is None else np.asarray(frame, np.float64).reshape(3, 3),
                             **kwargs)
    except Error as e:
        _attach_partial(e, _cad_run)
        raise
    run = _cad_run(r)
    if run.inverted and not allow_inverted:
        raise MeshingError(f"{run.inverted} inverted cells remain after improvement "
                           "(allow_inverted=True returns the mesh anyway)")
    return run
