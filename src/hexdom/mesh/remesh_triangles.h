// Isotropic remeshing of a closed triangle surface onto itself: the piecewise-linear surface is
// the geometry. Where FreeCAD's own mesher (or any other source) gives a closed triangulation with
// a face id per triangle but skinny triangles, this turns it into near-equilateral triangles of a
// target size without OpenCASCADE: the same remesher as cad::tessellate (mesh/remesh_surface.h),
// with vertices inside a face projected onto that face's input triangles, vertices on the curves
// where two face ids meet kept on those polylines, and corners (where three or more faces meet, or
// a curve ends) kept in place. The input's face ids carry over to the output triangles. Optionally
// sharp edges (dihedral angle) are curves too.
#pragma once

#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::mesh {

struct RemeshTrianglesOptions {
  double size = 0;      ///< target edge length; 0: the bounding-box diagonal / 30
  int iterations = 10;  ///< remeshing sweeps
  /// Degrees; > 0: an edge whose two triangles' normals differ by more than this is a curve too,
  /// and a curve turning by more than this at a vertex has a corner there (surfaces without face
  /// ids: STL, OBJ). 0: only the face ids make curves (a coarse tessellation of a smooth CAD face
  /// may have steep facets).
  double feature_angle = 0;
  LogCallback log;
};

/// Remeshes `surface` (V, F counter-clockwise seen from outside, patch = face id per triangle) to
/// edges of about `size`. Every output vertex lies on the input surface, on the input triangles of
/// its own face id; each output triangle keeps the face id of the region it covers. Vertices no
/// triangle uses (a .k file's spare nodes) are left out. Throws InputError for an open or non-manifold surface (naming the edge), a degenerate triangle
/// or a non-positive size.
SurfaceMesh remesh_triangles(const SurfaceMesh& surface, const RemeshTrianglesOptions& options = {});

}  // namespace hexdom::mesh
