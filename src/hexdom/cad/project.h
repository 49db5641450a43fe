// Nearest points on the B-rep: on one face, on one edge or on the whole boundary. Later stages use
// them to put final mesh boundary nodes exactly on the CAD faces.
#pragma once

#include <Eigen/Core>

#include "hexdom/cad/shape.h"

namespace hexdom::cad {

struct Projection {
  Eigen::MatrixXd points;    ///< #P by 3 nearest points
  Eigen::VectorXd distance;  ///< #P distances from the query points
  Eigen::MatrixXd param;     ///< #P by 2 surface (u, v) of the point; for edges (t, 0)
  Eigen::VectorXi id;        ///< #P 1-based face (or edge) id the point lies on
};

/// Nearest points of the face `face_id` (1-based, FreeCAD's Face{face_id}) to the rows of `P`
/// (#P by 3), respecting the face's trimming (its boundary). Throws InputError for an id out of range.
Projection project_to_face(const Shape& shape, int face_id, const Eigen::MatrixXd& P);

/// Nearest points of the edge `edge_id` (1-based, FreeCAD's Edge{edge_id}) to the rows of `P`.
Projection project_to_edge(const Shape& shape, int edge_id, const Eigen::MatrixXd& P);

/// Points along the edge `edge_id` (1-based, FreeCAD's Edge{edge_id}), from its first end to its
/// last, no two consecutive ones farther apart than about `spacing` (> 0) along it, at least 2,
/// at most 100,000. Throws InputError for an id out of range, GeometryError for a degenerated
/// edge (no 3D curve).
Eigen::MatrixXd edge_points(const Shape& shape, int edge_id, double spacing);

/// Nearest points of the whole boundary, with the id of the face each lies on.
Projection project_to_shape(const Shape& shape, const Eigen::MatrixXd& P);

}  // namespace hexdom::cad
