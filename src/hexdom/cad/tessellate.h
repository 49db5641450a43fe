// Tessellation of a B-rep solid into a closed triangle surface that keeps CAD face ids, made for
// harmonic parameterisation: near-isotropic triangles of a prescribed size instead of the long
// skinny ones BRepMesh makes.
//
// Method: BRepMesh_IncrementalMesh with a small deflection gives a watertight start (every CAD edge
// is discretised once and shared by its two faces); its nodes are merged through the B-rep topology
// (seams and degenerated edges such as sphere poles collapse into one vertex). Then an isotropic
// remeshing (split, collapse, flip, tangential relaxation, after Botsch and Kobbelt 2004) runs on the
// whole surface: vertices inside a face are projected onto that face's surface, vertices on a CAD
// edge slide along its 3D curve and CAD vertices stay fixed, so CAD edges stay mesh edges and the
// surface stays closed. Target edge lengths come from `size`, reduced where the curvature needs it
// (`deflection`, `angle`) and near short edges and thin faces, then graded.
//
// Repairs instead of refusals (cad/tessellate_merge.h): a face that BRepMesh leaves without
// triangles, or with triangles that do not fit its edges' nodes (an edge without nodes, an edge
// discretised differently in its two faces, folded triangles), is triangulated by hexdom in the
// face's (u, v) parameters from the nodes of its edges (cad/face_triangulation.h: a bad pcurve is
// replaced by projecting the edge's nodes, a periodic face without a seam edge gets one); faces that
// the B-rep's shell turns against their neighbours are turned back. Each repair is logged as a
// warning naming the face.
#pragma once

#include "hexdom/cad/shape.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::cad {

struct TessellateOptions {
  /// Target edge length; 0 means the bounding-box diagonal / 30, the box square to the frame the
  /// faces fit (segmentation::cube_frame) when `size_in_frame` and that frame is turned: a part lying
  /// at an angle gets the size it would get square to the axes.
  double size = 0;
  bool size_in_frame = true;
  /// Largest distance between a triangle and the surface it approximates (limits the edge length
  /// on curved faces to about sqrt(8 R deflection)); 0 means size / 50.
  double deflection = 0;
  /// Largest angle in degrees that an edge may turn on a curved face or edge (edge length <= R angle).
  double angle = 30;
  /// Smallest target edge length (short CAD edges still give shorter ones); 0 means size / 20.
  double min_size = 0;
  /// Remeshing sweeps (split, collapse, flip, relax); 0 keeps BRepMesh's triangles as they are.
  int iterations = 10;
  /// Start from BRepMesh's triangles of each face where they are usable (the default); false
  /// triangulates every face by hexdom's own triangulation, as for the faces BRepMesh fails on
  /// (for tests and comparisons).
  bool brepmesh_faces = true;
  LogCallback log;
};

/// Figures about a tessellation, for reports and tests.
struct TessellateStats {
  int triangles = 0, vertices = 0, faces = 0;
  double min_angle = 0;          ///< smallest triangle angle in degrees, all faces
  double min_angle_planar = 0;   ///< same on planar faces only (180 when there are none)
  double mean_edge = 0, min_edge = 0, max_edge = 0;
  double size = 0;               ///< the target size used (after defaults)
  bool closed = false;           ///< closed and 2-manifold, consistently oriented
  double volume = 0;             ///< volume enclosed by the triangles
  double brep_volume = 0;        ///< volume of the solid (OCCT GProp)
  double seconds = 0;
  long splits = 0;               ///< edges the remesher split (see mesh::remesh::SurfaceRemesher::splits)
};

/// Triangulates the boundary of `shape` (a solid). The result is closed, 2-manifold and oriented
/// outward (counter-clockwise seen from outside); every vertex lies on the B-rep; patch(i) is the
/// 1-based id of the CAD face triangle i lies on (FreeCAD's Face{patch}). Faces whose BRepMesh
/// triangles are missing or unusable are triangulated by hexdom, faces turned against their shell
/// are turned back (both logged as warnings). Throws GeometryError for an empty shape or one that is
/// not a closed solid; MeshingError "source: FaceN cannot be triangulated: <reason>" when neither
/// BRepMesh nor hexdom can triangulate a face (a wire off its surface, wires that cross in its
/// parameters, a wire whose edges do not join), and MeshingError naming a face when the result would
/// not be closed.
mesh::SurfaceMesh tessellate(const Shape& shape, const TessellateOptions& options = {},
                             TessellateStats* stats = nullptr);

/// Computes the figures of TessellateStats for `surface` (a tessellation of `shape`).
TessellateStats tessellation_stats(const Shape& shape, const mesh::SurfaceMesh& surface);

}  // namespace hexdom::cad
