#include "hexdom/autopolycube/blocks/apex_blocks.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

#include "hexdom/autopolycube/blocks/collapse_slivers.h"
#include "hexdom/autopolycube/repair/cut_triangles.h"
#include "hexdom/common/format.h"
#include "hexdom/polycube/match_faces.h"
#include "hexdom/polycube/patch_layout.h"
#include "hexdom/quality/metrics.h"
#include "hexdom/segmentation/axis_labels.h"

namespace hexdom::autopolycube {

namespace {

using GP = std::array<int, 3>;
using Cell = std::pair<mesh::CellType, std::array<int, 8>>;

double cell_quality(const Cell& c, const Eigen::MatrixXd& X) {
  quality::CellPoints cp = quality::CellPoints::Zero();
  for (int i = 0; i < mesh::node_count(c.first); ++i) cp.row(i) = X.row(c.second[i]);
  return quality::signed_sj(c.first, cp);
}

// The tet or prism of triangle `t` (and `u` for a prism), turned to positive orientation.
Cell oriented(mesh::CellType type, std::array<int, 3> t, std::array<int, 3> u, int apex, const Eigen::MatrixXd& X) {
  Cell c{type, {-1, -1, -1, -1, -1, -1, -1, -1}};
  auto fill = [&]() {
    c.second[0] = t[0]; c.second[1] = t[1]; c.second[2] = t[2];
    if (type == mesh::CellType::Tet) c.second[3] = apex;
    else { c.second[3] = u[0]; c.second[4] = u[1]; c.second[5] = u[2]; }
  };
  fill();
  if (cell_quality(c, X) < 0) {
    std::swap(t[0], t[1]);
    std::swap(u[0], u[1]);
    fill();
  }
  return c;
}

struct State {
  std::vector<int> rep;                  // structure vertex -> the vertex it became
  Eigen::MatrixXd X;                     // structure positions
  std::vector<std::vector<Cell>> cells;  // per block: its replacement (empty: unchanged)
  Eigen::VectorXi patch;                 // per patch triangle
  std::vector<char> removed;             // patch triangles dropped
  std::vector<std::array<int, 4>> added; // new triangles (a, b, c, patch): fans, halves of squares
  std::vector<Eigen::RowVector3d> extra;  // new patch vertices (indices from the patch surface's count)
  int next_patch = 0, tets = 0, prisms = 0, split = 0;
};

// Cuts the triangles `tris` of one square (axis `axis`, polycube positions D in grid units) along
// its diagonal from corner A to corner C (cut_triangles). The triangles on one side keep `keep`, the
// others get `other`. False when a triangle lies on the diagonal or one side is empty.
bool split_square(const mesh::SurfaceMesh& s, const Eigen::MatrixXd& D, int axis, const std::vector<int>& tris, int A, int C,
                  int keep, int other, State& st) {
  const int b = (axis + 1) % 3, d = (axis + 2) % 3, nv = static_cast<int>(s.V.rows());
  std::map<int, double> f;
  for (int t : tris)
    for (int k = 0; k < 3; ++k) {
      const int v = s.F(t, k);
      f[v] = (D(v, b) - D(A, b)) * (D(C, d) - D(A, d)) - (D(v, d) - D(A, d)) * (D(C, b) - D(A, b));
    }
  auto pos = [&](int v) -> Eigen::RowVector3d { return v < nv ? Eigen::RowVector3d(s.V.row(v)) : st.extra[v - nv]; };
  const auto pieces = cut_triangles(s.F, tris, f, 1e-9, nv, st.extra, pos);
  int sides[2] = {0, 0};
  std::vector<std::array<int, 4>> halves;
  for (const auto& v : pieces) {
    const double sum = f[v[0]] + f[v[1]] + f[v[2]];
    if (sum == 0) return false;
    ++sides[sum > 0];
    halves.push_back({v[0], v[1], v[2], sum > 0 ? keep : other});
  }
  if (!sides[0] || !sides[1]) return false;
  for (int t : tris) st.removed[t] = 1;
  st.added.insert(st.added.end(), halves.begin(), halves.end());
  return true;
}

}  // namespace

std::vector<int> add_apex_caps(mesh::SurfaceMesh& s, const ApexCapOptions& opt) {
  std::vector<std::pair<int, int>> apexes;  // vertex, cap label
  {
    const int nv = static_cast<int>(s.V.rows()), nf = static_cast<int>(s.F.rows());
    std::vector<std::vector<int>> tris(nv);
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) tris[s.F(f, k)].push_back(f);
    for (int v = 0; v < nv; ++v) {
      if (tris[v].size() < 3) continue;
      std::set<int> L;
      for (int f : tris[v]) L.insert(s.patch(f));
      if (L.size() < 3) continue;
      bool has[3] = {false, false, false};
      for (int l : L) has[(l - 1) / 2] = true;
      int missing = -1, axes = 0;
      for (int a = 0; a < 3; ++a) (has[a] ? ++axes : missing = a);
      if (axes != 2) continue;
      // A tip: the angles of its triangles at it sum to well below a full turn (a cone of half-angle
      // 32 degrees: 0.53 of a turn, the pyramid here 0.64, a point on a crease or a flat face 1), and
      // it points along the missing axis: every triangle of the ring leans that way (the end of a
      // knife edge has faces at right angles to it: no tip).
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      double lo = 1e300, hi = -1e300, angle = 0;
      for (int f : tris[v]) {
        const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
        const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
        mean += n;
        lo = std::min(lo, n[missing]);
        hi = std::max(hi, n[missing]);
        int k = 0;
        while (s.F(f, k) != v) ++k;
        const Eigen::Vector3d o = s.V.row(v), x = s.V.row(s.F(f, (k + 1) % 3)), y = s.V.row(s.F(f, (k + 2) % 3));
        angle += std::atan2((x - o).cross(y - o).norm(), (x - o).dot(y - o));
      }
      mean /= static_cast<double>(tris[v].size());
      if (angle > opt.max_angle * 2 * M_PI) continue;
      if (std::abs(mean[missing]) < opt.min_normal || (mean[missing] > 0 ? lo < opt.min_lean : hi > -opt.min_lean)) continue;
      const int cap = 1 + 2 * missing + (mean[missing] > 0 ? 0 : 1);
      bool near = false;  // within the cap of an apex found before
      for (const auto& [w, l] : apexes) near = near || (s.V.row(w) - s.V.row(v)).norm() <= 2 * opt.radius || w == v;
      if (near) continue;
      apexes.push_back({v, cap});
      if (opt.log)
        opt.log(0, "apex at (" + fmt("%.4g, %.4g, %.4g", s.V(v, 0), s.V(v, 1), s.V(v, 2)) + "): " + std::to_string(L.size()) +
                       " charts of two axes meet; a " + segmentation::label_name(cap) + " cap" +
                       (opt.radius > 0 ? fmt(" of radius %.3g", opt.radius) : std::string(" over its 1-ring")));
    }
  }
  std::vector<int> out;
  for (const auto& [v, cap] : apexes) {
    const int nv = static_cast<int>(s.V.rows()), nf = static_cast<int>(s.F.rows());
    const Eigen::RowVector3d p = s.V.row(v);
    std::vector<int> cap_tris;
    if (opt.radius <= 0) {
      for (int f = 0; f < nf; ++f)
        if ((s.F.row(f).array() == v).any()) cap_tris.push_back(f);
    } else {
      // The triangles reaching into the ball of the radius, connected to the apex, cut at its sphere.
      std::vector<std::vector<int>> tris(nv);
      for (int f = 0; f < nf; ++f)
        for (int k = 0; k < 3; ++k) tris[s.F(f, k)].push_back(f);
      std::map<int, double> dist;
      auto field = [&](int w) {
        auto it = dist.find(w);
        return it != dist.end() ? it->second : dist[w] = (s.V.row(w) - p).norm() - opt.radius;
      };
      std::set<int> seen(tris[v].begin(), tris[v].end());
      std::vector<int> stack(tris[v].begin(), tris[v].end()), near;
      while (!stack.empty()) {
        const int f = stack.back();
        stack.pop_back();
        near.push_back(f);
        for (int k = 0; k < 3; ++k) {
          const int w = s.F(f, k);
          if (field(w) >= 0) continue;
          for (int g : tris[w])
            if (seen.insert(g).second) stack.push_back(g);
        }
      }
      for (int f : near)
        for (int k = 0; k < 3; ++k) field(s.F(f, k));
      std::vector<Eigen::RowVector3d> extra;
      auto pos = [&](int w) -> Eigen::RowVector3d { return w < nv ? Eigen::RowVector3d(s.V.row(w)) : extra[w - nv]; };
      std::sort(near.begin(), near.end());
      const auto pieces = cut_triangles(s.F, near, dist, 0.05 * opt.radius, nv, extra, pos);
      std::vector<char> is_near(nf, 0);
      for (int f : near) is_near[f] = 1;
      mesh::SurfaceMesh c;
      c.V.resize(nv + static_cast<int>(extra.size()), 3);
      c.V.topRows(nv) = s.V;
      for (size_t i = 0; i < extra.size(); ++i) c.V.row(nv + i) = extra[i];
      const int kept = nf - static_cast<int>(near.size());
      c.F.resize(kept + static_cast<int>(pieces.size()), 3);
      c.patch.resize(c.F.rows());
      int n = 0;
      for (int f = 0; f < nf; ++f)
        if (!is_near[f]) { c.F.row(n) = s.F.row(f); c.patch(n++) = s.patch(f); }
      for (const auto& q : pieces) {
        const bool inside = dist.at(q[0]) + dist.at(q[1]) + dist.at(q[2]) < 0;
        if (inside) cap_tris.push_back(n);
        c.F.row(n) << q[0], q[1], q[2];
        c.patch(n++) = s.patch(q[3]);
      }
      s = std::move(c);
    }
    for (int f : cap_tris) s.patch(f) = cap;
    out.push_back(v);
  }
  return out;
}

namespace {

/// Grid point (i, j) at `level` along axis a, i along (a + 1) % 3 and j along (a + 2) % 3.
GP grid_point(int a, int i, int j, int level) {
  GP p{};
  p[a] = level;
  p[(a + 1) % 3] = i;
  p[(a + 2) % 3] = j;
  return p;
}

/// A column of blocks below a cap square, to the boundary square that ends it.
struct Column {
  int i = 0, j = 0, bottom = -1, far = 0;
  std::vector<int> blocks, levels;  // levels: each block's lower grid level along the axis
};

/// What collapse_apexes looks up on the grid polycube: grid points, blocks and triangles.
struct ApexContext {
  const GridPolycube& gp;
  int nv = 0, nb = 0, nsq = 0, nf = 0;
  std::map<GP, int> vertex_of, block_of;      // grid point -> structure vertex; lower grid point -> block
  std::vector<std::vector<int>> blocks_of;    // structure vertex -> blocks
  std::vector<std::vector<int>> tris_of_square;
  std::vector<std::vector<int>> vtris;        // patch vertex -> triangles
  std::map<std::pair<int, int>, int> tri_of_edge;  // directed edge -> triangle
  std::vector<int> patch_vertex;              // structure vertex -> patch vertex (boundary grid points)

  explicit ApexContext(const GridPolycube& g) : gp(g) {
    const mesh::Mesh& T = gp.structure;
    const mesh::SurfaceMesh& patches = gp.patches;
    nv = T.num_nodes();
    nb = T.num_cells();
    nsq = static_cast<int>(gp.grid.squares.size());
    nf = static_cast<int>(patches.F.rows());
    for (int v = 0; v < nv; ++v) vertex_of[gp.grid_of[v]] = v;
    blocks_of.resize(nv);
    for (int b = 0; b < nb; ++b) {
      GP lo = gp.grid_of[T.cells(b, 0)];
      for (int i = 0; i < 8; ++i) {
        blocks_of[T.cells(b, i)].push_back(b);
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], gp.grid_of[T.cells(b, i)][k]);
      }
      block_of[lo] = b;
    }
    tris_of_square.resize(nsq);
    for (int f = 0; f < nf; ++f) tris_of_square[patches.patch(f) - 1].push_back(f);
    vtris.resize(patches.V.rows());
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        vtris[patches.F(f, k)].push_back(f);
        tri_of_edge[{patches.F(f, k), patches.F(f, (k + 1) % 3)}] = f;
      }
    patch_vertex.assign(nv, -1);
    for (int v = 0; v < nv; ++v) {
      auto it = gp.grid_vertex.find(gp.grid_of[v]);
      if (it != gp.grid_vertex.end()) patch_vertex[v] = it->second;
    }
  }

  /// Every boundary face of the structure under `s` matches one patch by its corners.
  bool matches(const State& s, const std::vector<int>& apex_of, std::string* why) const {
    const mesh::SurfaceMesh& patches = gp.patches;
    mesh::SurfaceMesh surf;
    std::vector<std::array<int, 4>> F;
    for (int f = 0; f < nf; ++f)
      if (!s.removed[f]) F.push_back({patches.F(f, 0), patches.F(f, 1), patches.F(f, 2), s.patch(f)});
    for (const auto& t : s.added) F.push_back(t);
    surf.V.resize(patches.V.rows() + static_cast<int>(s.extra.size()), 3);
    surf.V.topRows(patches.V.rows()) = patches.V;
    for (size_t i = 0; i < s.extra.size(); ++i) surf.V.row(patches.V.rows() + i) = s.extra[i];
    surf.F.resize(static_cast<int>(F.size()), 3);
    surf.patch.resize(static_cast<int>(F.size()));
    for (size_t i = 0; i < F.size(); ++i) {
      surf.F.row(i) << F[i][0], F[i][1], F[i][2];
      surf.patch(i) = F[i][3];
    }
    std::map<int, int> structure_of;  // patch vertex -> structure vertex
    for (int v = 0; v < nv; ++v) {
      if (s.rep[v] != v) continue;
      const int pv = apex_of[v] >= 0 ? apex_of[v] : patch_vertex[v];
      if (pv >= 0) structure_of[pv] = v;
    }
    polycube::PatchLayout layout;
    try {
      layout = polycube::patch_layout(surf);
    } catch (const std::exception& e) {
      *why = e.what();
      return false;
    }
    std::vector<polycube::BlockFace> faces;
    for (int b = 0; b < nb; ++b) {
      std::vector<Cell> cs = s.cells[b];
      if (cs.empty()) {
        Cell c{mesh::CellType::Hex, {}};
        for (int i = 0; i < 8; ++i) c.second[i] = s.rep[gp.structure.cells(b, i)];
        cs.push_back(c);
      }
      for (const Cell& c : cs)
        for (const auto& vs : sorted_faces(c.first, c.second)) {
          if (std::adjacent_find(vs.begin(), vs.end()) != vs.end()) { *why = "a block with a collapsed face"; return false; }
          faces.push_back({b, -1, vs});
        }
    }
    std::vector<std::vector<int>> patch_corners;
    for (const auto& patch : layout.patches) {
      if (patch.num_loops != 1) { *why = "a patch that is not a disk"; return false; }
      patch_corners.emplace_back();
      for (int li : patch.corners) {
        auto it = structure_of.find(patch.loop[li]);
        if (it == structure_of.end()) { *why = "a patch corner off the block vertices"; return false; }
        patch_corners.back().push_back(it->second);
      }
    }
    const polycube::FaceMatch match = polycube::match_faces_to_patches(faces, patch_corners);
    if (!match.ok()) *why = match.problems.front().message;
    return match.ok();
  }

  /// The columns of blocks below the cap squares `cap` (axis a, sign sg, at `plane`), each ending at
  /// a boundary square facing the other way, none touched by an earlier collapse; `tops` gets their
  /// top blocks. False when a column does not end so.
  bool find_columns(const std::vector<int>& cap, int a, int sg, int plane, const State& state, std::vector<Column>* columns,
                    std::set<int>* tops) const {
    const PolycubeGrid& grid = gp.grid;
    bool ok = true;
    for (int q : cap) {
      Column c;
      c.i = grid.squares[q].i;
      c.j = grid.squares[q].j;
      int level = sg > 0 ? plane - 1 : plane;
      for (;;) {
        auto it = block_of.find(grid_point(a, c.i, c.j, level));
        if (it == block_of.end()) break;
        c.blocks.push_back(it->second);
        c.levels.push_back(level);
        level -= sg;
      }
      if (c.blocks.empty()) { ok = false; break; }
      c.far = sg > 0 ? c.levels.back() : c.levels.back() + 1;
      auto sq = grid.square_of.find({a, c.far, c.i, c.j});
      if (sq == grid.square_of.end() || grid.squares[sq->second].sign != -sg) { ok = false; break; }
      c.bottom = sq->second;
      tops->insert(c.blocks.front());
      for (int blk : c.blocks)
        if (!state.cells[blk].empty()) ok = false;
      columns->push_back(c);
    }
    return ok;
  }

  /// Each column's blocks become 2 tets (the top) and 2 prisms each (below) along the better
  /// diagonal, and its end square splits along it, in `s`; the worst scaled Jacobian before and
  /// after into *before / *after. Returns why it failed, or "".
  std::string split_columns(const std::vector<Column>& columns, int a, int sg, int apex_v, State& s, double* before,
                            double* after) const {
    for (const Column& c : columns) {
      for (int blk : c.blocks) {
        *before = std::min(*before, quality::signed_sj(mesh::CellType::Hex, quality::cell_points(gp.structure, blk)));
      }
      auto V = [&](int di, int dj, int level) { return vertex_of.at(grid_point(a, c.i + di, c.j + dj, level)); };
      // Two diagonals: (0,0)-(1,1) and (1,0)-(0,1); the better one that splits the end square.
      const int tri[2][2][3][2] = {{{{0, 0}, {1, 0}, {1, 1}}, {{0, 0}, {1, 1}, {0, 1}}},
                                   {{{1, 0}, {1, 1}, {0, 1}}, {{1, 0}, {0, 1}, {0, 0}}}};
      double best_q = -1e300;
      int best_o = -1;
      std::vector<std::vector<Cell>> best_cells;
      for (int o = 0; o < 2; ++o) {
        std::vector<std::vector<Cell>> cells(c.blocks.size());
        double worst = 1e300;
        for (size_t k = 0; k < c.blocks.size(); ++k)
          for (int h = 0; h < 2; ++h) {
            std::array<int, 3> lo3, hi3;
            for (int m = 0; m < 3; ++m) {
              lo3[m] = V(tri[o][h][m][0], tri[o][h][m][1], c.levels[k]);
              hi3[m] = V(tri[o][h][m][0], tri[o][h][m][1], c.levels[k] + 1);
            }
            Cell cell = k == 0 ? oriented(mesh::CellType::Tet, sg > 0 ? lo3 : hi3, {}, apex_v, s.X)
                               : oriented(mesh::CellType::Wedge, lo3, hi3, -1, s.X);
            worst = std::min(worst, cell_quality(cell, s.X));
            cells[k].push_back(cell);
          }
        if (worst > best_q) {
          best_q = worst;
          best_o = o;
          best_cells = std::move(cells);
        }
      }
      const int A = gp.grid_vertex.at(grid_point(a, c.i + tri[best_o][0][0][0], c.j + tri[best_o][0][0][1], c.far));
      const int C = gp.grid_vertex.at(grid_point(a, c.i + tri[best_o][0][2][0], c.j + tri[best_o][0][2][1], c.far));
      if (!split_square(gp.patches, gp.D, a, tris_of_square[c.bottom], A, C, c.bottom + 1, s.next_patch, s)) best_cells.clear();
      if (best_cells.empty()) return "the square ending a column does not split along its diagonal";
      *after = std::min(*after, best_q);
      for (size_t k = 0; k < c.blocks.size(); ++k) {
        s.cells[c.blocks[k]] = best_cells[k];
        (k == 0 ? s.tets : s.prisms) += 2;
      }
      ++s.next_patch;
      ++s.split;
    }
    return "";
  }

  /// The cap's triangles give way to a fan from the apex `av` over the cap's boundary, in `s`.
  /// Returns why it failed, or "".
  std::string fan_over_cap(const std::vector<int>& cap, int av, State& s) const {
    const mesh::SurfaceMesh& patches = gp.patches;
    std::set<int> cap_tris;
    for (int q : cap)
      for (int f : tris_of_square[q]) cap_tris.insert(f);
    std::set<std::pair<int, int>> cap_edges;
    for (int f : cap_tris)
      for (int k = 0; k < 3; ++k) cap_edges.insert({patches.F(f, k), patches.F(f, (k + 1) % 3)});
    for (const auto& [u, w] : cap_edges) {
      if (cap_edges.count({w, u})) continue;
      auto it = tri_of_edge.find({w, u});
      if (u == av || w == av || it == tri_of_edge.end() || s.removed[it->second]) return "the apex on the cap's boundary";
      const Eigen::Vector3d p = patches.V.row(av), x = patches.V.row(u), y = patches.V.row(w);
      if ((x - p).cross(y - p).norm() <= 1e-12 * (x - p).norm() * (y - p).norm()) return "a fan triangle of no area";
      s.added.push_back({av, u, w, s.patch(it->second)});
    }
    for (int f : cap_tris) s.removed[f] = 1;
    return "";
  }
};

/// The structure and the patch surface of `state` into `gp`: unused vertices dropped, patch ids 1..n.
void apply_apexes(const State& state, GridPolycube& gp) {
  mesh::Mesh& T = gp.structure;
  mesh::SurfaceMesh& patches = gp.patches;
  const int nv = T.num_nodes(), nb = T.num_cells(), nf = static_cast<int>(patches.F.rows());
  mesh::MeshBuilder builder;
  std::vector<int> id(nv, -1), used;
  auto node = [&](int v) {
    if (id[v] < 0) { id[v] = static_cast<int>(used.size()); used.push_back(v); }
    return id[v];
  };
  for (int b = 0; b < nb; ++b) {
    std::vector<Cell> cs = state.cells[b];
    if (cs.empty()) {
      Cell c{mesh::CellType::Hex, {}};
      for (int i = 0; i < 8; ++i) c.second[i] = state.rep[T.cells(b, i)];
      cs.push_back(c);
    }
    for (const Cell& c : cs) {
      int nodes[8];
      for (int i = 0; i < mesh::node_count(c.first); ++i) nodes[i] = node(c.second[i]);
      builder.add(c.first, nodes, static_cast<int>(T.region(b)));
    }
  }
  Eigen::MatrixXd V(static_cast<int>(used.size()), 3);
  std::vector<GP> g2(used.size());
  for (size_t i = 0; i < used.size(); ++i) {
    V.row(i) = state.X.row(used[i]);
    g2[i] = gp.grid_of[used[i]];
  }
  T = builder.finish(V);
  gp.grid_of = std::move(g2);

  std::vector<std::array<int, 4>> F;
  for (int f = 0; f < nf; ++f)
    if (!state.removed[f]) F.push_back({patches.F(f, 0), patches.F(f, 1), patches.F(f, 2), state.patch(f)});
  for (const auto& t : state.added) F.push_back(t);
  std::map<int, int> new_patch;
  const int npv = static_cast<int>(patches.V.rows());
  std::vector<int> vid(npv + state.extra.size(), -1);
  int n = 0;
  for (auto& t : F) {
    for (int k = 0; k < 3; ++k)
      if (vid[t[k]] < 0) vid[t[k]] = n++;
    t[3] = new_patch.emplace(t[3], static_cast<int>(new_patch.size()) + 1).first->second;
  }
  mesh::SurfaceMesh out_patches;
  out_patches.V.resize(n, 3);
  for (size_t v = 0; v < vid.size(); ++v)
    if (vid[v] >= 0)
      out_patches.V.row(vid[v]) = static_cast<int>(v) < npv ? Eigen::RowVector3d(patches.V.row(v)) : state.extra[v - npv];
  out_patches.F.resize(static_cast<int>(F.size()), 3);
  out_patches.patch.resize(static_cast<int>(F.size()));
  for (size_t i = 0; i < F.size(); ++i) {
    out_patches.F.row(i) << vid[F[i][0]], vid[F[i][1]], vid[F[i][2]];
    out_patches.patch(i) = F[i][3];
  }
  patches = std::move(out_patches);
}

}  // namespace

CollapseApexes collapse_apexes(GridPolycube& polycube, const std::vector<int>& apexes, LogCallback log_cb) {
  const PolycubeGrid& grid = polycube.grid;
  const mesh::Mesh& T = polycube.structure;
  const mesh::SurfaceMesh& patches = polycube.patches;
  CollapseApexes out;
  out.apexes = static_cast<int>(apexes.size());
  auto log = [&](const std::string& m) { if (log_cb) log_cb(0, m); };
  if (apexes.empty()) return out;
  const int nv = T.num_nodes(), nb = T.num_cells(), nsq = static_cast<int>(grid.squares.size());
  const int nf = static_cast<int>(patches.F.rows());
  for (int b = 0; b < nb; ++b)
    if (T.type(b) != mesh::CellType::Hex) { log("apexes: left as hex blocks (the structure has blocks other than hexes)"); return out; }
  for (int f = 0; f < nf; ++f)
    if (patches.patch(f) < 1 || patches.patch(f) > nsq) { log("apexes: left as hex blocks (patches are not squares)"); return out; }
  const ApexContext cx(polycube);

  State state;
  state.rep.resize(nv);
  for (int v = 0; v < nv; ++v) state.rep[v] = v;
  state.X = T.V;
  state.cells.resize(nb);
  state.patch = patches.patch;
  state.removed.assign(nf, 0);
  state.next_patch = nsq + 1;
  std::vector<int> apex_vertex_of(nv, -1);  // structure vertex -> the apex's patch vertex

  double worst_before = 1e300, worst_after = 1e300;
  for (int av : apexes) {
    const std::string where = "apex at (" + fmt("%.4g, %.4g, %.4g", patches.V(av, 0), patches.V(av, 1), patches.V(av, 2)) + ")";
    auto fail = [&](const std::string& why) { log(where + ": left as hex blocks under a cap (" + why + ")"); };
    if (av < 0 || av >= patches.V.rows() || cx.vtris[av].empty()) { fail("no such vertex"); continue; }
    int chart = -1;
    bool one = true;
    for (int f : cx.vtris[av]) {
      const int c = grid.squares[patches.patch(f) - 1].chart;
      one = one && (chart < 0 || c == chart) && !state.removed[f];
      chart = c;
    }
    if (!one) { fail("its triangles lie on several charts"); continue; }
    std::vector<int> cap;
    for (int q = 0; q < nsq; ++q)
      if (grid.squares[q].chart == chart) cap.push_back(q);
    const GridSquare& s0 = grid.squares[cap.front()];
    const int a = s0.axis, sg = s0.sign, plane = s0.plane;
    bool flat = true;
    for (int q : cap) flat = flat && grid.squares[q].axis == a && grid.squares[q].plane == plane && grid.squares[q].sign == sg;
    if (!flat) { fail("a cap of several planes"); continue; }
    // The cap's corners collapse to one vertex at the apex.
    std::set<int> cap_vertices;
    bool ok = true;
    for (int q : cap)
      for (int k = 0; k < 4; ++k) {
        auto it = cx.vertex_of.find(grid_point(a, grid.squares[q].i + (k & 1), grid.squares[q].j + (k >> 1), plane));
        if (it == cx.vertex_of.end()) ok = false;
        else cap_vertices.insert(it->second);
      }
    if (!ok) { fail("a cap corner without a block vertex"); continue; }
    std::vector<Column> columns;
    std::set<int> tops;
    if (!cx.find_columns(cap, a, sg, plane, state, &columns, &tops)) {
      fail("a column under the cap that does not end at a boundary square");
      continue;
    }
    for (int v : cap_vertices)
      for (int blk : cx.blocks_of[v])
        if (!tops.count(blk)) ok = false;
    if (!ok) { fail("a block beside the cap touches it"); continue; }

    State s = state;
    const int apex_v = *cap_vertices.begin();
    for (int v : cap_vertices) s.rep[v] = apex_v;
    s.X.row(apex_v) = patches.V.row(av);
    std::vector<int> apex_of = apex_vertex_of;
    apex_of[apex_v] = av;
    double before = 1e300, after = 1e300;
    std::string why = cx.split_columns(columns, a, sg, apex_v, s, &before, &after);
    if (!why.empty()) { fail(why); continue; }
    why = cx.fan_over_cap(cap, av, s);
    if (!why.empty()) { fail(why); continue; }
    if (after <= 0) { fail(fmt("an inverted block, scaled Jacobian %.3f", after)); continue; }
    if (!cx.matches(s, apex_of, &why)) { fail(why); continue; }
    log(where + fmt(": %.0f cap squares collapsed, %.0f tet and %.0f prism blocks; worst block SJ %.3f", cap.size(),
                    s.tets - state.tets, s.prisms - state.prisms, after) +
        fmt(" (%.3f as hexes)", before));
    worst_before = std::min(worst_before, before);
    worst_after = std::min(worst_after, after);
    state = std::move(s);
    apex_vertex_of = std::move(apex_of);
    ++out.collapsed;
  }
  if (out.collapsed == 0) return out;
  out.tets = state.tets;
  out.prisms = state.prisms;
  out.split_squares = state.split;
  out.min_quality_before = worst_before;
  out.min_quality_after = worst_after;
  apply_apexes(state, polycube);
  return out;
}

}  // namespace hexdom::autopolycube
