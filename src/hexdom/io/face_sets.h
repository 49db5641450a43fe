// Boundary faces named for the solvers' loads and supports: each tagged with the CAD face it lies
// on, the writers name the sets as FreeCAD names faces (Face1, Face2, ...).
#pragma once

#include <map>
#include <vector>

#include "hexdom/mesh/cell_faces.h"

namespace hexdom::io {

struct FaceSets {
  std::vector<mesh::BoundaryFace> faces;  ///< boundary faces of the mesh written
  std::vector<int> tag;                   ///< per face: its CAD face id (>= 1), or < 1 for none
  bool empty() const { return faces.empty(); }
  /// The faces (indices into `faces`) of each tag >= 1, by increasing tag.
  std::map<int, std::vector<size_t>> by_tag() const;
};

/// The boundary faces of `mesh` (mesh::boundary_faces), each tagged with the patch (CAD face id) of
/// the triangle of `surface` nearest its centre: for a mesh made from a tessellation with CAD face
/// ids, the CAD face it lies on (a face the overlay lets straddle a sharp curve gets the face of its
/// centre). Empty when `surface` has no triangles.
FaceSets face_sets(const mesh::Mesh& mesh, const mesh::SurfaceMesh& surface);

}  // namespace hexdom::io
