#include "hexdom/overlay/local_size.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "hexdom/common/error.h"
#include "hexdom/common/format.h"

namespace hexdom::overlay {

namespace {
const double kSqrt3 = std::sqrt(3.0);
}  // namespace

void check_growth_rate(double growth) {
  if (!(growth > 1 && growth <= 3)) throw InputError(fmt("growth rate %g: it must be above 1 and at most 3", growth));
}

void check_local_sizes(const std::vector<LocalSize>& sizes, const mesh::SurfaceMesh& surface, const std::string& what) {
  int top = 0;
  for (int t = 0; t < surface.patch.size(); ++t) top = std::max(top, surface.patch(t));
  for (const LocalSize& l : sizes) {
    const std::string where = l.polyline.rows() > 0 ? std::string("an edge") : fmt("face %.0f", double(l.patch));
    if (!(l.size > 0) || !std::isfinite(l.size))
      throw InputError(fmt("local size %g on ", l.size) + where + ": a size must be positive");
    if (l.polyline.rows() > 0) {
      if (l.polyline.rows() < 2 || l.polyline.cols() != 3 || !l.polyline.allFinite())
        throw InputError("local size on an edge: its polyline needs 2 or more finite points (x, y, z)");
      continue;
    }
    bool found = false;
    for (int t = 0; t < surface.patch.size() && !found; ++t) found = surface.patch(t) == l.patch;
    if (!found)
      throw InputError("local size on " + where + ": " + what +
                       fmt(" has no such face (its faces are numbered 1 to %.0f)", double(top)));
  }
}

LocalLevels local_levels(double spacing, const std::vector<LocalSize>& sizes, double min_size, int max_levels) {
  LocalLevels out;
  if (sizes.empty() || !(spacing > 0)) return out;
  double smallest = sizes.front().size;
  for (const LocalSize& l : sizes) smallest = std::min(smallest, l.size);
  smallest = std::max(smallest, min_size);
  const double tol = 1.2;  // a level's cells within this factor of the smallest size
  if (smallest * tol >= spacing) return out;  // met by the grid's cells: no size is asked below them
  // Level L meets it with a spacing in [smallest 3^L / tol, smallest 3^L tol]: the spacing as it is
  // when it lies in one, otherwise the end nearest it (by ratio) that is at most tol times it.
  double best = 0;
  for (int level = 0; level <= max_levels; ++level) {
    const double lo = smallest * std::pow(3.0, level) / tol, hi = smallest * std::pow(3.0, level) * tol;
    if (lo <= spacing && spacing <= hi) return {1.0, level};
    for (double end : {lo, hi}) {
      if (end > spacing * tol) continue;
      const double off = std::abs(std::log(end / spacing));
      if (best == 0 || off < best) {
        best = off;
        out = {end / spacing, level};
      }
    }
  }
  return out;
}

LocalSizeField::LocalSizeField(const mesh::SurfaceMesh& surface, const std::vector<LocalSize>& sizes, double growth,
                               const Eigen::Matrix3d& transform) {
  check_growth_rate(growth);
  band_ = std::max(0.0, std::log(3.0) / std::log(growth) - 1);
  std::map<double, std::vector<int>> triangles;  // size -> triangles asking for it
  std::map<double, std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>> segments;
  for (const LocalSize& l : sizes) {
    if (l.polyline.rows() > 0) {
      const Eigen::MatrixXd P = l.polyline * transform;
      auto& list = segments[l.size];
      for (Eigen::Index i = 0; i + 1 < P.rows(); ++i) list.emplace_back(P.row(i).transpose(), P.row(i + 1).transpose());
      continue;
    }
    for (int t = 0; t < surface.F.rows(); ++t)
      if (surface.patch(t) == l.patch) triangles[l.size].push_back(t);
  }
  std::map<double, Sized> all;
  for (auto& [size, ts] : triangles) {
    std::sort(ts.begin(), ts.end());
    ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
    Eigen::MatrixXi F(static_cast<int>(ts.size()), 3);
    for (size_t i = 0; i < ts.size(); ++i) F.row(static_cast<int>(i)) = surface.F.row(ts[i]);
    all[size].triangles = mesh::TriangleProjector(surface.V, F);
  }
  for (auto& [size, list] : segments) all[size].segments = std::move(list);
  for (auto& [size, sized] : all) {
    sized.size = size;
    by_size_.push_back(std::move(sized));
  }
}

bool LocalSizeField::split(const Eigen::Vector3d& lo, const Eigen::Vector3d& size, double real_side) const {
  const Eigen::Vector3d centre = lo + size / 2;
  const double reach = size.norm() / 2 + band_ * size.maxCoeff() / 3;
  for (const Sized& s : by_size_) {
    if (real_side <= s.size * kSqrt3 * (1 + 1e-9)) return false;  // this size and the larger ones are met
    if (!s.triangles.empty() && (s.triangles.project(centre) - centre).norm() <= reach) return true;
    for (const auto& [a, b] : s.segments)
      if ((mesh::closest_point_on_segment(centre, a, b) - centre).norm() <= reach) return true;
  }
  return false;
}

}  // namespace hexdom::overlay
