// The start of cad::tessellate: the faces' triangulations joined into one closed surface through the
// B-rep's topology. Internal to hexdom_cad: only cad/*.cpp include it.
//
// Contract: the result is closed, 2-manifold and consistently oriented, every triangle tagged with
// its face. BRepMesh's triangulation of a face is taken as it is when it is a proper patch (every
// edge of the face has its nodes, an edge shared with a face read before has as many, no triangle
// folds over another, the patch's border is exactly its edges' segments); a face for which BRepMesh
// gave none or a bad one is triangulated here instead (cad/face_triangulation.h) from the nodes of
// its edges, so both faces of an edge use the edge's one polygon. Faces whose triangles run against
// their neighbours' (a face turned over in the B-rep's shell) are turned to agree with the majority
// of their shell. What cannot be repaired throws MeshingError naming the face and the reason.
#pragma once

#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Shape.hxx>

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "hexdom/cad/tessellate.h"
#include "hexdom/mesh/remesh_surface.h"

namespace hexdom::cad {

/// The sizes a tessellation works with: the options' with their defaults filled in.
struct Sizes {
  double size = 0, deflection = 0, min_size = 0;
  double angle = 0;  ///< radians
};

/// The copy of the solid that BRepMesh triangulates, with its faces, edges and vertices numbered.
struct WorkShape {
  TopoDS_Shape shape;
  TopTools_IndexedMapOfShape faces, edges, vertices;
  std::vector<int> original_face;  ///< per face of the copy (0-based): the original's id (FreeCAD's FaceN)
  std::string source;              ///< for messages
  std::string face_name(int fi) const { return "Face" + std::to_string(original_face[fi]); }
};

/// The face triangulations merged into one surface for the remesher.
struct Merged {
  std::vector<mesh::remesh::RVertex> V;
  std::vector<std::vector<int>> edge_nodes;      ///< per edge: its vertices in V, first to last
  std::vector<std::vector<double>> edge_params;  ///< per edge: their parameters on the edge's curve
  std::vector<std::array<int, 3>> F;
  std::vector<int> face_of;  ///< per triangle: its face of the copy (0-based)
  int dropped = 0;           ///< degenerate triangles left out
  std::vector<std::string> repairs;  ///< what was repaired, one line each (logged as warnings)
};

/// Merges the faces' triangulations (BRepMesh's, or this stage's own where BRepMesh's is missing
/// or bad) into one closed, consistently oriented surface. Throws MeshingError naming the face and
/// the reason when no closed surface can be made.
Merged merge_triangulations(const WorkShape& w, const Sizes& z, const TessellateOptions& options);

/// "" when every edge is used by exactly two triangles in opposite directions, else a description;
/// `triangle` (when given) is set to a triangle at the problem (0-based), -1 when there is none.
std::string closed_manifold_problem(const Eigen::MatrixXi& F, int* triangle = nullptr);

}  // namespace hexdom::cad
