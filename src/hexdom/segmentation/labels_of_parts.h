// Polycube labels from a segmented surface whose part ids may be labels or patch numbers.
#pragma once

#include <Eigen/Core>

#include "hexdom/mesh/mesh.h"

namespace hexdom::segmentation {

/// Label 1..6 (+X, -X, +Y, -Y, +Z, -Z) per triangle of `surface`, whose `patch` holds either
/// labels already (hexdom segment's output) or patch numbers (the paper's patch files, hand-edited
/// segmentations). The ids are taken as labels when all lie in 1..6 and each id's area-weighted
/// normal is nearest its own label's axis; otherwise every part (triangles of one id) gets the
/// label of the axis nearest its area-weighted normal. `relabelled` (optional) receives true when
/// the ids were not labels. Throws InputError naming a part whose triangles face no one axis (its
/// area-weighted normal shorter than half its area, e.g. a whole closed surface as one part): the
/// surface is then neither labelled nor segmented.
Eigen::VectorXi labels_of_parts(const mesh::SurfaceMesh& surface, bool* relabelled = nullptr);

/// Label 1..6 per triangle of `surface` from its normals turned into `frame` (x_frame = frame * x):
/// the axis nearest each triangle's normal, or, with `per_part`, the axis nearest the area-weighted
/// normal of the triangle's part (the triangles of its patch id), one label per part. Ties and zero
/// normals go to the lower label (nearest_label).
Eigen::VectorXi labels_from_normals(const mesh::SurfaceMesh& surface, const Eigen::Matrix3d& frame, bool per_part);

}  // namespace hexdom::segmentation
