#include "hexdom/autopolycube/repair/cut_triangles.h"

#include <algorithm>
#include <cmath>

namespace hexdom::autopolycube {

std::vector<std::array<int, 4>> cut_triangles(const Eigen::MatrixXi& F, const std::vector<int>& tris, std::map<int, double>& f, double eps,
                                              int nv, std::vector<Eigen::RowVector3d>& extra,
                                              const std::function<Eigen::RowVector3d(int)>& pos) {
  for (auto& [v, x] : f)
    if (std::abs(x) < eps) x = 0;
  std::map<std::pair<int, int>, int> cut;
  auto mid = [&](int u, int w) {
    const std::pair<int, int> key{std::min(u, w), std::max(u, w)};
    auto it = cut.find(key);
    if (it != cut.end()) return it->second;
    const double x = f.at(u) / (f.at(u) - f.at(w));
    const int id = nv + static_cast<int>(extra.size());
    extra.push_back(pos(u) + x * (pos(w) - pos(u)));
    f[id] = 0;
    cut.emplace(key, id);
    return id;
  };
  std::vector<std::array<int, 4>> out;
  for (int t : tris) {
    std::array<int, 3> v{F(t, 0), F(t, 1), F(t, 2)};
    bool above = false, below = false;
    for (int k = 0; k < 3; ++k) { above = above || f.at(v[k]) > 0; below = below || f.at(v[k]) < 0; }
    if (!(above && below)) { out.push_back({v[0], v[1], v[2], t}); continue; }
    int z = -1;
    for (int k = 0; k < 3; ++k)
      if (f.at(v[k]) == 0) z = k;
    if (z >= 0) {
      // One vertex on the level, the others on either side.
      const int x = v[z], y = v[(z + 1) % 3], w = v[(z + 2) % 3], m = mid(y, w);
      out.push_back({x, y, m, t});
      out.push_back({x, m, w, t});
      continue;
    }
    // The vertex alone on its side first.
    int k0 = 0;
    for (int k = 0; k < 3; ++k)
      if ((f.at(v[k]) > 0) != (f.at(v[(k + 1) % 3]) > 0) && (f.at(v[k]) > 0) != (f.at(v[(k + 2) % 3]) > 0)) k0 = k;
    const int x = v[k0], y = v[(k0 + 1) % 3], w = v[(k0 + 2) % 3];
    const int m1 = mid(x, y), m2 = mid(w, x);
    out.push_back({x, m1, m2, t});
    out.push_back({m1, y, w, t});
    out.push_back({m1, w, m2, t});
  }
  return out;
}

}  // namespace hexdom::autopolycube
