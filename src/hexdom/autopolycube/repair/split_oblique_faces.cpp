#include "hexdom/autopolycube/repair/split_oblique_faces.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "hexdom/autopolycube/repair/cut_triangles.h"
#include "hexdom/common/format.h"
#include "hexdom/segmentation/axis_labels.h"
#include "hexdom/mesh/triangle_adjacency.h"

namespace hexdom::autopolycube {

namespace {

constexpr double kDeg = M_PI / 180.0;

// The surface as lists that grow: triangles, their labels and the flat region each belongs to.
struct Soup {
  std::vector<Eigen::RowVector3d> V;
  std::vector<std::array<int, 3>> F;
  std::vector<int> label, region;
};

// A face found: its region, its corners (vertex ids), the labels of its quads, its normal.
struct Found {
  int region = -1;
  std::array<int, 3> corners{};
  std::array<int, 3> labels{};
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
};

Eigen::Vector3d normal_of(const Soup& s, int t) {
  const Eigen::Vector3d a = s.V[s.F[t][0]], b = s.V[s.F[t][1]], c = s.V[s.F[t][2]];
  return (b - a).cross(c - a);
}

double angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Splits edge (a, b) at point p in every triangle that has it (the face's and the one beyond).
void split_edge(Soup& s, int a, int b, const Eigen::RowVector3d& p) {
  const int m = static_cast<int>(s.V.size());
  s.V.push_back(p);
  const int n = static_cast<int>(s.F.size());
  for (int t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) {
      const int x = s.F[t][k], y = s.F[t][(k + 1) % 3], z = s.F[t][(k + 2) % 3];
      if (!((x == a && y == b) || (x == b && y == a))) continue;
      s.F[t] = {x, m, z};
      s.F.push_back({m, y, z});
      s.label.push_back(s.label[t]);
      s.region.push_back(s.region[t]);
      break;
    }
}

// Checks that region r is an oblique triangular face (see ObliqueFaceOptions); fills `out`.
bool classify(const Soup& s, const Eigen::MatrixXi& TT, int r, const std::vector<int>& tris, const ObliqueFaceOptions& opt,
              Found& out, std::string& why) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (int t : tris) n += normal_of(s, t);
  n.normalize();
  const double cos_axis = std::cos(opt.min_axis_angle * kDeg);
  if (n.cwiseAbs().maxCoeff() > cos_axis || n.cwiseAbs().minCoeff() < opt.min_component) return false;
  // The boundary: one loop of crease edges.
  std::map<int, int> next;
  std::map<std::pair<int, int>, int> beyond;  // directed boundary edge -> triangle beyond it
  for (int t : tris)
    for (int k = 0; k < 3; ++k) {
      const int u = TT(t, k);
      if (u >= 0 && s.region[u] == r) continue;
      const int a = s.F[t][k], b = s.F[t][(k + 1) % 3];
      if (u < 0 || angle(normal_of(s, t), normal_of(s, u)) < opt.min_crease * kDeg) return false;  // not a face
      if (!next.emplace(a, b).second) { why = "its boundary touches itself"; return false; }
      beyond[{a, b}] = u;
    }
  if (next.empty()) return false;
  std::vector<int> loop{next.begin()->first};
  while (loop.size() <= next.size()) {
    auto it = next.find(loop.back());
    if (it == next.end()) { why = "its boundary is open"; return false; }
    if (it->second == loop.front()) break;
    loop.push_back(it->second);
  }
  if (loop.size() != next.size()) { why = "its boundary is several loops"; return false; }
  const int m = static_cast<int>(loop.size());
  auto tangent = [&](const Eigen::Vector3d& d) { return (d - d.dot(n) * n).normalized(); };
  std::vector<int> corner_at;
  for (int i = 0; i < m; ++i) {
    const Eigen::Vector3d p = s.V[loop[(i + m - 1) % m]], q = s.V[loop[i]], w = s.V[loop[(i + 1) % m]];
    if (angle(tangent(q - p), tangent(w - q)) > opt.corner_angle * kDeg) corner_at.push_back(i);
  }
  if (corner_at.size() != 3) { why = std::to_string(corner_at.size()) + " corners"; return false; }
  // Each side's neighbour label: the one beyond the longest share of it.
  std::array<int, 3> side_label{};
  for (int k = 0; k < 3; ++k) {
    std::map<int, double> length;
    double total = 0;
    for (int i = corner_at[k]; i != corner_at[(k + 1) % 3]; i = (i + 1) % m) {
      const int a = loop[i], b = loop[(i + 1) % m];
      const double l = (s.V[b] - s.V[a]).norm();
      length[s.label[beyond.at({a, b})]] += l;
      total += l;
    }
    if (total < opt.min_side) { why = fmt("a side of length %.3g", total); return false; }
    side_label[k] = std::max_element(length.begin(), length.end(), [](auto& x, auto& y) { return x.second < y.second; })->first;
  }
  bool axes[3] = {false, false, false};
  for (int l : side_label) axes[(l - 1) / 2] = true;
  if (!(axes[0] && axes[1] && axes[2])) { why = "its neighbours do not carry one label of each axis"; return false; }
  out.region = r;
  out.n = n;
  for (int k = 0; k < 3; ++k) {
    out.corners[k] = loop[corner_at[k]];
    // Side k runs from corner k to corner k + 1: the side opposite corner k is side k + 1.
    const int axis = (side_label[(k + 1) % 3] - 1) / 2;
    out.labels[k] = 1 + 2 * axis + (n[axis] > 0 ? 0 : 1);
  }
  return true;
}

}  // namespace

std::vector<ObliqueFace> split_oblique_faces(mesh::SurfaceMesh& labels, const ObliqueFaceOptions& opt) {
  auto log = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  Soup s;
  const int nf0 = static_cast<int>(labels.F.rows());
  for (int v = 0; v < labels.V.rows(); ++v) s.V.push_back(labels.V.row(v));
  for (int f = 0; f < nf0; ++f) {
    s.F.push_back({labels.F(f, 0), labels.F(f, 1), labels.F(f, 2)});
    s.label.push_back(labels.patch(f));
  }
  s.region.assign(nf0, -1);

  // Flat regions: triangles joined across edges that barely bend, near the first one's normal.
  const Eigen::MatrixXi TT0 = mesh::triangle_adjacency(labels.F);
  std::vector<std::vector<int>> regions;
  for (int f = 0; f < nf0; ++f) {
    if (s.region[f] >= 0) continue;
    const int r = static_cast<int>(regions.size());
    const Eigen::Vector3d seed = normal_of(s, f);
    regions.push_back({f});
    s.region[f] = r;
    for (size_t i = 0; i < regions[r].size(); ++i) {
      const int t = regions[r][i];
      for (int k = 0; k < 3; ++k) {
        const int u = TT0(t, k);
        if (u < 0 || s.region[u] >= 0) continue;
        const Eigen::Vector3d nu = normal_of(s, u);
        if (angle(normal_of(s, t), nu) < opt.max_bend * kDeg && angle(seed, nu) < opt.max_spread * kDeg) {
          s.region[u] = r;
          regions[r].push_back(u);
        }
      }
    }
  }
  std::vector<Found> found;
  for (int r = 0; r < static_cast<int>(regions.size()); ++r) {
    if (regions[r].size() < 2) continue;
    Found fd;
    std::string why;
    if (classify(s, TT0, r, regions[r], opt, fd, why)) found.push_back(fd);
    else if (!why.empty())
      log(fmt("oblique face of %.0f triangles left as it is: ", static_cast<double>(regions[r].size())) + why);
  }

  std::vector<ObliqueFace> out;
  for (const Found& fd : found) {
    // Barycentric coordinates in the triangle of the corners, projected to the face's plane.
    const Eigen::Vector3d n = fd.n;
    const Eigen::Vector3d u = (std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).cross(n).normalized();
    const Eigen::Vector3d w = n.cross(u);
    auto plane = [&](const Eigen::RowVector3d& p) { return Eigen::Vector2d(p.dot(u.transpose()), p.dot(w.transpose())); };
    const Eigen::Vector2d q0 = plane(s.V[fd.corners[0]]), q1 = plane(s.V[fd.corners[1]]), q2 = plane(s.V[fd.corners[2]]);
    Eigen::Matrix2d A;
    A.col(0) = q0 - q2;
    A.col(1) = q1 - q2;
    const Eigen::Matrix2d Ai = A.inverse();
    auto lambda = [&](const Eigen::RowVector3d& p) {
      const Eigen::Vector2d l = Ai * (plane(p) - q2);
      return Eigen::Vector3d(l[0], l[1], 1 - l[0] - l[1]);
    };
    const double eps = 0.01;
    for (int g = 0; g < 3; ++g) {
      auto field = [&](int v) { const Eigen::Vector3d l = lambda(s.V[v]); return l[g] - l[(g + 1) % 3]; };
      // Crease edges the median crosses are split first (with the triangle beyond), so that the cut
      // inside the face meets its boundary at a vertex.
      for (bool again = true; again;) {
        again = false;
        std::map<std::pair<int, int>, int> tri_of_edge;
        for (int t = 0; t < static_cast<int>(s.F.size()); ++t)
          for (int k = 0; k < 3; ++k) tri_of_edge[{s.F[t][k], s.F[t][(k + 1) % 3]}] = t;
        for (int t = 0; t < static_cast<int>(s.F.size()) && !again; ++t) {
          if (s.region[t] != fd.region) continue;
          for (int k = 0; k < 3 && !again; ++k) {
            const int a = s.F[t][k], b = s.F[t][(k + 1) % 3];
            auto it = tri_of_edge.find({b, a});
            if (it != tri_of_edge.end() && s.region[it->second] == fd.region) continue;  // inside the face
            const double fa = field(a), fb = field(b);
            if (std::abs(fa) < eps || std::abs(fb) < eps || (fa > 0) == (fb > 0)) continue;
            split_edge(s, a, b, s.V[a] + fa / (fa - fb) * (s.V[b] - s.V[a]));
            again = true;
          }
        }
      }
      std::vector<int> tris;
      std::map<int, double> f;
      for (int t = 0; t < static_cast<int>(s.F.size()); ++t)
        if (s.region[t] == fd.region) {
          tris.push_back(t);
          for (int v : s.F[t]) f[v] = field(v);
        }
      Eigen::MatrixXi F(static_cast<int>(s.F.size()), 3);
      for (size_t t = 0; t < s.F.size(); ++t) F.row(t) << s.F[t][0], s.F[t][1], s.F[t][2];
      std::vector<Eigen::RowVector3d> extra;
      const int nv = static_cast<int>(s.V.size());
      const auto pieces = cut_triangles(F, tris, f, eps, nv, extra, [&](int v) { return v < nv ? s.V[v] : extra[v - nv]; });
      s.V.insert(s.V.end(), extra.begin(), extra.end());
      Soup next;
      next.V = std::move(s.V);
      for (size_t t = 0; t < s.F.size(); ++t)
        if (s.region[t] != fd.region) {
          next.F.push_back(s.F[t]);
          next.label.push_back(s.label[t]);
          next.region.push_back(s.region[t]);
        }
      for (const auto& p : pieces) {
        next.F.push_back({p[0], p[1], p[2]});
        next.label.push_back(s.label[p[3]]);
        next.region.push_back(fd.region);
      }
      s = std::move(next);
    }
    // Each piece takes the label of the corner whose barycentric coordinate is largest at its centre.
    for (size_t t = 0; t < s.F.size(); ++t) {
      if (s.region[t] != fd.region) continue;
      const Eigen::Vector3d l = lambda((s.V[s.F[t][0]] + s.V[s.F[t][1]] + s.V[s.F[t][2]]) / 3.0);
      int k = 0;
      l.maxCoeff(&k);
      s.label[t] = fd.labels[k];
    }
    ObliqueFace of;
    for (int k = 0; k < 3; ++k) of.corners[k] = s.V[fd.corners[k]].transpose();
    of.labels = fd.labels;
    of.normal = n;
    out.push_back(of);
    log("oblique face at (" + fmt("%.4g, %.4g, %.4g", (of.corners[0] + of.corners[1] + of.corners[2]).x() / 3,
                                  (of.corners[0] + of.corners[1] + of.corners[2]).y() / 3, (of.corners[0] + of.corners[1] + of.corners[2]).z() / 3) +
        "), normal " + fmt("(%.3f, %.3f, %.3f)", n.x(), n.y(), n.z()) + ": split from its corners into " +
        segmentation::label_name(fd.labels[0]) + " / " + segmentation::label_name(fd.labels[1]) + " / " +
        segmentation::label_name(fd.labels[2]) + " quads");
  }
  if (out.empty()) return out;
  labels.V.resize(static_cast<int>(s.V.size()), 3);
  for (size_t v = 0; v < s.V.size(); ++v) labels.V.row(v) = s.V[v];
  labels.F.resize(static_cast<int>(s.F.size()), 3);
  labels.patch.resize(static_cast<int>(s.F.size()));
  for (size_t t = 0; t < s.F.size(); ++t) {
    labels.F.row(t) << s.F[t][0], s.F[t][1], s.F[t][2];
    labels.patch(t) = s.label[t];
  }
  return out;
}

}  // namespace hexdom::autopolycube
