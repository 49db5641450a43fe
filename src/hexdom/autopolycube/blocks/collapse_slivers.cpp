#include "hexdom/autopolycube/blocks/collapse_slivers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

#include "hexdom/common/disjoint_sets.h"
#include "hexdom/common/format.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/surface_check.h"
#include "hexdom/mesh/triangle_adjacency.h"
#include "hexdom/polycube/boundary_graph.h"
#include "hexdom/polycube/match_faces.h"
#include "hexdom/polycube/patch_layout.h"
#include "hexdom/quality/metrics.h"

namespace hexdom::autopolycube {

namespace {

using GP = std::array<int, 3>;

// A chart whose squares form a rectangle 1 or 2 squares wide across `thin` (an in-plane axis) and
// `nl` squares long along `lng`.
struct Strip {
  int chart = -1, axis = 0, plane = 0, thin = 0, lng = 0;
  int t0 = 0, nt = 0, l0 = 0, nl = 0;
  std::vector<int> squares;
  double ratio = 0;
  GP point(int t, int l) const {
    GP p{};
    p[axis] = plane;
    p[thin] = t;
    p[lng] = l;
    return p;
  }
};

struct State {
  DisjointSets rep{0};     // structure vertices joined into one
  std::vector<int> at;     // the vertex whose position and grid point a class takes (its corner)
  std::vector<int> owner;  // square -> the square whose patch its triangles join
  int find(int v) { return rep.find(v); }
  int owner_of(int q) const {
    while (owner[q] != q) q = owner[q];
    return q;
  }
};

quality::CellPoints points(const mesh::DegenerateHex& d, const Eigen::MatrixXd& pos) {
  quality::CellPoints cp = quality::CellPoints::Zero();
  for (int i = 0; i < mesh::node_count(d.type); ++i) cp.row(i) = pos.row(d.nodes[i]);
  return cp;
}

double shape_quality(const mesh::DegenerateHex& d, const Eigen::MatrixXd& pos) { return quality::signed_sj(d.type, points(d, pos)); }

/// Strips: charts whose squares fill a rectangle 1 or 2 squares wide (`vertex_of`: grid point ->
/// structure vertex), each across the direction with the smaller ratio across / along.
std::vector<Strip> find_strips(const PolycubeGrid& grid, const mesh::Mesh& T, const std::map<GP, int>& vertex_of) {
  auto X = [&](const GP& p) -> Eigen::RowVector3d { return T.V.row(vertex_of.at(p)); };
  std::map<int, std::vector<int>> of_chart;
  for (int q = 0; q < static_cast<int>(grid.squares.size()); ++q) of_chart[grid.squares[q].chart].push_back(q);
  std::vector<Strip> strips;
  for (const auto& [chart, sq] : of_chart) {
    const GridSquare& s0 = grid.squares[sq.front()];
    bool one_plane = true;
    int imin = s0.i, imax = s0.i, jmin = s0.j, jmax = s0.j;
    for (int q : sq) {
      const GridSquare& s = grid.squares[q];
      one_plane = one_plane && s.axis == s0.axis && s.plane == s0.plane;
      imin = std::min(imin, s.i); imax = std::max(imax, s.i);
      jmin = std::min(jmin, s.j); jmax = std::max(jmax, s.j);
    }
    if (!one_plane || static_cast<int>(sq.size()) != (imax - imin + 1) * (jmax - jmin + 1)) continue;
    Strip best;
    best.ratio = 1e300;
    for (int dir = 0; dir < 2; ++dir) {
      Strip st;
      st.chart = chart;
      st.axis = s0.axis;
      st.plane = s0.plane;
      const int b = (s0.axis + 1) % 3, c = (s0.axis + 2) % 3;
      st.thin = dir ? c : b;
      st.lng = dir ? b : c;
      st.t0 = dir ? jmin : imin;
      st.nt = dir ? jmax - jmin + 1 : imax - imin + 1;
      st.l0 = dir ? imin : jmin;
      st.nl = dir ? imax - imin + 1 : jmax - jmin + 1;
      if (st.nt > 2) continue;
      st.squares = sq;
      bool ok = true;
      double cross = 0, along = 1e300;
      for (int l = st.l0; l <= st.l0 + st.nl && ok; ++l) {
        double len = 0;
        for (int t = st.t0; t <= st.t0 + st.nt; ++t) {
          if (!vertex_of.count(st.point(t, l))) { ok = false; break; }
          if (t > st.t0) len += (X(st.point(t, l)) - X(st.point(t - 1, l))).norm();
          if (l > st.l0) along = std::min(along, (X(st.point(t, l)) - X(st.point(t, l - 1))).norm());
        }
        cross = std::max(cross, len);
      }
      if (!ok) continue;
      st.ratio = along > 0 ? cross / along : 1e300;
      if (st.ratio < best.ratio) best = st;
    }
    if (best.chart < 0) continue;
    strips.push_back(best);
  }
  return strips;
}

/// Grid edges (sorted grid points) -> the squares that have them.
std::map<std::pair<GP, GP>, std::vector<int>> grid_edge_squares(const PolycubeGrid& grid) {
  std::map<std::pair<GP, GP>, std::vector<int>> edge_squares;
  for (int q = 0; q < static_cast<int>(grid.squares.size()); ++q) {
    const GridSquare& s = grid.squares[q];
    const int b = (s.axis + 1) % 3, c = (s.axis + 2) % 3;
    GP p[4];
    for (int k = 0; k < 4; ++k) {
      p[k][s.axis] = s.plane;
      p[k][b] = s.i + (k == 1 || k == 2);
      p[k][c] = s.j + (k >= 2);
    }
    for (int k = 0; k < 4; ++k) {
      GP u = p[k], w = p[(k + 1) % 4];
      if (w < u) std::swap(u, w);
      edge_squares[{u, w}].push_back(q);
    }
  }
  return edge_squares;
}

/// The blocks of a structure under a State of collapses.
struct Blocks {
  const mesh::Mesh& T;
  const mesh::SurfaceMesh& patches;
  const std::vector<int>& structure_of;  // patch vertex -> structure vertex, -1 off the grid points
  // The patches' triangle adjacency, the surface checked closed and manifold on first use: every
  // candidate relabels the same triangles.
  mutable Eigen::MatrixXi adjacency;

  polycube::PatchLayout layout(const mesh::SurfaceMesh& surf) const {
    if (adjacency.size() == 0) {
      mesh::check_closed_manifold(surf);
      adjacency = mesh::triangle_adjacency(surf.F);
    }
    return polycube::patch_layout(polycube::boundary_graph(surf, adjacency));
  }

  /// The block as it is under `s`: type and nodes, or false when its pattern is none of the three.
  bool shape(State& s, int b, mesh::DegenerateHex* d) const {
    std::array<int, 8> h;
    for (int i = 0; i < 8; ++i) h[i] = s.find(T.cells(b, i));
    try {
      *d = mesh::classify_hex_nodes(h);
    } catch (const std::invalid_argument&) {
      return false;
    }
    return true;
  }

  /// Every boundary face of the structure under `s` matches one patch (one boundary loop) by its
  /// corners, each class has at most one corner; on success the class positions go to `pos`.
  bool matches(State& s, Eigen::MatrixXd& pos, std::string* why) const {
    mesh::SurfaceMesh surf = patches;
    for (int f = 0; f < surf.F.rows(); ++f) surf.patch(f) = 1 + s.owner_of(patches.patch(f) - 1);
    const polycube::PatchLayout layout = this->layout(surf);
    std::map<int, int> corner_of_class;
    for (size_t c = 0; c < layout.corners.size(); ++c) {
      const int v = structure_of[layout.corners[c]];
      if (v < 0) { *why = "a patch corner off the block vertices"; return false; }
      if (!corner_of_class.emplace(s.find(v), v).second) { *why = "two corners for one block vertex"; return false; }
    }
    std::vector<polycube::BlockFace> faces;
    for (int b = 0; b < T.num_cells(); ++b) {
      mesh::DegenerateHex d;
      if (!shape(s, b, &d)) { *why = "a block that is no hex, prism or tet"; return false; }
      for (auto& vs : sorted_faces(d.type, d.nodes)) faces.push_back({b, -1, std::move(vs)});
    }
    std::vector<std::vector<int>> patch_corners;
    for (const auto& patch : layout.patches) {
      if (patch.num_loops != 1) { *why = "a patch that is not a disk"; return false; }
      patch_corners.emplace_back();
      for (int li : patch.corners) patch_corners.back().push_back(s.find(structure_of[patch.loop[li]]));
    }
    const polycube::FaceMatch match = polycube::match_faces_to_patches(faces, patch_corners);
    if (!match.ok()) { *why = match.problems.front().message; return false; }
    for (const auto& [cls, v] : corner_of_class) {
      pos.row(cls) = T.V.row(v);
      s.at[cls] = v;
    }
    return true;
  }
};

/// The collapsed structure (positions P of the classes of `state`), unused vertices dropped, and
/// the patches renumbered 1..n, into `gp`; the blocks' and squares' counts into `out`.
void apply_collapse(State& state, const Eigen::MatrixXd& P, const Blocks& blocks, GridPolycube& gp, CollapseSlivers& out) {
  mesh::Mesh& T = gp.structure;
  const int nv = T.num_nodes(), nb = T.num_cells(), nsq = static_cast<int>(gp.grid.squares.size());
  mesh::MeshBuilder builder;
  std::vector<int> id(nv, -1);
  std::vector<int> used;
  for (int b = 0; b < nb; ++b) {
    mesh::DegenerateHex d;
    blocks.shape(state, b, &d);
    int nodes[8];
    for (int i = 0; i < mesh::node_count(d.type); ++i) {
      int& x = id[d.nodes[i]];
      if (x < 0) { x = static_cast<int>(used.size()); used.push_back(d.nodes[i]); }
      nodes[i] = x;
    }
    out.prisms += d.type == mesh::CellType::Wedge;
    out.tets += d.type == mesh::CellType::Tet;
    builder.add(d.type, nodes, static_cast<int>(T.region(b)));
  }
  Eigen::MatrixXd V(static_cast<int>(used.size()), 3);
  std::vector<GP> g2(used.size());
  for (size_t i = 0; i < used.size(); ++i) {
    V.row(i) = P.row(used[i]);
    g2[i] = gp.grid_of[state.at[used[i]]];
  }
  T = builder.finish(V);
  gp.grid_of = std::move(g2);
  std::map<int, int> new_id;
  for (int q = 0; q < nsq; ++q)
    if (state.owner[q] != q) ++out.merged_squares;
  for (int q = 0; q < nsq; ++q) {
    const int o = state.owner_of(q);
    if (!new_id.count(o)) new_id.emplace(o, static_cast<int>(new_id.size()) + 1);
  }
  for (int f = 0; f < gp.patches.F.rows(); ++f) gp.patches.patch(f) = new_id.at(state.owner_of(gp.patches.patch(f) - 1));
}

}  // namespace

CollapseSlivers collapse_slivers(GridPolycube& polycube, const CollapseSliversOptions& opt) {
  const PolycubeGrid& grid = polycube.grid;
  mesh::Mesh& T = polycube.structure;
  std::vector<GP>& grid_of = polycube.grid_of;
  mesh::SurfaceMesh& patches = polycube.patches;
  const std::map<GP, int>& grid_vertex = polycube.grid_vertex;
  CollapseSlivers out;
  auto log = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  const int nv = T.num_nodes(), nb = T.num_cells(), nsq = static_cast<int>(grid.squares.size());
  for (int b = 0; b < nb; ++b)
    if (T.type(b) != mesh::CellType::Hex) throw MeshingError("collapse_slivers expects hex blocks");
  std::map<GP, int> vertex_of;
  for (int v = 0; v < nv; ++v) vertex_of[grid_of[v]] = v;

  const std::vector<Strip> strips = find_strips(grid, T, vertex_of);
  out.candidates = static_cast<int>(strips.size());
  if (strips.empty()) return out;

  // Grid edges -> squares, structure vertices -> blocks, surface vertices -> structure vertices.
  const std::map<std::pair<GP, GP>, std::vector<int>> edge_squares = grid_edge_squares(grid);
  std::vector<std::vector<int>> blocks_of(nv);
  for (int b = 0; b < nb; ++b)
    for (int i = 0; i < 8; ++i) blocks_of[T.cells(b, i)].push_back(b);
  std::vector<int> structure_of(patches.V.rows(), -1);
  for (const auto& [p, sv] : grid_vertex) {
    auto it = vertex_of.find(p);
    if (it != vertex_of.end()) structure_of[sv] = it->second;
  }

  State state;
  state.rep = DisjointSets(nv);
  state.at.resize(nv);
  for (int v = 0; v < nv; ++v) state.at[v] = v;
  state.owner.resize(nsq);
  for (int q = 0; q < nsq; ++q) state.owner[q] = q;
  Eigen::MatrixXd P = T.V;  // class positions (at the representative)

  const Blocks blocks{T, patches, structure_of, {}};
  auto block_shape = [&](State& s, int b, mesh::DegenerateHex* d) { return blocks.shape(s, b, d); };
  auto matches = [&](State& s, Eigen::MatrixXd& pos, std::string* why) { return blocks.matches(s, pos, why); };

  for (const Strip& st : strips) {
    opt.deadline.check("autopolycube (slivers)");
    // Blocks around the strip's vertices and their worst quality now.
    std::set<int> touched;
    for (int l = st.l0; l <= st.l0 + st.nl; ++l)
      for (int t = st.t0; t <= st.t0 + st.nt; ++t)
        for (int b : blocks_of[vertex_of.at(st.point(t, l))]) touched.insert(b);
    double before = 1e300, volume_before = 0;
    for (int b : touched) {
      mesh::DegenerateHex d;
      block_shape(state, b, &d);
      before = std::min(before, shape_quality(d, P));
      volume_before += quality::volume(d.type, points(d, P));
    }
    const bool thin = st.ratio <= opt.max_ratio, poor = before <= opt.poor_quality;
    if (!thin && !poor) continue;
    ++out.slivers;
    // Candidates: a 1-wide strip joins the patches on either side; a 2-wide one splits between both.
    State best_state;
    Eigen::MatrixXd best_pos;
    double best_after = -1e300, best_volume = 0;
    std::string last_why;
    int best_prisms = 0;
    for (int side = 0; side < (st.nt == 1 ? 2 : 1); ++side) {
      State s = state;
      bool ok = true;
      for (int l = st.l0; l <= st.l0 + st.nl; ++l) {
        const int keep = st.nt == 2 ? st.t0 + 1 : side == 0 ? st.t0 + 1 : st.t0;
        const int k = s.find(vertex_of.at(st.point(keep, l)));
        for (int t = st.t0; t <= st.t0 + st.nt; ++t) {
          const int r = s.find(vertex_of.at(st.point(t, l)));
          s.rep.unite(r, k);
        }
      }
      for (int q : st.squares) {
        const GridSquare& g = grid.squares[q];
        const int t = st.thin == (g.axis + 1) % 3 ? g.i : g.j, l = st.lng == (g.axis + 1) % 3 ? g.i : g.j;
        // The long edge this square's triangles cross to join their neighbour.
        const int te = st.nt == 2 ? (t == st.t0 ? t : t + 1) : side == 0 ? t : t + 1;
        GP u = st.point(te, l), w = st.point(te, l + 1);
        if (w < u) std::swap(u, w);
        const auto& es = edge_squares.at({u, w});
        int nbr = -1;
        for (int o : es)
          if (o != q) nbr = nbr < 0 ? o : -2;
        if (nbr < 0 || grid.squares[nbr].chart == st.chart) { ok = false; last_why = "no single neighbouring square"; break; }
        s.owner[q] = s.owner_of(nbr);
      }
      Eigen::MatrixXd pos = P;
      std::string why;
      if (!ok || !matches(s, pos, &why)) {
        if (ok) last_why = why;
        continue;
      }
      double after = 1e300, volume = 0;
      int prisms = 0;
      for (int b : touched) {
        mesh::DegenerateHex d;
        block_shape(s, b, &d);
        prisms += d.type == mesh::CellType::Wedge;
        after = std::min(after, shape_quality(d, pos));
        volume += quality::volume(d.type, points(d, pos));
      }
      // Among the ways that keep the volume, the best worst block.
      const double dv = volume_before > 0 ? std::abs(volume - volume_before) / volume_before : 1.0;
      const bool keeps = dv <= opt.max_volume_change;
      const bool best_keeps = best_after > -1e300 && std::abs(best_volume - volume_before) <= opt.max_volume_change * volume_before;
      if (best_after == -1e300 || (keeps && !best_keeps) || (keeps == best_keeps && after > best_after)) {
        best_after = after;
        best_volume = volume;
        best_state = std::move(s);
        best_pos = std::move(pos);
        best_prisms = prisms;
      }
    }
    const std::string what = fmt("slivers: chart %.0f (%.0f x %.0f squares, across / along %.3f)", st.chart + 1, st.nt, st.nl, st.ratio);
    if (best_after == -1e300) {
      log(what + ": kept as hex blocks (" + last_why + ")");
      continue;
    }
    const double dv = volume_before > 0 ? (best_volume - volume_before) / volume_before : 1.0;
    const std::string figures = fmt(" (worst block SJ %.3f as hexes, %.3f as prisms; block volume %+.2f%%)", before, best_after, 100 * dv);
    if ((thin ? best_after < before - opt.quality_slack : best_after < before + opt.min_gain) || std::abs(dv) > opt.max_volume_change) {
      log(what + ": kept as hex blocks" + figures);
      continue;
    }
    log(what + fmt(": %.0f prism blocks", best_prisms) + figures);
    state = std::move(best_state);
    P = std::move(best_pos);
    ++out.collapsed;
  }
  if (out.collapsed == 0) return out;

  apply_collapse(state, P, blocks, polycube, out);
  return out;
}

std::vector<std::vector<int>> sorted_faces(mesh::CellType type, const std::array<int, 8>& nodes) {
  const auto [faces, n] = mesh::cell_faces(type);
  std::vector<std::vector<int>> out(n);
  for (int f = 0; f < n; ++f) {
    for (int i = 0; i < faces[f].n; ++i) out[f].push_back(nodes[faces[f].v[i]]);
    std::sort(out[f].begin(), out[f].end());
  }
  return out;
}

}  // namespace hexdom::autopolycube
