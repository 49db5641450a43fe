// Triangulation of a plane polygon with holes by ear clipping, for a CAD face whose own
// triangulation failed: its boundary nodes in the face's (u, v) parameters become triangles that
// use exactly those nodes and the boundary segments between them, so that the face still meets
// its neighbours' triangles along the shared edge nodes. No new points are made; refining the
// triangles is up to the caller.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace hexdom::mesh {

/// Triangulates the region bounded by `loops` (each a closed polygon, its last point joined to its
/// first; the loop of largest area is the outer one, the others are holes inside it; each loop may
/// run either way). Points are numbered through the loops in order (loop 0's first, ..., loop 1's
/// first, ...). The result's triangles are counter-clockwise in the plane and cover the region
/// exactly: every boundary segment is used by one triangle, every other triangle edge by two.
/// Returns an empty list and sets `why` (when given) for input it cannot triangulate: fewer than
/// three points, a loop without area, or loops that cross or touch each other or themselves.
std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<std::vector<Eigen::Vector2d>>& loops,
                                                    std::string* why = nullptr);

/// True when some two segments of `loops` (closed polygons) cross or touch other than at the point
/// that two consecutive segments of one loop share; `where`, when given, names the first pair.
bool loops_intersect(const std::vector<std::vector<Eigen::Vector2d>>& loops, std::string* where = nullptr);

}  // namespace hexdom::mesh
