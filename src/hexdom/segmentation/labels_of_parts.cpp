#include "hexdom/segmentation/labels_of_parts.h"

#include <Eigen/Geometry>
#include <map>

#include "hexdom/segmentation/axis_labels.h"

namespace hexdom::segmentation {

Eigen::VectorXi labels_of_parts(const mesh::SurfaceMesh& s, bool* relabelled) {
  std::map<int, Eigen::Vector3d> normal;  // part id -> area-weighted normal (twice the area)
  for (int t = 0; t < s.F.rows(); ++t) {
    const Eigen::Vector3d a = s.V.row(s.F(t, 0)), b = s.V.row(s.F(t, 1)), c = s.V.row(s.F(t, 2));
    auto [it, fresh] = normal.emplace(s.patch(t), Eigen::Vector3d::Zero());
    it->second += (b - a).cross(c - a);
  }
  bool are_labels = true;
  std::map<int, int> label;
  for (const auto& [id, n] : normal) {
    label[id] = nearest_label(n);
    if (id < 1 || id > 6 || label[id] != id) are_labels = false;
  }
  if (relabelled) *relabelled = !are_labels;
  if (are_labels) return s.patch;
  Eigen::VectorXi out(s.patch.size());
  for (Eigen::Index t = 0; t < s.patch.size(); ++t) out(t) = label[s.patch(t)];
  return out;
}

}  // namespace hexdom::segmentation
