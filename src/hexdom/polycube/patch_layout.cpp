#include "hexdom/polycube/patch_layout.h"

#include <algorithm>
#include <map>
#include <set>
#include <unordered_map>

#include "hexdom/common/error.h"

namespace hexdom::polycube {

namespace {

using EdgeKey = long long;
EdgeKey key(int a, int b) { return (static_cast<EdgeKey>(std::min(a, b)) << 32) | std::max(a, b); }

}  // namespace

void check_closed_manifold(const mesh::SurfaceMesh& s) {
  const int nf = static_cast<int>(s.F.rows());
  if (nf == 0) throw GeometryError("the surface has no triangles");
  std::unordered_map<EdgeKey, int> count;
  count.reserve(3 * nf);
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      int a = s.F(f, k), b = s.F(f, (k + 1) % 3);
      if (a < 0 || a >= s.V.rows()) throw GeometryError("triangle " + std::to_string(f + 1) + " refers to a missing vertex");
      if (a == b) throw GeometryError("triangle " + std::to_string(f + 1) + " is degenerate (repeats vertex " + std::to_string(a + 1) + ")");
      count[key(a, b)]++;
    }
  }
  for (const auto& [k, c] : count) {
    if (c != 2) {
      int a = static_cast<int>(k >> 32), b = static_cast<int>(k & 0xffffffff);
      throw GeometryError(std::string(c == 1 ? "open surface: boundary" : "non-manifold") + " edge (" +
                          std::to_string(a + 1) + ", " + std::to_string(b + 1) + ") is shared by " +
                          std::to_string(c) + " triangle" + (c == 1 ? "" : "s") + " (a closed surface needs 2)");
    }
  }
  // With two triangles per edge, a directed edge used twice means the two disagree on orientation.
  std::unordered_map<EdgeKey, int> directed;
  directed.reserve(3 * nf);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      int a = s.F(f, k), b = s.F(f, (k + 1) % 3);
      if (++directed[(static_cast<EdgeKey>(a) << 32) | b] > 1)
        throw GeometryError("triangles next to edge (" + std::to_string(a + 1) + ", " + std::to_string(b + 1) +
                            ") are inconsistently oriented (triangle " + std::to_string(f + 1) + ")");
    }
}

PatchLayout patch_layout(const mesh::SurfaceMesh& s) {
  const int nf = static_cast<int>(s.F.rows()), nv = static_cast<int>(s.V.rows());
  PatchLayout out;
  // Triangle adjacency through edges.
  std::unordered_map<EdgeKey, std::pair<int, int>> edge_tris;
  edge_tris.reserve(3 * nf);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      auto& e = edge_tris.try_emplace(key(s.F(f, k), s.F(f, (k + 1) % 3)), -1, -1).first->second;
      (e.first < 0 ? e.first : e.second) = f;
    }
  auto neighbour = [&](int f, int k) {
    const auto& e = edge_tris.at(key(s.F(f, k), s.F(f, (k + 1) % 3)));
    return e.first == f ? e.second : e.first;
  };
  // Regions by flood fill.
  out.region = Eigen::VectorXi::Constant(nf, -1);
  for (int f0 = 0; f0 < nf; ++f0) {
    if (out.region(f0) >= 0) continue;
    const int r = static_cast<int>(out.patches.size());
    Patch p;
    p.label = s.patch(f0);
    std::vector<int> stack{f0};
    out.region(f0) = r;
    while (!stack.empty()) {
      int f = stack.back();
      stack.pop_back();
      p.triangles.push_back(f);
      for (int k = 0; k < 3; ++k) {
        int g = neighbour(f, k);
        if (g >= 0 && out.region(g) < 0 && s.patch(g) == p.label) {
          out.region(g) = r;
          stack.push_back(g);
        }
      }
    }
    out.patches.push_back(std::move(p));
  }
  // Corners: vertices touching 3 or more regions.
  std::vector<std::vector<int>> vregions(nv);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      auto& v = vregions[s.F(f, k)];
      if (std::find(v.begin(), v.end(), out.region(f)) == v.end()) v.push_back(out.region(f));
    }
  out.corner_of = Eigen::VectorXi::Constant(nv, -1);
  for (int v = 0; v < nv; ++v)
    if (vregions[v].size() >= 3) {
      out.corner_of(v) = static_cast<int>(out.corners.size());
      out.corners.push_back(v);
    }
  // Boundary loops: directed edges a->b of the patch's triangles whose other side is another region.
  for (auto& p : out.patches) {
    std::unordered_map<int, std::vector<int>> next;
    int nedges = 0;
    for (int f : p.triangles)
      for (int k = 0; k < 3; ++k) {
        int g = neighbour(f, k);
        if (g < 0 || out.region(g) != out.region(f)) {
          next[s.F(f, k)].push_back(s.F(f, (k + 1) % 3));
          ++nedges;
        }
      }
    if (nedges == 0) continue;
    std::set<std::pair<int, int>> used;
    int walked = 0;
    while (walked < nedges) {
      // Start a loop at an unused edge, preferably from a corner.
      int start = -1;
      for (const auto& [a, bs] : next)
        for (int b : bs)
          if (!used.count({a, b}) && (start < 0 || out.corner_of(a) >= 0)) start = a;
      if (start < 0) break;
      std::vector<int> loop;
      int a = start;
      do {
        int b = -1;
        for (int c : next[a])
          if (!used.count({a, c})) { b = c; break; }
        if (b < 0) break;
        used.insert({a, b});
        loop.push_back(a);
        ++walked;
        a = b;
      } while (a != start);
      p.num_loops++;
      if (p.num_loops == 1) p.loop = loop;
    }
    for (int i = 0; i < static_cast<int>(p.loop.size()); ++i)
      if (out.corner_of(p.loop[i]) >= 0) p.corners.push_back(i);
  }
  return out;
}

}  // namespace hexdom::polycube
