#include "hexdom/autopolycube/map/untangle_plane_map.h"

#include "hexdom/common/hash128.h"
#include "hexdom/common/kept_results.h"
#include "hexdom/common/interrupt.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <map>

namespace hexdom::autopolycube {

namespace {

// chi(d, eps) = (d + sqrt(eps^2 + d^2)) / 2: a smooth positive stand-in for max(d, 0).
double chi(double d, double eps) { return 0.5 * (d + std::sqrt(eps * eps + d * d)); }

struct Problem {
  std::vector<std::array<int, 3>> vid;    // per triangle: free index or -1 - fixed vertex index
  std::vector<Eigen::Matrix2d> dinv;      // inverse of the reference edge matrix
  std::vector<double> weight;             // reference area
  Eigen::MatrixX2d fixed;                 // positions of fixed vertices (by global index)
  double theta = 1.0 / 128;
  int b = 1, c = 2, sign = 1;
  mutable int evaluations = 0;            // calls of eval

  Eigen::Vector2d pos(const Eigen::VectorXd& x, int id) const {
    return id >= 0 ? Eigen::Vector2d(x(2 * id), x(2 * id + 1)) : Eigen::Vector2d(fixed.row(-1 - id).transpose());
  }
  Eigen::Matrix2d jacobian(const Eigen::VectorXd& x, size_t t) const {
    const Eigen::Vector2d p = pos(x, vid[t][0]);
    Eigen::Matrix2d U;
    U.col(0) = pos(x, vid[t][1]) - p;
    U.col(1) = pos(x, vid[t][2]) - p;
    return U * dinv[t];
  }
  // Energy and (optionally) its gradient; also the smallest determinant and the folded count.
  double eval(const Eigen::VectorXd& x, double eps, Eigen::VectorXd* grad, double* mindet, int* folded) const {
    double E = 0, md = 1e300;
    int nf = 0;
    ++evaluations;
    if (grad) grad->setZero(x.size());
    for (size_t t = 0; t < vid.size(); ++t) {
      const Eigen::Matrix2d J = jacobian(x, t);
      const double d = J.determinant();
      md = std::min(md, d);
      nf += d <= 0;
      const double r = std::sqrt(eps * eps + d * d);  // chi and its derivative share it
      const double ch = 0.5 * (d + r), tr = J.squaredNorm();
      E += weight[t] * ((1 - theta) * tr / ch + theta * (d * d + 1) / ch);
      if (!grad) continue;
      Eigen::Matrix2d cof;
      cof << J(1, 1), -J(1, 0), -J(0, 1), J(0, 0);
      const double cd = 0.5 * (1.0 + d / r);
      const Eigen::Matrix2d dJ = (1 - theta) * (2 * J / ch - tr / (ch * ch) * cd * cof) +
                                 theta * (2 * d / ch * cof - (d * d + 1) / (ch * ch) * cd * cof);
      const Eigen::Matrix2d dU = weight[t] * dJ * dinv[t].transpose();
      const Eigen::Vector2d g1 = dU.col(0), g2 = dU.col(1), g0 = -(g1 + g2);
      const Eigen::Vector2d g[3] = {g0, g1, g2};
      for (int k = 0; k < 3; ++k)
        if (vid[t][k] >= 0) {
          (*grad)(2 * vid[t][k]) += g[k](0);
          (*grad)(2 * vid[t][k] + 1) += g[k](1);
        }
    }
    if (mindet) *mindet = md;
    if (folded) *folded = nf;
    return E;
  }
};

// Limited-memory BFGS with a backtracking (Armijo) line search; the energy is +inf-free for eps > 0.
// Ends after `iterations` steps or at a step that lowers the energy by no more than `tolerance`
// times it. Returns the iterations whose step was taken.
int lbfgs(const Problem& P, Eigen::VectorXd& x, double eps, int iterations, double tolerance) {
  int taken = 0;
  const int m = 8;
  // The last m steps s and gradient changes y, with y . s; the vectors of a dropped pair are
  // reused for the next one, and every work vector is made once.
  std::deque<Eigen::VectorXd> S, Y;
  std::deque<double> YS;
  Eigen::VectorXd g, gn, q, dir, xn, s, y;
  std::vector<double> alpha;
  double E = P.eval(x, eps, &g, nullptr, nullptr);
  const double g0 = g.norm();
  for (int it = 0; it < iterations; ++it) {
    check_interrupt("autopolycube (chart maps)");
    if (g.norm() <= 1e-8 * std::max(g0, 1e-300)) break;
    // Two-loop recursion.
    q = g;
    alpha.assign(S.size(), 0.0);
    for (int i = static_cast<int>(S.size()) - 1; i >= 0; --i) {
      alpha[i] = S[i].dot(q) / YS[i];
      q -= alpha[i] * Y[i];
    }
    if (!S.empty()) q *= YS.back() / Y.back().squaredNorm();
    for (size_t i = 0; i < S.size(); ++i) {
      const double beta = Y[i].dot(q) / YS[i];
      q += (alpha[i] - beta) * S[i];
    }
    dir = -q;
    double slope = g.dot(dir);
    if (!(slope < 0)) {
      S.clear();
      Y.clear();
      YS.clear();
      dir = -g;
      slope = -g.squaredNorm();
    }
    double step = 1.0;
    if (S.empty()) step = std::min(1.0, 1.0 / std::max(g.norm(), 1e-300));
    double En = 0;
    bool ok = false, have_gradient = false;
    for (int ls = 0; ls < 40; ++ls) {
      xn = x + step * dir;
      // The first step is almost always taken: its gradient comes with its energy (the same numbers
      // as a separate evaluation), which saves one pass over the triangles per iteration.
      have_gradient = ls == 0;
      En = P.eval(xn, eps, have_gradient ? &gn : nullptr, nullptr, nullptr);
      if (std::isfinite(En) && En <= E + 1e-4 * step * slope) { ok = true; break; }
      step *= 0.5;
    }
    if (!ok) {
      if (S.empty()) break;
      S.clear();
      Y.clear();
      YS.clear();
      continue;
    }
    if (!have_gradient) P.eval(xn, eps, &gn, nullptr, nullptr);
    s = xn - x;
    y = gn - g;
    const double ys = s.dot(y);
    if (ys > 1e-12 * s.norm() * y.norm()) {
      Eigen::VectorXd so, yo;
      if (static_cast<int>(S.size()) == m) {  // the oldest pair goes; its vectors take the new one
        so = std::move(S.front());
        yo = std::move(Y.front());
        S.pop_front();
        Y.pop_front();
        YS.pop_front();
      }
      so = s;
      yo = y;
      S.push_back(std::move(so));
      Y.push_back(std::move(yo));
      YS.push_back(ys);
    }
    const double dE = E - En;
    ++taken;
    x.swap(xn);
    g.swap(gn);
    E = En;
    if (dE <= tolerance * std::abs(E)) break;
  }
  return taken;
}

// The untangling itself (untangle_plane_map without the memo).
UntangleResult untangle(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& tris,
                        const std::vector<char>& free_vertex, int axis, int sign, Eigen::MatrixXd& D, const UntangleOptions& opt) {
  UntangleResult r;
  Problem P;
  P.theta = opt.theta;
  P.b = (axis + 1) % 3;
  P.c = (axis + 2) % 3;
  P.sign = sign;
  // Target coordinates (D_b, sign * D_c): positive orientation there is the right one.
  std::vector<int> index(V.rows(), -1);
  std::vector<int> freev;
  P.fixed.resize(V.rows(), 2);
  double target_area = 0, ref_area = 0;
  for (int f : tris) {
    std::array<int, 3> id{};
    for (int k = 0; k < 3; ++k) {
      const int v = F(f, k);
      P.fixed(v, 0) = D(v, P.b);
      P.fixed(v, 1) = sign * D(v, P.c);
      if (free_vertex[v]) {
        if (index[v] < 0) { index[v] = static_cast<int>(freev.size()); freev.push_back(v); }
        id[k] = index[v];
      } else {
        id[k] = -1 - v;
      }
    }
    P.vid.push_back(id);
    const Eigen::Vector2d p(P.fixed(F(f, 0), 0), P.fixed(F(f, 0), 1)), q(P.fixed(F(f, 1), 0), P.fixed(F(f, 1), 1)),
        s(P.fixed(F(f, 2), 0), P.fixed(F(f, 2), 1));
    target_area += 0.5 * ((q - p)(0) * (s - p)(1) - (q - p)(1) * (s - p)(0));
    const Eigen::Vector3d e1 = V.row(F(f, 1)) - V.row(F(f, 0)), e2 = V.row(F(f, 2)) - V.row(F(f, 0));
    ref_area += 0.5 * e1.cross(e2).norm();
  }
  if (tris.empty()) return r;
  Eigen::VectorXd x(2 * freev.size());
  for (size_t i = 0; i < freev.size(); ++i) { x(2 * i) = P.fixed(freev[i], 0); x(2 * i + 1) = P.fixed(freev[i], 1); }
  // Reference triangles: the input's shapes, scaled to the polygon's area; degenerate ones become
  // equilateral triangles of the mean area.
  const double scale = std::sqrt(std::max(target_area, 1e-300) / std::max(ref_area, 1e-300));
  const double mean_area = std::max(target_area, 1e-300) / static_cast<double>(tris.size());
  for (int f : tris) {
    Eigen::Vector3d e1 = scale * (V.row(F(f, 1)) - V.row(F(f, 0))).transpose();
    Eigen::Vector3d e2 = scale * (V.row(F(f, 2)) - V.row(F(f, 0))).transpose();
    double area = 0.5 * e1.cross(e2).norm();
    Eigen::Matrix2d R;
    if (area < 1e-6 * mean_area || e1.norm() == 0) {
      const double l = std::sqrt(4 * mean_area / std::sqrt(3.0));
      R << l, 0.5 * l, 0, 0.5 * std::sqrt(3.0) * l;
      area = mean_area;
    } else {
      const double l1 = e1.norm();
      R << l1, e1.dot(e2) / l1, 0, 2 * area / l1;
    }
    P.dinv.push_back(R.inverse());
    P.weight.push_back(area);
  }
  double mindet = 0;
  int folded = 0;
  P.eval(x, 1.0, nullptr, &mindet, &folded);
  r.folded_before = folded;
  if (x.size() == 0) { r.folded_after = folded; return r; }
  double eps = std::sqrt(1e-12 + 0.04 * std::pow(std::min(mindet, 0.0), 2));
  eps = std::max(eps, 1e-6);
  Eigen::VectorXd best = x;
  int best_folded = folded;
  for (int round = 0; round < opt.outer; ++round) {
    opt.deadline.check("autopolycube (chart maps)");
    r.rounds = round + 1;
    const double E_prev = P.eval(x, eps, nullptr, nullptr, nullptr);
    r.iterations += lbfgs(P, x, eps, opt.inner, opt.step_tolerance);
    const double E = P.eval(x, eps, nullptr, &mindet, &folded);
    if (folded < best_folded || (folded == 0)) { best = x; best_folded = folded; }
    const double sigma = std::max(1.0 - E / E_prev, 0.1);
    const double mu = (1 - sigma) * chi(mindet, eps);
    eps = mindet < mu ? 2 * std::sqrt(mu * (mu - mindet)) : 1e-10;
    if (folded == 0 && E > (1 - 1e-3) * E_prev) break;
  }
  for (size_t i = 0; i < freev.size(); ++i) {
    D(freev[i], P.b) = best(2 * i);
    D(freev[i], P.c) = sign * best(2 * i + 1);
  }
  r.folded_after = best_folded;
  r.evaluations = P.evaluations;
  for (size_t t = 0; t < P.vid.size(); ++t)
    if (P.vid[t][0] < 0 && P.vid[t][1] < 0 && P.vid[t][2] < 0 && P.jacobian(best, t).determinant() <= 0) ++r.folded_fixed;
  return r;
}

// A hash of every input untangle() reads.
using Key = Hash128;

Key key_of(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& tris, const std::vector<char>& free_vertex,
           int axis, int sign, const Eigen::MatrixXd& D, const UntangleOptions& opt) {
  Key k;
  for (double x : {double(axis), double(sign), double(opt.outer), double(opt.inner), opt.theta, opt.step_tolerance, double(tris.size())})
    k.add(x);
  const int b = (axis + 1) % 3, c = (axis + 2) % 3;
  for (int f : tris)
    for (int i = 0; i < 3; ++i) {
      const int v = F(f, i);
      for (double x : {double(v), double(free_vertex[v] != 0), V(v, 0), V(v, 1), V(v, 2), D(v, b), D(v, c)}) k.add(x);
    }
  return k;
}

// What an untangling gave: the free vertices' new coordinates in the plane, and its result.
struct Untangled {
  std::vector<std::array<double, 3>> moves;  // vertex, D(v, b), D(v, c)
  UntangleResult result;
};

// The results kept, the oldest dropped beyond about 24 MB of moves in all.
KeptResults<Untangled>& memo() {
  static KeptResults<Untangled> m(size_t(1) << 20, [](const Untangled& u) { return u.moves.size(); });
  return m;
}

}  // namespace

UntangleResult untangle_plane_map(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& tris,
                                  const std::vector<char>& free_vertex, int axis, int sign, Eigen::MatrixXd& D,
                                  const UntangleOptions& opt) {
  opt.deadline.check("autopolycube (chart maps)");
  const Key k = key_of(V, F, tris, free_vertex, axis, sign, D, opt);
  const int b = (axis + 1) % 3, c = (axis + 2) % 3;
  Untangled u;
  if (memo().find(k, &u)) {
    for (const auto& [v, x, y] : u.moves) D(static_cast<int>(v), b) = x, D(static_cast<int>(v), c) = y;
    return u.result;
  }
  u.result = untangle(V, F, tris, free_vertex, axis, sign, D, opt);
  std::vector<char> seen(V.rows(), 0);
  for (int f : tris)
    for (int i = 0; i < 3; ++i) {
      const int v = F(f, i);
      if (free_vertex[v] && !seen[v]) {
        seen[v] = 1;
        u.moves.push_back({double(v), D(v, b), D(v, c)});
      }
    }
  const UntangleResult r = u.result;
  memo().keep(k, std::move(u));
  return r;
}

}  // namespace hexdom::autopolycube
