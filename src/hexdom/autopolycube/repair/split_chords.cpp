#include "hexdom/autopolycube/repair/split_chords.h"

#include <array>
#include <map>
#include <vector>

#include "hexdom/mesh/triangle_adjacency.h"

namespace hexdom::autopolycube {

mesh::SurfaceMesh split_chords(const mesh::SurfaceMesh& s, const ChartGraph& g, int* count) {
  const int nv = static_cast<int>(s.V.rows()), nf = static_cast<int>(s.F.rows());
  const Eigen::MatrixXi TT = mesh::triangle_adjacency(s.F);
  std::vector<char> boundary(nv, 0);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      if (g.region(TT(f, k)) != g.region(f)) boundary[s.F(f, k)] = boundary[s.F(f, (k + 1) % 3)] = 1;
  std::vector<Eigen::RowVector3d> extra;
  std::map<std::pair<int, int>, int> mid;
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = s.F(f, k), b = s.F(f, (k + 1) % 3);
      if (a > b || g.region(TT(f, k)) != g.region(f) || !boundary[a] || !boundary[b]) continue;
      mid[{a, b}] = nv + static_cast<int>(extra.size());
      extra.push_back(0.5 * (s.V.row(a) + s.V.row(b)));
    }
  if (count) *count = static_cast<int>(extra.size());
  if (extra.empty()) return s;
  auto midpoint = [&](int a, int b) {
    auto it = mid.find({std::min(a, b), std::max(a, b)});
    return it == mid.end() ? -1 : it->second;
  };
  std::vector<std::array<int, 3>> tris;
  std::vector<int> label;
  for (int f = 0; f < nf; ++f) {
    int v[3] = {s.F(f, 0), s.F(f, 1), s.F(f, 2)};
    int m[3];
    int n = 0;
    for (int k = 0; k < 3; ++k) n += (m[k] = midpoint(v[k], v[(k + 1) % 3])) >= 0;
    auto add = [&](int a, int b, int c) { tris.push_back({a, b, c}); label.push_back(s.patch(f)); };
    if (n == 0) { add(v[0], v[1], v[2]); continue; }
    if (n == 3) {
      add(v[0], m[0], m[2]); add(m[0], v[1], m[1]); add(m[2], m[1], v[2]); add(m[0], m[1], m[2]);
      continue;
    }
    // Rotate so that edge 0 (v0 v1) is split and, with two splits, edge 1 (v1 v2) too.
    int r = 0;
    if (n == 1) while (m[r] < 0) ++r;
    else while (!(m[r] >= 0 && m[(r + 1) % 3] >= 0)) ++r;
    const int a = v[r], b = v[(r + 1) % 3], c = v[(r + 2) % 3], mab = m[r], mbc = m[(r + 1) % 3];
    if (n == 1) { add(a, mab, c); add(mab, b, c); }
    else { add(mab, b, mbc); add(a, mab, mbc); add(a, mbc, c); }
  }
  mesh::SurfaceMesh out;
  out.V.resize(nv + static_cast<int>(extra.size()), 3);
  out.V.topRows(nv) = s.V;
  for (size_t i = 0; i < extra.size(); ++i) out.V.row(nv + i) = extra[i];
  out.F.resize(static_cast<int>(tris.size()), 3);
  out.patch.resize(static_cast<int>(tris.size()));
  for (size_t t = 0; t < tris.size(); ++t) {
    out.F.row(t) << tris[t][0], tris[t][1], tris[t][2];
    out.patch(t) = label[t];
  }
  return out;
}

}  // namespace hexdom::autopolycube
