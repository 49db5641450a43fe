#include "hexdom/autopolycube/blocks/cut_along_grid.h"

#include <cmath>
#include <vector>

namespace hexdom::autopolycube {

namespace {

struct PV {
  int id;
  Eigen::Vector3d d;  // grid units
};
struct Support {
  bool cut;  // false: edge `val` (0..2) of the input triangle; true: the cut along line `val` of the first in-plane axis
  int val;
};
struct Poly {
  std::vector<PV> v;
  std::vector<Support> sup;  // per edge v[i] -> v[i+1]
};

/// The vertex of `poly` to fan it from: the one whose fan has the largest smallest area (in the plane
/// of axes ax[0], ax[1], facing sg).
int fan_apex(const Poly& poly, const int ax[2], int sg) {
  const int n = static_cast<int>(poly.v.size());
  auto area = [&](int i, int j, int l) {
    const Eigen::Vector3d& p = poly.v[i].d;
    const Eigen::Vector3d& q = poly.v[j].d;
    const Eigen::Vector3d& r = poly.v[l].d;
    return sg * ((q(ax[0]) - p(ax[0])) * (r(ax[1]) - p(ax[1])) - (r(ax[0]) - p(ax[0])) * (q(ax[1]) - p(ax[1])));
  };
  int best = 0;
  double best_min = -1e300;
  for (int r = 0; r < n; ++r) {
    double mn = 1e300;
    for (int q = 1; q + 1 < n; ++q) mn = std::min(mn, area(r, (r + q) % n, (r + q + 1) % n));
    if (mn > best_min) { best_min = mn; best = r; }
    if (n == 3) break;
  }
  return best;
}

/// The cut surface of vertices at outX (polycube positions outD), triangles `tris` with patch ids
/// `patch`, and its grid points.
GridCut assemble_cut(const std::vector<Eigen::Vector3d>& outD, const std::vector<Eigen::Vector3d>& outX,
                     const std::vector<std::array<int, 3>>& tris, const std::vector<int>& patch) {
  GridCut out;
  const int nout = static_cast<int>(outD.size());
  out.patches.V.resize(nout, 3);
  out.D.resize(nout, 3);
  for (int v = 0; v < nout; ++v) {
    out.patches.V.row(v) = outX[v].transpose();
    out.D.row(v) = outD[v].transpose();
  }
  out.patches.F.resize(static_cast<int>(tris.size()), 3);
  out.patches.patch.resize(static_cast<int>(tris.size()));
  for (size_t t = 0; t < tris.size(); ++t) {
    for (int k = 0; k < 3; ++k) out.patches.F(t, k) = tris[t][k];
    out.patches.patch(t) = patch[t];
  }
  for (int v = 0; v < nout; ++v) {
    const Eigen::Vector3d& d = outD[v];
    if (d(0) != std::round(d(0)) || d(1) != std::round(d(1)) || d(2) != std::round(d(2))) continue;
    const std::array<int, 3> key{static_cast<int>(d(0)), static_cast<int>(d(1)), static_cast<int>(d(2))};
    auto [it, fresh] = out.grid_vertex.emplace(key, v);
    if (!fresh)
      throw MeshingError("cutting along the grid: vertices " + std::to_string(it->second + 1) + " and " + std::to_string(v + 1) +
                         " both lie on grid point (" + std::to_string(key[0]) + ", " + std::to_string(key[1]) + ", " +
                         std::to_string(key[2]) + ") of the polycube, at (" + std::to_string(outX[it->second](0)) + ", " +
                         std::to_string(outX[it->second](1)) + ", " + std::to_string(outX[it->second](2)) + ") and (" +
                         std::to_string(outX[v](0)) + ", " + std::to_string(outX[v](1)) + ", " + std::to_string(outX[v](2)) + ")");
  }
  return out;
}

}  // namespace

GridCut cut_along_grid(const mesh::SurfaceMesh& s, const ChartGraph& g, const PolycubeMap& m, const PolycubeGrid& grid) {
  const int nv = static_cast<int>(s.V.rows()), nf = static_cast<int>(s.F.rows());
  // A vertex a hair off a grid line (1e-3 of a grid step) is put on it (only its polycube position,
  // which decides where cuts run): cutting there would leave a speck of a triangle (edges 5e-5 mm,
  // area 1e-9 mm^2 on bracket.step) that the polycube check calls degenerate.
  Eigen::MatrixXd D = m.D;
  for (Eigen::Index i = 0; i < D.size(); ++i) {
    const double r = std::round(D.data()[i]);
    if (std::abs(D.data()[i] - r) < 1e-3) D.data()[i] = r;
  }
  std::vector<Eigen::Vector3d> outD, outX;
  outD.reserve(2 * nv);
  outX.reserve(2 * nv);
  for (int v = 0; v < nv; ++v) {
    outD.push_back(D.row(v).transpose());
    outX.push_back(s.V.row(v).transpose());
  }
  std::map<std::array<int, 4>, int> on_edge;    // (p < q, axis, line) -> vertex
  std::map<std::array<int, 3>, int> in_tri;     // (triangle, line b, line c) -> vertex
  std::vector<std::array<int, 3>> tris;
  std::vector<int> patch;

  for (int f = 0; f < nf; ++f) {
    const int c = g.region(f), a = (g.label[c] - 1) / 2, ax[2] = {(a + 1) % 3, (a + 2) % 3};
    const int sg = g.label[c] % 2 == 1 ? 1 : -1;
    int P[3] = {s.F(f, 0), s.F(f, 1), s.F(f, 2)};
    std::vector<Poly> pieces(1);
    for (int k = 0; k < 3; ++k) {
      pieces[0].v.push_back({P[k], outD[P[k]]});
      pieces[0].sup.push_back({false, k});
    }
    // Point where edge i of `poly` crosses plane x_k = L.
    auto crossing = [&](const Poly& poly, size_t i, int k, int L) -> PV {
      const PV& u = poly.v[i];
      const PV& w = poly.v[(i + 1) % poly.v.size()];
      const Support sp = poly.sup[i];
      if (!sp.cut) {
        int p = P[sp.val], q = P[(sp.val + 1) % 3];
        if (p > q) std::swap(p, q);
        const std::array<int, 4> key{p, q, k, L};
        auto it = on_edge.find(key);
        if (it != on_edge.end()) return {it->second, outD[it->second]};
        const double t = (L - D(p, k)) / (D(q, k) - D(p, k));
        Eigen::Vector3d d = D.row(p).transpose() + t * (D.row(q) - D.row(p)).transpose();
        d(k) = L;
        // An edge through a grid point (regular meshes of planar faces have them): the crossing is the
        // grid point itself, so that the other axis' line finds it on the line rather than a hair away.
        for (int o = 0; o < 3; ++o)
          if (o != k && std::abs(d(o) - std::round(d(o))) < 1e-9) d(o) = std::round(d(o));
        const Eigen::Vector3d x = s.V.row(p).transpose() + t * (s.V.row(q) - s.V.row(p)).transpose();
        const int id = static_cast<int>(outD.size());
        outD.push_back(d);
        outX.push_back(x);
        on_edge[key] = id;
        return {id, d};
      }
      // On the cut along the first in-plane axis, inside this triangle.
      const int first_line = sp.val;
      const std::array<int, 3> key{f, first_line, L};
      auto it = in_tri.find(key);
      if (it != in_tri.end()) return {it->second, outD[it->second]};
      const double t = (L - u.d(k)) / (w.d(k) - u.d(k));
      Eigen::Vector3d d = u.d + t * (w.d - u.d);
      d(k) = L;
      d(ax[0]) = first_line;
      const Eigen::Vector3d x = outX[u.id] + t * (outX[w.id] - outX[u.id]);
      const int id = static_cast<int>(outD.size());
      outD.push_back(d);
      outX.push_back(x);
      in_tri[key] = id;
      return {id, d};
    };
    for (int stage = 0; stage < 2; ++stage) {
      const int k = ax[stage];
      double lo = outD[P[0]](k), hi = lo;
      for (int q = 1; q < 3; ++q) { lo = std::min(lo, outD[P[q]](k)); hi = std::max(hi, outD[P[q]](k)); }
      for (int L = static_cast<int>(std::floor(lo)) + 1; L < hi; ++L) {
        if (L <= lo) continue;
        std::vector<Poly> next;
        for (const Poly& poly : pieces) {
          const size_t n = poly.v.size();
          bool neg = false, pos = false;
          for (const auto& x : poly.v) { neg |= x.d(k) < L; pos |= x.d(k) > L; }
          if (!neg || !pos) { next.push_back(poly); continue; }
          Poly A, B;  // below and above the line
          for (size_t i = 0; i < n; ++i) {
            const PV& u = poly.v[i];
            const PV& w = poly.v[(i + 1) % n];
            const double su = u.d(k) - L, sw = w.d(k) - L;
            if (su <= 0) { A.v.push_back(u); A.sup.push_back(poly.sup[i]); }
            if (su >= 0) { B.v.push_back(u); B.sup.push_back(poly.sup[i]); }
            if ((su < 0 && sw > 0) || (su > 0 && sw < 0)) {
              const PV x = crossing(poly, i, k, L);
              A.v.push_back(x); A.sup.push_back(poly.sup[i]);
              B.v.push_back(x); B.sup.push_back(poly.sup[i]);
            }
          }
          // The edge joining the two points on the line is the cut.
          for (Poly* Q : {&A, &B}) {
            const size_t m2 = Q->v.size();
            for (size_t i = 0; i < m2; ++i)
              if (Q->v[i].d(k) == L && Q->v[(i + 1) % m2].d(k) == L) Q->sup[i] = {true, L};
            if (m2 >= 3) next.push_back(std::move(*Q));
          }
        }
        pieces = std::move(next);
      }
    }
    (void)sg;
    for (const Poly& poly : pieces) {
      const int n = static_cast<int>(poly.v.size());
      Eigen::Vector3d cen = Eigen::Vector3d::Zero();
      for (const auto& x : poly.v) cen += x.d;
      cen /= n;
      // The piece lies in [i, i+1] x [j, j+1]: i and j are the floors of its smallest coordinates.
      double lo0 = 1e300, lo1 = 1e300;
      for (const auto& x : poly.v) { lo0 = std::min(lo0, x.d(ax[0])); lo1 = std::min(lo1, x.d(ax[1])); }
      const int plane = static_cast<int>(std::lround(cen(a)));
      const std::array<int, 4> key{a, plane, static_cast<int>(std::floor(lo0)), static_cast<int>(std::floor(lo1))};
      auto it = grid.square_of.find(key);
      if (it == grid.square_of.end())
        throw MeshingError("cutting along the grid: triangle " + std::to_string(f + 1) + " of " + chart_name(g, c) +
                           " falls outside the polycube's squares (piece centre " + std::to_string(cen(0)) + ", " +
                           std::to_string(cen(1)) + ", " + std::to_string(cen(2)) + ")");
      const int best = fan_apex(poly, ax, sg);
      for (int q = 1; q + 1 < n; ++q) {
        tris.push_back({poly.v[best].id, poly.v[(best + q) % n].id, poly.v[(best + q + 1) % n].id});
        patch.push_back(it->second + 1);
      }
    }
  }

  return assemble_cut(outD, outX, tris, patch);
}

}  // namespace hexdom::autopolycube
