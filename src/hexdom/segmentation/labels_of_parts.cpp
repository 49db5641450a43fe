#include "hexdom/segmentation/labels_of_parts.h"

#include <Eigen/Geometry>
#include <cstdio>
#include <map>
#include <string>

#include "hexdom/common/error.h"

#include "hexdom/segmentation/axis_labels.h"

namespace hexdom::segmentation {

Eigen::VectorXi labels_of_parts(const mesh::SurfaceMesh& s, bool* relabelled) {
  std::map<int, Eigen::Vector3d> normal;  // part id -> area-weighted normal (twice the area)
  std::map<int, double> area;             // part id -> twice its area
  std::map<int, int> count;
  for (int t = 0; t < s.F.rows(); ++t) {
    const Eigen::Vector3d a = s.V.row(s.F(t, 0)), b = s.V.row(s.F(t, 1)), c = s.V.row(s.F(t, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    auto [it, fresh] = normal.emplace(s.patch(t), Eigen::Vector3d::Zero());
    it->second += n;
    area[s.patch(t)] += n.norm();
    ++count[s.patch(t)];
  }
  bool are_labels = true;
  std::map<int, int> label;
  for (const auto& [id, n] : normal) {
    label[id] = nearest_label(n);
    if (id < 1 || id > 6 || label[id] != id) are_labels = false;
  }
  if (relabelled) *relabelled = !are_labels;
  if (are_labels) return s.patch;
  for (const auto& [id, n] : normal)
    if (!(n.norm() >= 0.5 * area[id])) {
      char ratio[32];
      std::snprintf(ratio, sizeof ratio, "%.2f", area[id] > 0 ? n.norm() / area[id] : 0.0);
      throw InputError("part " + std::to_string(id) + " (" + std::to_string(count[id]) +
                       " triangles) faces no one axis (its mean normal is " + ratio +
                       " long): the part ids are neither labels 1..6 nor patches of one orientation; "
                       "label the surface first (hexdom segment)");
    }
  Eigen::VectorXi out(s.patch.size());
  for (Eigen::Index t = 0; t < s.patch.size(); ++t) out(t) = label[s.patch(t)];
  return out;
}

Eigen::VectorXi labels_from_normals(const mesh::SurfaceMesh& s, const Eigen::Matrix3d& frame, bool per_part) {
  const TriangleGeometry g = triangle_geometry(s);
  const int nf = static_cast<int>(s.F.rows());
  Eigen::VectorXi out(nf);
  if (!per_part) {
    for (int t = 0; t < nf; ++t) out(t) = nearest_label(frame * g.normal.row(t).transpose());
    return out;
  }
  std::map<int, Eigen::Vector3d> normal;  // part id -> area-weighted normal
  for (int t = 0; t < nf; ++t) {
    auto [it, fresh] = normal.emplace(s.patch(t), Eigen::Vector3d::Zero());
    it->second += g.area(t) * g.normal.row(t).transpose();
  }
  std::map<int, int> label;
  for (const auto& [id, n] : normal) label[id] = nearest_label(frame * n);
  for (int t = 0; t < nf; ++t) out(t) = label[s.patch(t)];
  return out;
}

}  // namespace hexdom::segmentation
