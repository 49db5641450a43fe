// The overlay path's core: the grid cells well inside the solid, made into a volume whose boundary
// is a 2-manifold quad surface, as a hex mesh.
#pragma once

#include <cstdint>
#include <vector>

#include "hexdom/mesh/closest_point.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/overlay/grid.h"

namespace hexdom::overlay {

struct Core {
  std::vector<char> keep;   ///< per grid cell
  int cells = 0;            ///< cells kept
  int dropped = 0;          ///< cells dropped to make the boundary manifold
  int components = 0;       ///< face-connected pieces of the cells inside; only the largest is kept
  int apart = 0;            ///< cells of the other pieces, dropped
  int parted = 0;           ///< cells dropped because they faced a kept neighbour across the surface
};

/// Whether two face-adjacent cells whose centres a and b lie inside the surface, at distances at
/// least da and db from it, face each other across a slot: the segment between the centres leaves
/// the solid and enters it again through walls facing each other (their normals more than 120
/// degrees apart: a slot, or the notch at a reflex curve sharper than 60 degrees, narrower than the
/// cells there); not across the void corner of a reflex curve of 90 degrees (a pocket's floor and
/// wall). Only when da + db is less than the segment's length can it leave; the triangles are
/// looked at only then.
bool across_surface(const Eigen::Vector3d& a, double da, const Eigen::Vector3d& b, double db,
                    const mesh::TriangleProjector& surface);

/// The cells whose eight corners are inside and at least `margin` from the surface (field from
/// classify_nodes with a band >= margin), made manifold (manifold_core).
Core core_cells(const Grid& grid, const NodeField& field, double margin);

/// The cells whose centre is inside and at least `margin` from the surface (`centres`: the field of
/// cell_centres(grid) from classify_nodes with a band >= margin), made manifold (manifold_core).
/// Such a core reaches up to the surface, and out of it by up to half a cell's diagonal less the
/// margin: its boundary nodes need moving in (pull_inner_nodes) before a buffer layer fits. Given
/// the surface (`surface`, and `band`: the distance below which `centres` holds every centre's
/// distance), of two kept cells facing each other across it (across_surface) the one nearer the
/// surface is dropped first, so that the core's boundary runs between them and the buffer layer
/// can reach into the notch.
Core core_cells_by_centres(const Grid& grid, const NodeField& centres, double margin,
                           const mesh::TriangleProjector* surface = nullptr, double band = 0);

/// The cells flagged in `keep`, less the cells that would make the boundary of their union other
/// than a 2-manifold: at every grid node, the kept and the empty cells around it must each be
/// face-connected among themselves; where they are not, the kept cell of least `safety` (its
/// distance inside the surface) there is dropped, and its corners checked again (each drop removes
/// a cell, so this ends). Of the face-connected pieces left, only the largest is kept.
Core manifold_core(const Grid& grid, std::vector<char> keep, const std::vector<double>& safety);

/// The kept cells as hexahedra (VTK order, region 1) over their own nodes; `grid_node` receives
/// each mesh node's grid node index.
mesh::Mesh core_mesh(const Grid& grid, const Core& core, std::vector<int64_t>* grid_node = nullptr);

/// manifold_core on an all-hex conforming mesh instead of a grid (octree_mesh's): the cells flagged
/// in `keep`, less those that would make the boundary of their union other than a 2-manifold. At
/// every node the kept cells around it and the empty ones must each be connected through the faces
/// they share; where not, the kept cell of least `safety` there is dropped and its nodes checked
/// again. Of the face-connected pieces left, only the largest is kept.
Core manifold_core(const mesh::Mesh& cells, std::vector<char> keep, const std::vector<double>& safety);

/// The kept cells of `cells` (region 1) over their own nodes.
mesh::Mesh core_mesh(const mesh::Mesh& cells, const Core& core);

}  // namespace hexdom::overlay
