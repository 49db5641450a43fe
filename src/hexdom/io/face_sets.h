// Boundary faces named for the solvers' loads and supports: each tagged with the CAD face it lies
// on, the writers name the sets as FreeCAD names faces (Face1, Face2, ...).
#pragma once

#include <vector>

#include "hexdom/mesh/cell_faces.h"

namespace hexdom::io {

struct FaceSets {
  std::vector<mesh::BoundaryFace> faces;  ///< boundary faces of the mesh written
  std::vector<int> tag;                   ///< per face: its CAD face id (>= 1), or < 1 for none
  bool empty() const { return faces.empty(); }
};

}  // namespace hexdom::io
