#include "hexdom/overlay/features.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>

#include "hexdom/common/disjoint_sets.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/triangle_adjacency.h"

namespace hexdom::overlay {

SurfaceFeatures::SurfaceFeatures(const mesh::SurfaceMesh& s, const FeatureOptions& opt) : all_(s.V, s.F) {
  const int nf = static_cast<int>(s.F.rows()), nv = static_cast<int>(s.V.rows());
  const Eigen::MatrixXi TT = mesh::triangle_adjacency(s.F);
  std::vector<Eigen::Vector3d> normal(nf);
  for (int f = 0; f < nf; ++f) {
    const Eigen::Vector3d A = s.V.row(s.F(f, 0)), B = s.V.row(s.F(f, 1)), C = s.V.row(s.F(f, 2));
    normal[f] = (B - A).cross(C - A).normalized();
  }
  normal_ = normal;
  const double cos_across = std::cos(opt.angle_across * M_PI / 180), cos_within = std::cos(opt.angle_within * M_PI / 180);
  DisjointSets joined(nf);  // triangles joined across edges that are no curve
  const bool given = !opt.regions.empty();
  if (given && static_cast<int>(opt.regions.size()) != nf)
    throw GeometryError("features: " + std::to_string(opt.regions.size()) + " regions given for " + std::to_string(nf) + " triangles");
  const bool patches = s.patch.size() == nf;
  // With patch_edges: the pairs of patches that meet along a sharp edge somewhere. Their smooth
  // edges stay joined (a curve that turns tangent on its way, as where two crossing cylinders touch:
  // capturing its tangent stretch flattens cells); the edges of the other pairs are curves.
  std::set<std::pair<int, int>> sharp_pairs;
  auto pair_of = [&](int f, int g) { return std::minmax(s.patch(f), s.patch(g)); };
  if (!given && patches && opt.patch_edges)
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const int g = TT(f, k);
        if (g > f && s.patch(f) != s.patch(g) && normal[f].dot(normal[g]) < cos_across) sharp_pairs.insert(pair_of(f, g));
      }
  std::vector<std::array<int, 4>> sharp;  // vertex a, vertex b, triangle f, triangle g
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int g = TT(f, k);
      if (g <= f) continue;
      const bool same_patch = patches && s.patch(f) == s.patch(g);
      const double c = normal[f].dot(normal[g]);
      const bool curve = given        ? opt.regions[f] != opt.regions[g]
                         : same_patch ? c < cos_within
                                      : c < cos_across || (opt.patch_edges && patches && !sharp_pairs.count(pair_of(f, g)));
      if (curve)
        sharp.push_back({s.F(f, k), s.F(f, (k + 1) % 3), f, g});
      else
        joined.unite(f, g);
    }
  std::vector<int> id(nf, -1);
  region_.resize(nf);
  for (int f = 0; f < nf; ++f) {
    const int r = joined.find(f);
    if (id[r] < 0) id[r] = regions_++;
    region_[f] = id[r];
  }
  // Vertices: regions around and sharp edges between two regions.
  std::vector<std::set<int>> around(nv);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) around[s.F(f, k)].insert(region_[f]);
  std::vector<int> degree(nv, 0);
  std::map<std::pair<int, int>, std::vector<std::array<int, 2>>> segments;
  for (const auto& e : sharp) {
    int a = region_[e[2]], b = region_[e[3]];
    if (a == b) continue;  // a crease inside a region, not captured
    if (a > b) std::swap(a, b);
    ++degree[e[0]];
    ++degree[e[1]];
    segments[{a, b}].push_back({e[0], e[1]});
  }
  for (int v = 0; v < nv; ++v)
    if (around[v].size() >= 3 || (degree[v] != 0 && degree[v] != 2)) {
      corners_.push_back(v);
      corner_regions_.emplace_back(around[v].begin(), around[v].end());
      corner_position_.push_back(s.V.row(v).transpose());
    }
  for (auto& [key, segs] : segments)
    curves_[key] = std::make_unique<mesh::TriangleProjector>(mesh::segment_projector(s.V, segs));
  std::vector<std::vector<int>> tris(regions_);
  for (int f = 0; f < nf; ++f) tris[region_[f]].push_back(f);
  for (int r = 0; r < regions_; ++r) {
    Eigen::MatrixXi F(static_cast<int>(tris[r].size()), 3);
    for (size_t i = 0; i < tris[r].size(); ++i) F.row(static_cast<int>(i)) = s.F.row(tris[r][i]);
    by_region_.push_back(std::make_unique<mesh::TriangleProjector>(s.V, F));
  }
}

bool SurfaceFeatures::has_curve(int a, int b) const {
  if (a > b) std::swap(a, b);
  return curves_.count({a, b}) > 0;
}

Eigen::Vector3d SurfaceFeatures::project(const Eigen::Vector3d& p, int* region, Eigen::Vector3d* normal) const {
  int t = -1;
  const Eigen::Vector3d q = all_.project(p, &t);
  if (region) *region = t >= 0 ? region_[t] : -1;
  if (normal) *normal = t >= 0 ? normal_[t] : Eigen::Vector3d::Zero();
  return q;
}

Eigen::Vector3d SurfaceFeatures::project_region(int r, const Eigen::Vector3d& p, int* hint) const {
  return by_region_[r]->project(p, hint, hint ? *hint : -1);
}

Eigen::Vector3d SurfaceFeatures::project_curve(int a, int b, const Eigen::Vector3d& p, int* hint) const {
  if (a > b) std::swap(a, b);
  return curves_.at({a, b})->project(p, hint, hint ? *hint : -1);
}

}  // namespace hexdom::overlay
