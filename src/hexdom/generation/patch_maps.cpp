#include "hexdom/generation/patch_maps.h"

#include <algorithm>
#include <cmath>

#include "hexdom/common/parallel_for.h"

namespace hexdom::generation {

Vec3 Curve::at(double t) const {
  const double target = t * s.back();
  auto it = std::upper_bound(s.begin(), s.end(), target);
  size_t i = it == s.begin() ? 0 : static_cast<size_t>(it - s.begin()) - 1;
  if (i + 1 >= p.size()) return p.back();
  const double len = s[i + 1] - s[i];
  const double a = len > 0 ? (target - s[i]) / len : 0.0;
  return (1 - a) * p[i] + a * p[i + 1];
}

namespace {

// The point-location grid of a mapped patch: about two triangles per cell.
void build_grid(PatchMap& pm) {
  pm.g = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(pm.tris.size()) / 2.0)));
  pm.cells.assign(pm.g * pm.g, {});
  pm.all.resize(pm.tris.size());
  for (size_t t = 0; t < pm.tris.size(); ++t) pm.all[t] = static_cast<int>(t);
  for (int t : pm.all) {
    double lo[2] = {1e30, 1e30}, hi[2] = {-1e30, -1e30};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 2; ++d) {
        lo[d] = std::min(lo[d], pm.uv(pm.F(t, k), d));
        hi[d] = std::max(hi[d], pm.uv(pm.F(t, k), d));
      }
    auto cell = [&](double x) { return std::max(0, std::min(pm.g - 1, static_cast<int>(std::floor(x * pm.g)))); };
    for (int y = cell(lo[1] - 1e-9); y <= cell(hi[1] + 1e-9); ++y)
      for (int x = cell(lo[0] - 1e-9); x <= cell(hi[0] + 1e-9); ++x) pm.cells[y * pm.g + x].push_back(t);
  }
}

}  // namespace

Vec3 evaluate(const PatchMap& pm, const mesh::SurfaceMesh& S, double u, double v) {
  auto cell = [&](double x) { return std::max(0, std::min(pm.g - 1, static_cast<int>(std::floor(x * pm.g)))); };
  double best = -1e30;
  Vec3 result = Vec3::Zero();
  auto try_tris = [&](const std::vector<int>& list) {
    for (int t : list) {
      const int a = pm.F(t, 0), b = pm.F(t, 1), c = pm.F(t, 2);
      const double x0 = pm.uv(a, 0), y0 = pm.uv(a, 1);
      const double d = (pm.uv(b, 0) - x0) * (pm.uv(c, 1) - y0) - (pm.uv(c, 0) - x0) * (pm.uv(b, 1) - y0);
      if (d == 0) continue;
      const double l1 = ((u - x0) * (pm.uv(c, 1) - y0) - (pm.uv(c, 0) - x0) * (v - y0)) / d;
      const double l2 = ((pm.uv(b, 0) - x0) * (v - y0) - (u - x0) * (pm.uv(b, 1) - y0)) / d;
      const double l0 = 1 - l1 - l2;
      const double m = std::min({l0, l1, l2});
      if (m > best) {
        best = m;
        double c0 = std::max(0.0, l0), c1 = std::max(0.0, l1), c2 = std::max(0.0, l2);
        const double sum = c0 + c1 + c2;
        result = (c0 * S.V.row(pm.vertex[a]) + c1 * S.V.row(pm.vertex[b]) + c2 * S.V.row(pm.vertex[c])).transpose() / sum;
      }
    }
  };
  try_tris(pm.cells[cell(v) * pm.g + cell(u)]);
  if (best < -1e-9) try_tris(pm.all);  // outside every candidate: search the whole patch
  return result;
}

Eigen::Vector2d domain_corner(int nface, int i) {
  static const double q[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  static const double t[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  return nface == 4 ? Eigen::Vector2d(q[i][0], q[i][1]) : Eigen::Vector2d(t[i][0], t[i][1]);
}

void solve_patch_maps(std::vector<MapJob>& jobs, std::vector<PatchMap>& maps, int threads) {
  // The maps are independent; each job writes only its own PatchMap.
  std::vector<int> order(jobs.size());
  for (size_t j = 0; j < jobs.size(); ++j) order[j] = static_cast<int>(j);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return jobs[a].V.rows() > jobs[b].V.rows(); });
  parallel_for(static_cast<int>(order.size()), threads, [&](int q) {
    MapJob& job = jobs[order[q]];
    try {
      job.result = parametrization::harmonic_map(job.V, maps[job.patch].F, job.bnd, job.bc);
      if (job.result.flipped == 0) {
        PatchMap& pm = maps[job.patch];
        pm.uv = std::move(job.result.uv);
        build_grid(pm);
      }
    } catch (...) {
      job.error = std::current_exception();
    }
  });
}

}  // namespace hexdom::generation
