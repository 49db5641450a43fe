// Editing a patch map (a patch id per triangle; a patch is a connected region of one id), as the
// paper did by hand in LS-PrePost: reassign triangles, merge two patches, split one along a path.
// Each operation returns the new map and leaves the surface alone; `hexdom check` / check_patches
// tells whether the result still satisfies the polycube conditions.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::segmentation {

/// One id per connected region, 1..R in the order of each region's first triangle (the patch
/// numbers of check_patches and the shell ids of the polycube). Turns a labelling (ids 1..6 shared
/// by many regions) into a patch map whose ids name single patches.
Eigen::VectorXi number_patches(const mesh::SurfaceMesh& surface);

/// `triangles` (0-based) take patch id `id`; id <= 0 gives them a new id, one more than the
/// largest. Throws InputError for a triangle out of range.
Eigen::VectorXi reassign_triangles(const mesh::SurfaceMesh& surface, const std::vector<int>& triangles, int id);

/// The triangles of patch id `b` take id `a`. Throws InputError when an id is not in the map or
/// a == b, GeometryError when the two patches share no edge.
Eigen::VectorXi merge_patches(const mesh::SurfaceMesh& surface, int a, int b);

/// Splits patch id `id` along a path of vertices (0-based). Consecutive path vertices are joined
/// by the shortest chain of the patch's interior edges, so two clicks on its boundary make a cut
/// across it; the path may also close on itself inside the patch. Of each region of the id that
/// the cut separates, the part holding the region's first triangle keeps the id and every other
/// part gets a new id (largest + 1, + 2, ...). Throws InputError for an unknown id, a vertex out
/// of range or a path of fewer than 2 vertices, GeometryError when a path vertex is not on the
/// patch, two consecutive vertices cannot be joined inside it, or the cut separates nothing.
Eigen::VectorXi split_patch(const mesh::SurfaceMesh& surface, int id, const std::vector<int>& path);

}  // namespace hexdom::segmentation
