// Node positions: boundary nodes on the surface from their keys, then interior structure faces,
// then block interiors.
#include <algorithm>
#include <cmath>

#include "hexdom/common/parallel_for.h"
#include "hexdom/generation/steps.h"
#include "hexdom/mesh/cell_faces.h"

namespace hexdom::generation {

using mesh::CellType;
using optimize::NodeFreedom;

void place_boundary_nodes(GenerationState& g) {
  const int nn = static_cast<int>(g.node_key.size());
  const double N3 = static_cast<double>(g.N3);
  g.X = Eigen::MatrixXd::Zero(nn, 3);
  g.known.assign(nn, 0);
  NodeFreedom& freedom = g.freedom;
  freedom.kind.assign(nn, optimize::NodeKind::Interior);
  freedom.param.assign(nn, {0.0, 0.0});
  g.on_curve.assign(nn, nullptr);
  g.on_patch.assign(nn, nullptr);
  Eigen::MatrixXd& X = g.X;
  for (int id = 0; id < nn; ++id) {
    if (g.node_block[id] >= 0) continue;
    const Key& k = g.node_key[id];
    int vs[4], ws[4], m = 0;
    for (int q = 0; q < 4 && k[q] >= 0; ++q, ++m) {
      vs[m] = static_cast<int>(k[q] >> 32);
      ws[m] = static_cast<int>(k[q] & 0xffffffff);
    }
    if (m == 1) {  // a structure vertex
      X.row(id) = g.P[vs[0]].transpose();
      g.known[id] = 1;
      if (g.vertex_corner[vs[0]] >= 0) freedom.kind[id] = optimize::NodeKind::Corner;
    } else if (m == 2) {  // on a structure edge: on its curve when the edge is on the boundary
      auto c = g.curves.find({vs[0], vs[1]});
      if (g.boundary_edges.count({vs[0], vs[1]}) && c != g.curves.end()) {
        X.row(id) = c->second.at(static_cast<double>(ws[1]) / N3).transpose();
        freedom.kind[id] = optimize::NodeKind::Curve;
        freedom.param[id] = {static_cast<double>(ws[1]) / N3, 0.0};
        g.on_curve[id] = &c->second;
      } else {
        X.row(id) = ((ws[0] * g.P[vs[0]] + ws[1] * g.P[vs[1]]) / N3).transpose();
      }
      g.known[id] = 1;
    } else {  // on a structure face: on its patch when the face is on the boundary
      std::vector<int> sv(vs, vs + m);
      auto f = g.boundary_face_patch.find(sv);
      if (f == g.boundary_face_patch.end()) continue;  // interior face: filled later
      const PatchMap& pm = g.maps[f->second];
      Eigen::Vector2d uv = Eigen::Vector2d::Zero();
      for (int q = 0; q < m; ++q) uv += ws[q] * pm.domain.at(vs[q]);
      uv /= N3;
      X.row(id) = evaluate(pm, g.S, uv(0), uv(1)).transpose();
      g.known[id] = 1;
      freedom.kind[id] = optimize::NodeKind::Surface;
      freedom.param[id] = {uv(0), uv(1)};
      g.on_patch[id] = &pm;
    }
  }
}

namespace {

// Harmonic fill of the nodes ids[q] not yet known, each the mean of its neighbours ids[nbrs[q][.]]:
// successive over-relaxation from their current (linear) positions.
void harmonic_fill(GenerationState& g, const std::vector<int>& ids, const std::vector<std::vector<int>>& nbrs) {
  Eigen::MatrixXd& X = g.X;
  const double omega = 2.0 / (1.0 + std::sin(M_PI / std::max(2, g.n)));
  std::vector<int> todo;
  for (size_t q = 0; q < ids.size(); ++q)
    if (!g.known[ids[q]]) todo.push_back(static_cast<int>(q));
  const double tol = 1e-10 * g.diag;
  for (int sweep = 0; sweep < 50 + 20 * g.n && !todo.empty(); ++sweep) {
    double change = 0;
    for (int q : todo) {
      double s0 = 0, s1 = 0, s2 = 0;
      for (int r : nbrs[q]) {
        s0 += X(ids[r], 0);
        s1 += X(ids[r], 1);
        s2 += X(ids[r], 2);
      }
      const double inv = 1.0 / static_cast<double>(nbrs[q].size());
      const int i = ids[q];
      const double d0 = s0 * inv - X(i, 0), d1 = s1 * inv - X(i, 1), d2 = s2 * inv - X(i, 2);
      X(i, 0) += omega * d0;
      X(i, 1) += omega * d1;
      X(i, 2) += omega * d2;
      change = std::max(change, std::fabs(d0) + std::fabs(d1) + std::fabs(d2));
    }
    if (change < tol) break;
  }
  for (int q : todo) g.known[ids[q]] = 1;
}

// Linear start for the unknown nodes of block b from its corners.
void linear_start(GenerationState& g, int b) {
  const CellType t = g.T.type(b);
  const int n = g.n;
  int w[8];
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        if (!in_lattice(t, n, i, j, k)) continue;
        const int id = g.lattice[b][g.lidx(i, j, k)];
        if (g.known[id]) continue;
        const int nw = weights(t, n, i, j, k, w);
        Vec3 s = Vec3::Zero();
        for (int v = 0; v < nw; ++v) s += w[v] * g.P[g.T.cells(b, v)];
        g.X.row(id) = (s / static_cast<double>(g.N3)).transpose();
      }
}

// Local face f of block b (not on the boundary): the Coons patch of its edges (quad) or the
// harmonic fill of its lattice (triangle).
void fill_face(GenerationState& g, int b, const mesh::LocalFace& lf) {
  const int n = g.n;
  Eigen::MatrixXd& X = g.X;
  const int (*C)[3] = corner_table(g.T.type(b));
  // Lattice coordinates of the face's corners in this block.
  auto corner = [&](int i) { return Eigen::Vector3i(C[lf.v[i]][0] * n, C[lf.v[i]][1] * n, C[lf.v[i]][2] * n); };
  const Eigen::Vector3i c0 = corner(0), e1 = (corner(1) - c0) / n, e2 = (corner(lf.n == 4 ? 3 : 2) - c0) / n;
  auto at = [&](int s, int u) { Eigen::Vector3i p = c0 + s * e1 + u * e2; return g.lattice[b][g.lidx(p(0), p(1), p(2))]; };
  if (lf.n == 4) {
    for (int u = 1; u < n; ++u)
      for (int s = 1; s < n; ++s) {
        const double a = static_cast<double>(s) / n, c = static_cast<double>(u) / n;
        Vec3 x = (1 - c) * X.row(at(s, 0)).transpose() + c * X.row(at(s, n)).transpose() +
                 (1 - a) * X.row(at(0, u)).transpose() + a * X.row(at(n, u)).transpose() -
                 ((1 - a) * (1 - c) * X.row(at(0, 0)).transpose() + a * (1 - c) * X.row(at(n, 0)).transpose() +
                  (1 - a) * c * X.row(at(0, n)).transpose() + a * c * X.row(at(n, n)).transpose());
        X.row(at(s, u)) = x.transpose();
        g.known[at(s, u)] = 1;
      }
    return;
  }
  std::vector<int> ids;
  std::map<std::pair<int, int>, int> pos;
  for (int u = 0; u <= n; ++u)
    for (int s = 0; s + u <= n; ++s) { pos[{s, u}] = static_cast<int>(ids.size()); ids.push_back(at(s, u)); }
  std::vector<std::vector<int>> nbrs(ids.size());
  for (const auto& [su, q] : pos)
    for (const auto& d : kTriNb) {
      auto it = pos.find({su.first + d[0], su.second + d[1]});
      if (it != pos.end()) nbrs[q].push_back(it->second);
    }
  harmonic_fill(g, ids, nbrs);
}

// Transfinite interpolation of a hex block's interior from its (known) boundary.
void hex_interior(GenerationState& g, int b) {
  const int n = g.n;
  const auto& L = g.lattice[b];
  Eigen::MatrixXd& X = g.X;
  auto x = [&](int i, int j, int k) -> Vec3 { return X.row(L[g.lidx(i, j, k)]).transpose(); };
  for (int k = 1; k < n; ++k)
    for (int j = 1; j < n; ++j)
      for (int i = 1; i < n; ++i) {
        const double s = static_cast<double>(i) / n, u = static_cast<double>(j) / n, v = static_cast<double>(k) / n;
        Vec3 f = (1 - s) * x(0, j, k) + s * x(n, j, k) + (1 - u) * x(i, 0, k) + u * x(i, n, k) + (1 - v) * x(i, j, 0) + v * x(i, j, n);
        Vec3 e = (1 - u) * (1 - v) * x(i, 0, 0) + u * (1 - v) * x(i, n, 0) + (1 - u) * v * x(i, 0, n) + u * v * x(i, n, n) +
                 (1 - s) * (1 - v) * x(0, j, 0) + s * (1 - v) * x(n, j, 0) + (1 - s) * v * x(0, j, n) + s * v * x(n, j, n) +
                 (1 - s) * (1 - u) * x(0, 0, k) + s * (1 - u) * x(n, 0, k) + (1 - s) * u * x(0, n, k) + s * u * x(n, n, k);
        Vec3 c = Vec3::Zero();
        for (int q = 0; q < 8; ++q) {
          const int* cc = kHexCorner[q];
          c += (cc[0] ? s : 1 - s) * (cc[1] ? u : 1 - u) * (cc[2] ? v : 1 - v) * x(cc[0] * n, cc[1] * n, cc[2] * n);
        }
        X.row(L[g.lidx(i, j, k)]) = (f - e + c).transpose();
        g.known[L[g.lidx(i, j, k)]] = 1;
      }
}

// Harmonic fill of a wedge or tet block's interior from its (known) boundary.
void simplex_interior(GenerationState& g, int b) {
  const CellType t = g.T.type(b);
  const int n = g.n, n1 = g.n1;
  const auto& L = g.lattice[b];
  std::vector<int> ids;
  std::vector<int> where(n1 * n1 * n1, -1);
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        if (in_lattice(t, n, i, j, k)) { where[g.lidx(i, j, k)] = static_cast<int>(ids.size()); ids.push_back(L[g.lidx(i, j, k)]); }
  std::vector<std::vector<int>> nbrs(ids.size());
  const int (*nb3)[3] = t == CellType::Wedge ? kWedgeNb : kTetNb;
  const int nnb = t == CellType::Wedge ? 8 : 12;
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        if (!in_lattice(t, n, i, j, k)) continue;
        for (int d = 0; d < nnb; ++d) {
          const int a = i + nb3[d][0], c = j + nb3[d][1], e = k + nb3[d][2];
          if (in_lattice(t, n, a, c, e)) nbrs[where[g.lidx(i, j, k)]].push_back(where[g.lidx(a, c, e)]);
        }
      }
  harmonic_fill(g, ids, nbrs);
}

}  // namespace

void fill_interior_faces(GenerationState& g) {
  std::set<std::vector<int>> done_faces;
  for (int b = 0; b < g.T.num_cells(); ++b) {
    auto [lf, nlf] = mesh::cell_faces(g.T.type(b));
    linear_start(g, b);
    for (int f = 0; f < nlf; ++f) {
      std::vector<int> vs;
      for (int i = 0; i < lf[f].n; ++i) vs.push_back(g.T.cells(b, lf[f].v[i]));
      std::sort(vs.begin(), vs.end());
      if (g.boundary_face_patch.count(vs) || !done_faces.insert(vs).second) continue;
      fill_face(g, b, lf[f]);
    }
  }
}

void fill_block_interiors(GenerationState& g) {
  // Each block writes only its own interior nodes and reads its (known) boundary: blocks run in
  // parallel.
  parallel_for(g.T.num_cells(), g.nthreads, [&](int b) {
    if (g.T.type(b) == CellType::Hex) hex_interior(g, b);
    else simplex_interior(g, b);
  });
}

}  // namespace hexdom::generation
