#include "hexdom/overlay/buffer.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
#include <tuple>
#include <unordered_map>

#include "hexdom/common/disjoint_sets.h"
#include "hexdom/common/interrupt.h"
#include "hexdom/mesh/edge_key.h"

namespace hexdom::overlay {

namespace {
// quad_regions: a quad whose normal makes more than 60 degrees with the normal at its centroid's
// closest point takes the face its normal line meets within kFacingReach quad diagonals (or twice
// the closest point's distance) instead.
constexpr double kFacingCos = 0.5;
constexpr double kFacingReach = 1.5;

// Twice the vector area of quad q of m (the cross product of its diagonals): outward for an outer
// quad; its length, not its direction, is 0 for a quad folded flat.
Eigen::Vector3d quad_area_normal(const mesh::Mesh& m, const std::array<int, 4>& q) {
  const Eigen::Vector3d d1 = m.V.row(q[2]) - m.V.row(q[0]), d2 = m.V.row(q[3]) - m.V.row(q[1]);
  return d1.cross(d2);
}
}  // namespace

mesh::Mesh add_buffer_layer(const mesh::Mesh& core, std::vector<std::array<int, 4>>* outer, std::vector<int>* copy_out) {
  const std::vector<mesh::BoundaryFace> faces = mesh::boundary_faces(core);
  const int n0 = core.num_nodes();
  std::vector<int> copy(n0, -1);
  int added = 0;
  for (const auto& f : faces)
    for (int i = 0; i < f.n; ++i)
      if (copy[f.v[i]] < 0) copy[f.v[i]] = n0 + added++;
  Eigen::MatrixXd V(n0 + added, 3);
  V.topRows(n0) = core.V;
  for (int v = 0; v < n0; ++v)
    if (copy[v] >= 0) V.row(copy[v]) = core.V.row(v);
  mesh::MeshBuilder b;
  for (int c = 0; c < core.num_cells(); ++c) b.add(core.type(c), core.cells.row(c).data(), core.region(c));
  outer->clear();
  for (const auto& f : faces) {
    // The quad's right-hand normal points out of the core, towards the new face: VTK's bottom face.
    const int hex[8] = {f.v[0], f.v[1], f.v[2], f.v[3], copy[f.v[0]], copy[f.v[1]], copy[f.v[2]], copy[f.v[3]]};
    b.add(mesh::CellType::Hex, hex, 2);
    outer->push_back({copy[f.v[0]], copy[f.v[1]], copy[f.v[2]], copy[f.v[3]]});
  }
  if (copy_out) *copy_out = copy;
  return b.finish(V);
}

int pull_inner_nodes(mesh::Mesh& m, const std::vector<std::array<int, 4>>& outer, const std::vector<int>& copy,
                     const SurfaceFeatures& feat, const std::vector<double>& depth) {
  std::vector<Eigen::Vector3d> normal(m.num_nodes(), Eigen::Vector3d::Zero());
  for (const auto& q : outer) {
    const Eigen::Vector3d n = quad_area_normal(m, q);
    for (int v : q) normal[v] += n;
  }
  int moved = 0;
  for (size_t v = 0; v < copy.size(); ++v) {
    const int o = copy[v];
    if (o < 0 || normal[o].norm() == 0) continue;
    const Eigen::Vector3d n = normal[o].normalized();
    const Eigen::Vector3d xo = m.V.row(o).transpose();
    double d = depth.size() == 1 ? depth[0] : depth[v];
    for (int halving = 0; halving < 4; ++halving, d *= 0.5) {
      Eigen::Vector3d nc;
      feat.project(xo - 1.5 * d * n, nullptr, &nc);
      if (nc.dot(n) > 0) break;  // still nearest its own side
    }
    const Eigen::Vector3d x = m.V.row(static_cast<int>(v)).transpose();
    const double short_by = d - (xo - x).dot(n);
    if (short_by <= 0) continue;
    m.V.row(static_cast<int>(v)) = (x - short_by * n).transpose();
    ++moved;
  }
  return moved;
}

namespace {

// Region per outer quad: the one nearest its centroid, then a few passes in which a quad whose
// edge neighbours mostly (3 or 4 of them) took one other region takes it.
std::vector<int> quad_regions(const mesh::Mesh& m, const std::vector<std::array<int, 4>>& quads, const SurfaceFeatures& feat,
                              const std::vector<std::array<int, 4>>& nbr) {
  std::vector<int> r(quads.size());
  for (size_t q = 0; q < quads.size(); ++q) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int v : quads[q]) c += m.V.row(v).transpose() / 4;
    Eigen::Vector3d normal;
    const Eigen::Vector3d x = feat.project(c, &r[q], &normal);
    // A quad facing away from the nearest point's face (a core cell jutting out past a face next
    // to the one it faces) takes the face its own normal line meets, when that one faces its way.
    const Eigen::Vector3d n = quad_area_normal(m, quads[q]);
    if (n.norm() == 0) continue;
    const Eigen::Vector3d u = n.normalized();
    if (normal.dot(u) >= kFacingCos) continue;
    const double diagonal = std::max((m.V.row(quads[q][2]) - m.V.row(quads[q][0])).norm(),
                                     (m.V.row(quads[q][3]) - m.V.row(quads[q][1])).norm());
    const double reach = std::max(kFacingReach * diagonal, 2 * (x - c).norm());
    int best = -1;
    double best_t = std::numeric_limits<double>::infinity();
    for (const double sign : {1.0, -1.0}) {
      int t = -1;
      const double along = feat.triangles().ray_distance(c, sign * u, 0, reach, -1, &t);
      if (t >= 0 && along < best_t && feat.triangles().normal(t).dot(u) >= kFacingCos) {
        best_t = along;
        best = t;
      }
    }
    if (best >= 0) r[q] = feat.region()[best];
  }
  for (int pass = 0; pass < 3; ++pass) {
    bool changed = false;
    for (size_t q = 0; q < quads.size(); ++q) {
      std::map<int, int> count;
      for (int n : nbr[q])
        if (n >= 0) ++count[r[n]];
      for (const auto& [reg, k] : count)
        if (reg != r[q] && k >= 3) {
          r[q] = reg;
          changed = true;
        }
    }
    if (!changed) break;
  }
  return r;
}

// Whether node v lies on region a: a surface node of a, a curve node of a curve of a, a corner of a.
bool on_region(const Placement& p, const SurfaceFeatures& feat, int v, int a) {
  switch (p.kind[v]) {
    case optimize::Surface: return p.a[v] == a;
    case optimize::Curve: return p.a[v] == a || p.b[v] == a;
    case optimize::Corner: {
      const auto& rc = feat.corner_regions()[p.a[v]];
      return std::binary_search(rc.begin(), rc.end(), a);
    }
    default: return false;
  }
}

// Whether node v is on the curve between regions a < b: a curve node of that pair, or a corner on both.
bool on_the_curve(const Placement& p, const SurfaceFeatures& feat, int v, int a, int b) {
  if (p.kind[v] == optimize::Curve) return p.a[v] == a && p.b[v] == b;
  return p.kind[v] == optimize::Corner && on_region(p, feat, v, a) && on_region(p, feat, v, b);
}

}  // namespace

// Laplacian passes over the outer quads for the crowded nodes (an outer edge shorter than `crowded`):
// each moves to the mean of its neighbours on what it is on (a surface node: the nodes on its region,
// its curves and corners included; a curve node: the nodes on its curve), then back onto that.
// Closest points crowd where the surface turns away from the core (a reflex curve takes every node
// whose nearest point it is); this spreads them, leaving the others where they are.
void spread(mesh::Mesh& m, const std::vector<std::array<int, 4>>& quads, const Placement& p, const SurfaceFeatures& feat,
            int passes, double crowded) {
  const int nn = m.num_nodes();
  std::vector<std::vector<int>> nbrs(nn);
  for (const auto& q : quads)
    for (int i = 0; i < 4; ++i) {
      nbrs[q[i]].push_back(q[(i + 1) % 4]);
      nbrs[q[(i + 1) % 4]].push_back(q[i]);
    }
  for (auto& n : nbrs) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  auto on = [&](int u, int a) { return on_region(p, feat, u, a); };
  auto follows = [&](int v, int u) {
    if (p.kind[v] == optimize::Surface) return on(u, p.a[v]);
    return p.kind[u] != optimize::Surface && on(u, p.a[v]) && on(u, p.b[v]);
  };
  std::vector<char> moving(nn, 0);
  for (int v = 0; v < nn; ++v) {
    if (nbrs[v].empty() || p.kind[v] == optimize::Corner) continue;
    for (int u : nbrs[v])
      if ((m.V.row(u) - m.V.row(v)).norm() < crowded) moving[v] = 1;
  }
  for (int pass = 0; pass < passes; ++pass) {
    Eigen::MatrixXd next = m.V;
    for (int v = 0; v < nn; ++v) {
      if (!moving[v]) continue;
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      int k = 0;
      for (int u : nbrs[v])
        if (follows(v, u)) {
          c += m.V.row(u).transpose();
          ++k;
        }
      if (k > 0) next.row(v) = place(p, feat, v, c / k).transpose();
    }
    m.V = std::move(next);
  }
}

std::vector<std::vector<int>> curve_neighbours(const Placement& p, const std::vector<std::array<int, 4>>& quads,
                                               const SurfaceFeatures& feat) {
  std::vector<std::vector<int>> out(p.kind.size());
  for (const auto& q : quads)
    for (int i = 0; i < 4; ++i) {
      const int v = q[i], u = q[(i + 1) % 4];
      for (auto [x, y] : {std::pair<int, int>{v, u}, std::pair<int, int>{u, v}})
        if (p.kind[x] == optimize::Curve && on_the_curve(p, feat, y, p.a[x], p.b[x]) &&
            std::find(out[x].begin(), out[x].end(), y) == out[x].end())
          out[x].push_back(y);
    }
  return out;
}

Placement place_outer_nodes(mesh::Mesh& m, const std::vector<std::array<int, 4>>& quads, const SurfaceFeatures& feat,
                            double reach, bool staircases) {
  const int nn = m.num_nodes();
  Placement p;
  p.kind.assign(nn, optimize::Interior);
  p.a.assign(nn, -1);
  p.b.assign(nn, -1);
  // Start: every outer node at its closest point.
  std::vector<char> is_outer(nn, 0);
  for (const auto& q : quads)
    for (int v : q) is_outer[v] = 1;
  for (int v = 0; v < nn; ++v)
    if (is_outer[v]) m.V.row(v) = feat.project(m.V.row(v).transpose()).transpose();
  std::unordered_map<int64_t, std::vector<int>> by_edge;
  for (size_t q = 0; q < quads.size(); ++q)
    for (int i = 0; i < 4; ++i) by_edge[mesh::undirected_edge(quads[q][i], quads[q][(i + 1) % 4])].push_back(static_cast<int>(q));
  std::vector<std::array<int, 4>>& nbr = p.quad_neighbours;
  nbr.resize(quads.size());
  for (size_t q = 0; q < quads.size(); ++q)
    for (int i = 0; i < 4; ++i) {
      nbr[q][i] = -1;
      for (int o : by_edge[mesh::undirected_edge(quads[q][i], quads[q][(i + 1) % 4])])
        if (o != static_cast<int>(q)) nbr[q][i] = o;
    }
  p.quad_region = quad_regions(m, quads, feat, nbr);
  const std::vector<int>& region = p.quad_region;
  // Regions around each outer node, with the number of its quads in each.
  std::vector<std::map<int, int>> around(nn);
  for (size_t q = 0; q < quads.size(); ++q)
    for (int v : quads[q]) ++around[v][region[q]];
  auto majority = [&](int v) {
    int best = -1, most = -1;
    for (const auto& [reg, k] : around[v])
      if (k > most) best = reg, most = k;
    return best;
  };
  for (int v = 0; v < nn; ++v) {
    if (!is_outer[v]) continue;
    p.kind[v] = optimize::Surface;
    p.a[v] = majority(v);
    if (around[v].size() < 2) continue;
    // On two or more regions: the curve of the pair with the most quads.
    int best = -1;
    for (auto i = around[v].begin(); i != around[v].end(); ++i)
      for (auto j = std::next(i); j != around[v].end(); ++j)
        if (feat.has_curve(i->first, j->first) && i->second + j->second > best) {
          best = i->second + j->second;
          p.kind[v] = optimize::Curve;
          p.a[v] = i->first;
          p.b[v] = j->first;
        }
  }
  // Corners: the nearest node on two of a corner's regions, nearest pairs first.
  std::vector<std::tuple<double, int, int>> pairs;  // distance, corner, node
  const auto& corners = feat.corners();
  for (size_t c = 0; c < corners.size(); ++c) {
    check_interrupt("overlay");
    const Eigen::Vector3d X = feat.corner_position(static_cast<int>(c));
    const auto& rc = feat.corner_regions()[c];
    for (int v = 0; v < nn; ++v) {
      if (!is_outer[v] || around[v].size() < 2) continue;
      int shared = 0;
      for (const auto& e : around[v]) shared += std::binary_search(rc.begin(), rc.end(), e.first);
      if (shared < 2) continue;
      const double d = (m.V.row(v).transpose() - X).norm();
      if (d <= reach) pairs.emplace_back(d, static_cast<int>(c), v);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<char> corner_done(corners.size(), 0), node_done(nn, 0);
  for (const auto& [d, c, v] : pairs) {
    if (corner_done[c] || node_done[v]) continue;
    corner_done[c] = node_done[v] = 1;
    p.kind[v] = optimize::Corner;
    p.a[v] = c;
    p.b[v] = -1;
  }
  for (char done : corner_done) p.corners_missed += !done;
  // Staircases: a quad with three consecutive nodes on one curve lets the middle one go.
  auto on_curve = [&](int v, int a, int b) { return on_the_curve(p, feat, v, a, b); };
  for (bool changed = staircases; changed;) {
    changed = false;
    for (size_t q = 0; q < quads.size(); ++q)
      for (int i = 0; i < 4; ++i) {
        const int a = quads[q][(i + 3) % 4], v = quads[q][i], c = quads[q][(i + 1) % 4];
        if (p.kind[v] != optimize::Curve) continue;
        if (!on_curve(a, p.a[v], p.b[v]) || !on_curve(c, p.a[v], p.b[v])) continue;
        p.kind[v] = optimize::Surface;
        p.a[v] = region[q] == p.a[v] ? p.b[v] : p.a[v];
        p.b[v] = -1;
        ++p.demoted;
        changed = true;
      }
  }
  const Eigen::MatrixXd closest = m.V;
  for (int v = 0; v < nn; ++v)
    if (is_outer[v]) m.V.row(v) = place(p, feat, v, m.V.row(v).transpose()).transpose();
  // Two nodes of an outer edge put on one point (a curve node whose nearest point on its curve is
  // the curve's end, where a neighbour holds the corner) would make a degenerate cell: the one
  // lower in the feature order goes onto the region around it whose nearest point is nearest to
  // its own nearest point on the surface while not on the other's (onto a region, a node beyond a
  // curve's end lies beside it, not on it).
  const double collapsed = 1e-3 * reach;
  auto rank = [&](int v) { return p.kind[v] == optimize::Corner ? 2 : p.kind[v] == optimize::Curve ? 1 : 0; };
  for (const auto& [key, qs] : by_edge) {
    const std::array<int, 4>& q = quads[qs.front()];
    int u = -1, v = -1;
    for (int i = 0; i < 4 && u < 0; ++i)
      if (mesh::undirected_edge(q[i], q[(i + 1) % 4]) == key) u = q[i], v = q[(i + 1) % 4];
    if ((m.V.row(u) - m.V.row(v)).norm() >= collapsed) continue;
    if (rank(u) > rank(v)) std::swap(u, v);  // v stays, u moves
    if (p.kind[u] == optimize::Corner) continue;
    double move = std::numeric_limits<double>::infinity();
    int best = -1;
    Eigen::Vector3d to;
    for (const auto& [reg, k] : around[u]) {
      const Eigen::Vector3d x = feat.project_region(reg, closest.row(u).transpose());
      const double d = (x - closest.row(u).transpose()).norm();
      if ((x - m.V.row(v).transpose()).norm() >= collapsed && d < move) move = d, best = reg, to = x;
    }
    if (best < 0) continue;
    p.kind[u] = optimize::Surface;
    p.a[u] = best;
    p.b[u] = -1;
    m.V.row(u) = to.transpose();
  }
  for (int v = 0; v < nn; ++v) {
    if (!is_outer[v]) continue;
    p.surface += p.kind[v] == optimize::Surface;
    p.curve += p.kind[v] == optimize::Curve;
    p.corner += p.kind[v] == optimize::Corner;
  }
  return p;
}

CurvePillow pillow_curves(mesh::Mesh& m, std::vector<std::array<int, 4>>& outer, Placement& p, const SurfaceFeatures& feat,
                          double offset) {
  const int nq = static_cast<int>(outer.size()), base = m.num_cells() - nq;
  if (base < 0 || static_cast<int>(p.quad_region.size()) != nq || static_cast<int>(p.quad_neighbours.size()) != nq)
    throw std::logic_error("pillow_curves: the mesh's buffer hexes and the outer quads do not match");
  for (int q = 0; q < nq; ++q)
    for (int i = 0; i < 4; ++i)
      if (m.type(base + q) != mesh::CellType::Hex || m.cells(base + q, 4 + i) != outer[q][i])
        throw std::logic_error("pillow_curves: cell " + std::to_string(base + q) + " is not outer quad " +
                               std::to_string(q) + "'s buffer hex");
  const std::vector<int>& region = p.quad_region;
  // Corners (q, i) of the outer quads; those of one node joined across the edges between two quads
  // of one region: a sector is a set.
  auto corner_of = [&](int q, int v) {
    for (int i = 0; i < 4; ++i)
      if (outer[q][i] == v) return 4 * q + i;
    throw std::logic_error("pillow_curves: an outer edge's quads do not share its nodes");
  };
  auto across = [&](int q, int i) {  // the other quad on edge i of q
    const int o = p.quad_neighbours[q][i];
    if (o < 0) throw std::logic_error("pillow_curves: outer edge with one quad (the buffer layer is not closed)");
    return o;
  };
  DisjointSets sector(4 * nq);
  for (int q = 0; q < nq; ++q)
    for (int i = 0; i < 4; ++i) {
      const int o = across(q, i), u = outer[q][i], w = outer[q][(i + 1) % 4];
      if (o > q && region[o] == region[q]) {
        sector.unite(4 * q + i, corner_of(o, u));
        sector.unite(4 * q + (i + 1) % 4, corner_of(o, w));
      }
    }
  // Nodes with two or more sectors: a copy per sector, numbered after m's nodes.
  const int n0 = m.num_nodes();
  std::vector<std::vector<int>> sectors_at(n0);  // per node, its sectors' representatives
  for (int k = 0; k < 4 * nq; ++k) {
    auto& s = sectors_at[outer[k / 4][k % 4]];
    const int r = sector.find(k);
    if (std::find(s.begin(), s.end(), r) == s.end()) s.push_back(r);
  }
  std::unordered_map<int, int> copy_of;  // sector representative -> new node
  for (int v = 0; v < n0; ++v)
    if (sectors_at[v].size() >= 2)
      for (int r : sectors_at[v]) copy_of.emplace(r, n0 + static_cast<int>(copy_of.size()));
  CurvePillow out;
  out.copies = static_cast<int>(copy_of.size());
  if (out.copies == 0) return out;
  // The copies' positions: `offset` of the way to their sector's mean quad centroid, on its region.
  std::vector<Eigen::Vector3d> towards(out.copies, Eigen::Vector3d::Zero());
  std::vector<int> count(out.copies, 0), copy_region(out.copies, -1), original(out.copies, -1);
  auto node_of = [&](int q, int i) {
    const auto it = copy_of.find(sector.find(4 * q + i));
    return it == copy_of.end() ? outer[q][i] : it->second;
  };
  for (int q = 0; q < nq; ++q) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int v : outer[q]) centroid += m.V.row(v).transpose() / 4;
    for (int i = 0; i < 4; ++i) {
      const int c = node_of(q, i) - n0;
      if (c < 0) continue;
      towards[c] += centroid;
      ++count[c];
      copy_region[c] = region[q];
      original[c] = outer[q][i];
    }
  }
  Eigen::MatrixXd V(n0 + out.copies, 3);
  V.topRows(n0) = m.V;
  for (int c = 0; c < out.copies; ++c) {
    const Eigen::Vector3d x = m.V.row(original[c]).transpose();
    V.row(n0 + c) = feat.project_region(copy_region[c], x + offset * (towards[c] / count[c] - x)).transpose();
  }
  p.kind.resize(n0 + out.copies, optimize::Surface);
  p.a.resize(n0 + out.copies, -1);
  p.b.resize(n0 + out.copies, -1);
  for (int c = 0; c < out.copies; ++c) p.a[n0 + c] = copy_region[c];
  p.surface += out.copies;
  // The cells: the core and the buffer hexes with their sectors' copies, then a wedge on each
  // side of every outer edge between two regions. In hex q (bottom: core nodes, top: outer[q], in
  // VTK order), the wedge at its edge i takes the core node under each end, the old outer node and
  // its copy: {core u, u, copy u, core w, w, copy w}, which the hex's own corners orient as VTK's
  // wedge (its first triangle faces away from the second).
  mesh::MeshBuilder b;
  for (int c = 0; c < base; ++c) b.add(m.type(c), m.cells.row(c).data(), m.region(c));
  std::vector<std::array<int, 4>> strips;
  std::vector<int> strip_region;
  for (int q = 0; q < nq; ++q) {
    int hex[8];
    for (int i = 0; i < 8; ++i) hex[i] = i < 4 ? m.cells(base + q, i) : node_of(q, i - 4);
    b.add(mesh::CellType::Hex, hex, m.region(base + q));
    for (int i = 0; i < 4; ++i) {
      const int j = (i + 1) % 4;
      if (region[across(q, i)] == region[q]) continue;
      const int wedge[6] = {hex[i], outer[q][i], hex[4 + i], hex[j], outer[q][j], hex[4 + j]};
      b.add(mesh::CellType::Wedge, wedge, m.region(base + q));
      strips.push_back({outer[q][i], outer[q][j], hex[4 + j], hex[4 + i]});
      strip_region.push_back(region[q]);
      ++out.prisms;
    }
    for (int i = 0; i < 4; ++i) outer[q][i] = hex[4 + i];
  }
  m = b.finish(std::move(V));
  outer.insert(outer.end(), strips.begin(), strips.end());
  p.quad_region.insert(p.quad_region.end(), strip_region.begin(), strip_region.end());
  p.quad_neighbours.clear();
  return out;
}

int loosen_nodes(Placement& p, std::vector<int> nodes, const SurfaceFeatures& feat) {
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  int freed = 0;
  for (int v : nodes) {
    if (p.kind[v] == optimize::Surface && p.a[v] >= 0) {
      p.a[v] = -1;
      ++freed;
    } else if (p.kind[v] == optimize::Curve) {
      p.kind[v] = optimize::Surface;
      p.b[v] = -1;
      --p.curve, ++p.surface;
      ++freed;
    } else if (p.kind[v] == optimize::Corner) {
      const auto& rc = feat.corner_regions()[p.a[v]];
      for (size_t i = 0; i < rc.size() && p.kind[v] == optimize::Corner; ++i)
        for (size_t j = i + 1; j < rc.size(); ++j)
          if (feat.has_curve(rc[i], rc[j])) {
            p.kind[v] = optimize::Curve;
            p.a[v] = rc[i];
            p.b[v] = rc[j];
            --p.corner, ++p.curve;
            ++freed;
            break;
          }
    }
  }
  return freed;
}

Eigen::Vector3d place(const Placement& p, const SurfaceFeatures& feat, int v, const Eigen::Vector3d& x, int* hint) {
  switch (p.kind[v]) {
    case optimize::Surface: return p.a[v] >= 0 ? feat.project_region(p.a[v], x, hint) : feat.project(x);
    case optimize::Curve: return feat.project_curve(p.a[v], p.b[v], x, hint);
    case optimize::Corner: return feat.corner_position(p.a[v]);
    default: return x;
  }
}

}  // namespace hexdom::overlay
