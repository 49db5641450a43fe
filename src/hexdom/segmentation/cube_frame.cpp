#include "hexdom/segmentation/cube_frame.h"

#include "hexdom/common/hash128.h"
#include "hexdom/common/kept_results.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace hexdom::segmentation {

namespace {

constexpr int kSharpExponents[] = {16, 64};

// Unit normals and areas of the triangles (zero-area triangles are left out), triangles of one
// normal (to about 1e-9: a planar face's) merged into one entry with their summed area, so that
// the fits below cost per distinct normal, not per triangle.
struct Normals {
  std::vector<Eigen::Vector3d> n;
  std::vector<double> area;
  std::vector<int> count;  ///< triangles merged into each entry
  double total = 0;
};

// The same normals with the entries of three triangles or more (planar faces: a curved face's
// triangles have normals of their own) weighted `weight` times their area.
Normals planar_weighted(const Normals& ns, double weight) {
  Normals out = ns;
  out.total = 0;
  for (size_t i = 0; i < out.n.size(); ++i) {
    if (out.count[i] >= 3) out.area[i] *= weight;
    out.total += out.area[i];
  }
  return out;
}

Normals normals_of(const mesh::SurfaceMesh& s) {
  struct Key {
    int64_t x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct Hash {
    size_t operator()(const Key& k) const {
      return std::hash<int64_t>()(k.x) ^ (std::hash<int64_t>()(k.y) * 0x9e3779b97f4a7c15ULL) ^ (std::hash<int64_t>()(k.z) << 1);
    }
  };
  std::unordered_map<Key, int, Hash> index;
  std::vector<Eigen::Vector3d> sum;  // area-weighted normals of each entry
  Normals out;
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    const Eigen::Vector3d x = (b - a).cross(c - a);
    const double twice = x.norm();
    if (!(twice > 0)) continue;
    const Eigen::Vector3d n = x / twice;
    const Key key{std::llround(n.x() * 1e9), std::llround(n.y() * 1e9), std::llround(n.z() * 1e9)};
    auto [it, added] = index.emplace(key, static_cast<int>(sum.size()));
    if (added) {
      sum.push_back(Eigen::Vector3d::Zero());
      out.area.push_back(0);
      out.count.push_back(0);
    }
    ++out.count[it->second];
    sum[it->second] += 0.5 * x;
    out.area[it->second] += 0.5 * twice;
    out.total += 0.5 * twice;
  }
  out.n.reserve(sum.size());
  for (const Eigen::Vector3d& m : sum) out.n.push_back(m.normalized());
  return out;
}

// x^k for k >= 0 by squaring (std::pow costs several times more in the fits' inner loop).
double int_pow(double x, int k) {
  double r = 1;
  for (; k > 0; k >>= 1, x *= x)
    if (k & 1) r *= x;
  return r;
}

// Fit of R with exponent p (even): the area-weighted mean of sum_k (R n)_k^p, and, when `gradient` is
// given, its gradient with respect to a small rotation w applied after R (R -> exp([w]x) R):
// p sum A (m x m^(p-1)) / sum A, m = R n. p = 4 is cube_fit; a higher p rewards faces lying exactly
// along an axis far more than faces near one.
double fit_of(const Normals& ns, const Eigen::Matrix3d& R, Eigen::Vector3d* gradient, int p = 4) {
  double e = 0;
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < ns.n.size(); ++i) {
    const Eigen::Vector3d m = R * ns.n[i];
    const Eigen::Vector3d c = p == 4 ? Eigen::Vector3d(m.array().cube().matrix())
                                      : Eigen::Vector3d(int_pow(m.x(), p - 1), int_pow(m.y(), p - 1), int_pow(m.z(), p - 1));
    e += ns.area[i] * m.dot(c);
    if (gradient) g += ns.area[i] * m.cross(c);
  }
  if (gradient) *gradient = p * g / ns.total;
  return e / ns.total;
}

Eigen::Matrix3d exp_rotation(const Eigen::Vector3d& w) {
  const double a = w.norm();
  if (a < 1e-300) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(a, w / a).toRotationMatrix();
}

// Gradient ascent from R with a step that doubles after an accepted move and halves after a
// refused one. Returns the fit reached; R is updated.
double ascend(const Normals& ns, Eigen::Matrix3d& R, int iterations, int p = 4) {
  Eigen::Vector3d g;
  double e = fit_of(ns, R, &g, p), step = 1.0 / p;
  for (int it = 0; it < iterations && g.norm() > 1e-12; ++it) {
    bool moved = false;
    for (int tries = 0; tries < 30; ++tries) {
      const Eigen::Matrix3d T = exp_rotation(step * g) * R;
      Eigen::Vector3d gt;
      const double et = fit_of(ns, T, &gt, p);
      if (et > e) {
        R = T;
        e = et;
        g = gt;
        step *= 2.0;
        moved = true;
        break;
      }
      step *= 0.5;
    }
    if (!moved) break;
  }
  return e;
}

// The frame that best turns the triangles already within about 0.1 degree of an axis exactly onto
// it (orthogonal Procrustes, area-weighted): the ascent stops within about 1e-7 of the peak, which
// two tessellations of one part reach differently; this makes the frame of planar faces exact.
// Left as it is unless those normals span at least two axes.
void polish(const Normals& ns, Eigen::Matrix3d& R) {
  for (int round = 0; round < 3; ++round) {
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    for (size_t i = 0; i < ns.n.size(); ++i) {
      const Eigen::Vector3d m = R * ns.n[i];
      int k;
      const double c = m.cwiseAbs().maxCoeff(&k);
      if (c < 1.0 - 2e-6) continue;
      Eigen::Vector3d a = Eigen::Vector3d::Zero();
      a(k) = m(k) > 0 ? 1.0 : -1.0;
      M += ns.area[i] * a * ns.n[i].transpose();
    }
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Vector3d s = svd.singularValues();
    if (!(s(1) > 1e-9 * s(0))) return;
    Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
    D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
    R = svd.matrixU() * D * svd.matrixV().transpose();
  }
}

// The 24 rotations of a cube: signed permutation matrices of determinant +1.
std::vector<Eigen::Matrix3d> cube_rotations() {
  std::vector<Eigen::Matrix3d> out;
  const std::array<std::array<int, 3>, 6> perms{{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (const auto& p : perms)
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
      for (int r = 0; r < 3; ++r) S(r, p[r]) = (signs >> r) & 1 ? -1.0 : 1.0;
      if (S.determinant() > 0) out.push_back(S);
    }
  return out;
}

// Starting rotations spread evenly over the rotation group (super-Fibonacci spiral of unit
// quaternions, Alexa 2022).
std::vector<Eigen::Matrix3d> spread_rotations(int n) {
  std::vector<Eigen::Matrix3d> out;
  const double phi = std::sqrt(2.0), psi = 1.533751168755204288118041;
  for (int i = 0; i < n; ++i) {
    const double s = i + 0.5, r = std::sqrt(s / n), R = std::sqrt(1.0 - s / n);
    const double alpha = 2.0 * M_PI * s / phi, beta = 2.0 * M_PI * s / psi;
    const Eigen::Quaterniond q(R * std::cos(beta), r * std::sin(alpha), r * std::cos(alpha), R * std::sin(beta));
    out.push_back(q.normalized().toRotationMatrix());
  }
  return out;
}

}  // namespace

double cube_fit(const mesh::SurfaceMesh& surface, const Eigen::Matrix3d& rotation) {
  const Normals ns = normals_of(surface);
  return ns.total > 0 ? fit_of(ns, rotation, nullptr) : 0.0;
}

namespace {

// The frame of the merged normals `raw` (normals_of), uncached.
CubeFrame frame_of_normals(const Normals& raw, const CubeFrameOptions& opt) {
  CubeFrame out;
  const Normals ns = planar_weighted(raw, std::max(1.0, opt.planar_weight));
  if (!(ns.total > 0)) return out;
  out.fit_identity = out.fit = fit_of(ns, Eigen::Matrix3d::Identity(), nullptr);
  // A few steps from every start, then the best few ascended to the end.
  std::vector<std::pair<double, Eigen::Matrix3d>> runs;
  std::vector<Eigen::Matrix3d> starts{Eigen::Matrix3d::Identity()};
  for (const auto& R : spread_rotations(std::max(0, opt.starts))) starts.push_back(R);
  for (Eigen::Matrix3d R : starts) {
    const double e = ascend(ns, R, 5);
    runs.emplace_back(-e, R);
  }
  std::stable_sort(runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  double best = -1;
  Eigen::Matrix3d best_R = Eigen::Matrix3d::Identity();
  for (size_t i = 0; i < runs.size() && i < 6; ++i) {
    Eigen::Matrix3d R = runs[i].second;
    const double e = ascend(ns, R, opt.iterations);
    if (e > best) { best = e; best_R = R; }
  }
  // Then with a sharp exponent from there: faces square to the frame win over the compromise the
  // fourth powers strike with faces at an angle (a tilted bore can pull it degrees off a plate;
  // docs/tuning-notes.md).
  for (int p : kSharpExponents) ascend(ns, best_R, opt.iterations, p);
  polish(ns, best_R);
  best = fit_of(ns, best_R, nullptr);
  if (best - out.fit_identity <= opt.min_gain) return out;
  // The equivalent rotation (a cube's symmetry applied after it) with the smallest angle.
  Eigen::Matrix3d chosen = best_R;
  for (const auto& S : cube_rotations()) {
    const Eigen::Matrix3d T = S * best_R;
    if (T.trace() > chosen.trace() + 1e-12) chosen = T;
  }
  // Re-orthonormalise (products of many small rotations drift by rounding).
  Eigen::Quaterniond q(chosen);
  q.normalize();
  const CubeFrame turned = frame_of(q.toRotationMatrix());
  out.rotation = turned.rotation;
  out.angle_degrees = turned.angle_degrees;
  out.axis = turned.axis;
  out.fit = fit_of(ns, out.rotation, nullptr);
  return out;
}

// A hash of the merged normals and the options.
using FrameKey = Hash128;

FrameKey key_of(const Normals& ns, const CubeFrameOptions& opt) {
  FrameKey k;
  for (double x : {opt.min_gain, opt.planar_weight, double(opt.starts), double(opt.iterations), ns.total, double(ns.n.size())})
    k.add(x);
  for (size_t i = 0; i < ns.n.size(); ++i)
    for (double x : {ns.n[i](0), ns.n[i](1), ns.n[i](2), ns.area[i], double(ns.count[i])}) k.add(x);
  return k;
}

// The last 16 frames computed (the pipeline asks for the same surface's frame in the tessellation,
// the polycube path and the overlay path).
KeptResults<CubeFrame>& frame_memo() {
  static KeptResults<CubeFrame> m(16);
  return m;
}

}  // namespace

CubeFrame cube_frame(const mesh::SurfaceMesh& surface, const CubeFrameOptions& opt) {
  const Normals raw = normals_of(surface);
  const FrameKey k = key_of(raw, opt);
  CubeFrame out;
  if (frame_memo().find(k, &out)) return out;
  out = frame_of_normals(raw, opt);
  frame_memo().keep(k, out);
  return out;
}

CubeFrame frame_of(const Eigen::Matrix3d& rotation) {
  CubeFrame f;
  f.rotation = rotation;
  if (rotation == Eigen::Matrix3d::Identity()) return f;
  const Eigen::AngleAxisd aa(rotation);
  f.angle_degrees = aa.angle() * 180.0 / M_PI;
  f.axis = aa.axis();
  return f;
}

double frame_diagonal(const mesh::SurfaceMesh& surface, const Eigen::Matrix3d& rotation) {
  if (surface.V.rows() == 0) return 0.0;
  const Eigen::MatrixXd V = surface.V * rotation.transpose();
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

mesh::SurfaceMesh rotated(const mesh::SurfaceMesh& surface, const Eigen::Matrix3d& rotation) {
  mesh::SurfaceMesh out = surface;
  out.V = surface.V * rotation.transpose();
  return out;
}

}  // namespace hexdom::segmentation
