#include "hexdom/segmentation/segment_cvt.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "hexdom/common/interrupt.h"
#include "hexdom/segmentation/axis_labels.h"
#include "hexdom/segmentation/cube_frame.h"
#include "hexdom/mesh/triangle_adjacency.h"

namespace hexdom::segmentation {

namespace {

/// Triangles within `ring` edge steps of each triangle (itself excluded), optionally only those of
/// the same face; compressed rows.
void build_rings(const Eigen::MatrixXi& TT, int ring, const std::vector<int>* face, std::vector<int>& start,
                 std::vector<int>& list) {
  const int nf = static_cast<int>(TT.rows());
  start.assign(nf + 1, 0);
  list.clear();
  list.reserve(static_cast<size_t>(nf) * 10);
  std::vector<int> mark(nf, -1), frontier, next;
  for (int t = 0; t < nf; ++t) {
    start[t] = static_cast<int>(list.size());
    mark[t] = t;
    frontier.assign(1, t);
    for (int step = 0; step < ring && !frontier.empty(); ++step) {
      next.clear();
      for (int f : frontier)
        for (int k = 0; k < 3; ++k) {
          const int g = TT(f, k);
          if (g < 0 || mark[g] == t) continue;
          if (face && (*face)[g] != (*face)[t]) continue;
          mark[g] = t;
          list.push_back(g);
          next.push_back(g);
        }
      frontier.swap(next);
    }
  }
  start[nf] = static_cast<int>(list.size());
}

/// The input's CAD faces (its patch ids, numbered 0.. in order of first appearance), when the
/// segmentation respects them.
struct CadFaces {
  std::vector<int> face;               ///< per triangle: its face (all 0 when not respected)
  std::vector<std::vector<int>> tris;  ///< per face: its triangles (empty when not respected)
};

/// Counts the faces into out.faces and decides out.respected_faces.
CadFaces cad_faces(const mesh::SurfaceMesh& s, const CvtOptions& opt, Segmentation& out) {
  const int nf = static_cast<int>(s.F.rows());
  std::map<int, int> face_index;
  for (int f = 0; f < nf; ++f) face_index.try_emplace(s.patch(f), static_cast<int>(face_index.size()));
  out.faces = static_cast<int>(face_index.size());
  out.respected_faces = opt.respect_faces == FaceMode::On || (opt.respect_faces == FaceMode::Auto && out.faces > 1);
  CadFaces cf;
  cf.face.assign(nf, 0);
  if (out.respected_faces) {
    cf.tris.resize(out.faces);
    for (int f = 0; f < nf; ++f) {
      cf.face[f] = face_index[s.patch(f)];
      cf.tris[cf.face[f]].push_back(f);
    }
  }
  return cf;
}

/// A planar CAD face (all normals within planar_angle of its area-weighted mean) takes the label of
/// its mean normal, fixed.
void fix_planar_faces(const CadFaces& cf, const TriangleGeometry& geo, const CvtOptions& opt, std::vector<char>& fixed,
                      Segmentation& out) {
  const double cos_planar = std::cos(opt.planar_angle * M_PI / 180.0);
  for (const auto& tris : cf.tris) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (int f : tris) n += geo.area(f) * geo.normal.row(f).transpose();
    if (n.norm() == 0) continue;
    n.normalize();
    bool planar = true;
    for (int f : tris)
      if (geo.normal.row(f).dot(n) < cos_planar) { planar = false; break; }
    if (!planar) continue;
    ++out.planar_faces;
    const int l = nearest_label(n);
    for (int f : tris) {
      out.label(f) = l;
      fixed[f] = 1;
    }
  }
}

/// Curved CAD faces that are (almost) one label by their normals become one label, fixed.
void fix_uniform_faces(const CadFaces& cf, const TriangleGeometry& geo, const CvtOptions& opt, std::vector<char>& fixed,
                       Segmentation& out) {
  Eigen::VectorXi& label = out.label;
  for (const auto& tris : cf.tris) {
    if (tris.empty() || fixed[tris[0]]) continue;
    double area[7] = {0, 0, 0, 0, 0, 0, 0}, total = 0;
    for (int f : tris) { area[label(f)] += geo.area(f); total += geo.area(f); }
    const int major = static_cast<int>(std::max_element(area + 1, area + 7) - area);
    if (area[major] < opt.face_majority * total) continue;
    ++out.uniform_faces;
    for (int f : tris)
      if (!fixed[f]) { label(f) = major; fixed[f] = 1; }
  }
}

/// The manual labels, fixed; InputError for a triangle or label out of range.
void apply_manual_labels(const CvtOptions& opt, int nf, Eigen::VectorXi& label, std::vector<char>& fixed) {
  for (const auto& [t, l] : opt.manual) {
    if (t < 0 || t >= nf)
      throw InputError("manual label for triangle " + std::to_string(t) + " (0-based), but the surface has " +
                       std::to_string(nf) + " triangles");
    if (l < 1 || l > 6) throw InputError("manual label " + std::to_string(l) + " for triangle " + std::to_string(t) + " is not 1..6");
    label(t) = l;
    fixed[t] = 1;
  }
}

/// What both passes look at: the normals, the neighbours, the labels and which of them are fixed.
struct Sweep {
  const TriangleGeometry& geo;
  const Eigen::MatrixXi& TT;
  Eigen::VectorXi& label;
  const std::vector<char>& fixed;

  int size() const { return static_cast<int>(label.size()); }
  bool on_boundary(int f) const {
    for (int k = 0; k < 3; ++k)
      if (TT(f, k) >= 0 && label(TT(f, k)) != label(f)) return true;
    return false;
  }
  double sq_dist(int f, const Eigen::Vector3d& g) const { return 0.25 * (geo.normal.row(f).transpose() - g).squaredNorm(); }
};

/// Classical pass: generators follow their regions' area-weighted mean normals (at most max_drift
/// from their axes); a boundary triangle moves to the neighbouring label whose generator is nearest.
void classical_pass(const Sweep& sw, const CvtOptions& opt, Segmentation& out) {
  const int nf = sw.size();
  const TriangleGeometry& geo = sw.geo;
  Eigen::VectorXi& label = sw.label;
  Eigen::Matrix<double, 6, 3> sum = Eigen::Matrix<double, 6, 3>::Zero();
  for (int f = 0; f < nf; ++f) sum.row(label(f) - 1) += geo.area(f) * geo.normal.row(f);
  Eigen::Matrix<double, 6, 3>& gen = out.generators;
  const double cos_drift = std::cos(opt.max_drift * M_PI / 180.0), sin_drift = std::sin(opt.max_drift * M_PI / 180.0);
  auto update_generator = [&](int l) {
    const double n = sum.row(l - 1).norm();
    const Eigen::Vector3d axis = label_axis(l);
    Eigen::Vector3d g = n > 1e-300 ? Eigen::Vector3d(sum.row(l - 1).transpose() / n) : axis;
    if (g.dot(axis) < cos_drift) {  // keep the generator within max_drift of its axis
      Eigen::Vector3d perp = g - g.dot(axis) * axis;
      g = perp.norm() > 1e-12 ? Eigen::Vector3d(cos_drift * axis + sin_drift * perp.normalized()) : axis;
    }
    gen.row(l - 1) = g.transpose();
  };
  for (int l = 1; l <= 6; ++l) update_generator(l);
  for (int sweep = 0; sweep < opt.classical_sweeps; ++sweep) {
    check_interrupt("segment");
    int moves = 0;
    for (int f = 0; f < nf; ++f) {
      if (sw.fixed[f] || !sw.on_boundary(f)) continue;
      const int cur = label(f);
      int best = cur;
      double best_d = sw.sq_dist(f, gen.row(cur - 1).transpose());
      for (int k = 0; k < 3; ++k) {
        const int g = sw.TT(f, k);
        if (g < 0 || label(g) == cur || label(g) == best) continue;
        const double d = sw.sq_dist(f, gen.row(label(g) - 1).transpose());
        if (d < best_d) { best_d = d; best = label(g); }
      }
      if (best != cur) {
        sum.row(cur - 1) -= geo.area(f) * geo.normal.row(f);
        sum.row(best - 1) += geo.area(f) * geo.normal.row(f);
        label(f) = best;
        update_generator(cur);
        update_generator(best);
        ++moves;
      }
    }
    out.classical_sweeps = sweep + 1;
    out.classical_moves += moves;
    if (moves < opt.min_moves) break;
  }
}

/// Edge-weighted pass with fixed generators: the energy adds 2 lambda times the share of the
/// triangle's ring (of the same CAD face, given `face`) carrying another label.
void edge_weighted_pass(const Sweep& sw, const CvtOptions& opt, const std::vector<int>* face, Segmentation& out) {
  const int nf = sw.size();
  Eigen::VectorXi& label = sw.label;
  const Eigen::Matrix<double, 6, 3>& gen = out.generators;
  std::vector<int> start, ring;
  build_rings(sw.TT, opt.ring, face, start, ring);
  const double two_lambda = 2.0 * opt.edge_weight;
  for (int sweep = 0; sweep < opt.edge_sweeps; ++sweep) {
    check_interrupt("segment");
    int moves = 0;
    for (int f = 0; f < nf; ++f) {
      if (sw.fixed[f] || !sw.on_boundary(f)) continue;
      int count[7] = {0, 0, 0, 0, 0, 0, 0};
      const int n = start[f + 1] - start[f];
      for (int i = start[f]; i < start[f + 1]; ++i) ++count[label(ring[i])];
      auto energy = [&](int l) {
        double d = sw.sq_dist(f, gen.row(l - 1).transpose());
        if (n > 0) d += two_lambda * (n - count[l]) / n;
        return d;
      };
      const int cur = label(f);
      int best = cur;
      double best_e = energy(cur);
      for (int k = 0; k < 3; ++k) {
        const int g = sw.TT(f, k);
        if (g < 0 || label(g) == cur || label(g) == best) continue;
        const double e = energy(label(g));
        if (e < best_e - 1e-15) { best_e = e; best = label(g); }
      }
      if (best != cur) {
        label(f) = best;
        ++moves;
      }
    }
    out.edge_sweeps = sweep + 1;
    out.edge_moves += moves;
    if (moves == 0) break;
  }
}

}  // namespace

Segmentation segment_cvt(const mesh::SurfaceMesh& s, const CvtOptions& opt) {
  check_surface(s);
  if (opt.frame != Eigen::Matrix3d::Identity()) {  // the labels of the turned surface are the frame's
    CvtOptions in_frame = opt;
    in_frame.frame.setIdentity();
    return segment_cvt(rotated(s, opt.frame), in_frame);
  }
  if (opt.ring < 1) throw GeometryError("segmentation: ring must be at least 1, got " + std::to_string(opt.ring));
  if (!(opt.edge_weight >= 0)) throw GeometryError("segmentation: lambda must be >= 0");
  const int nf = static_cast<int>(s.F.rows());
  const TriangleGeometry geo = triangle_geometry(s);
  const Eigen::MatrixXi TT = mesh::triangle_adjacency(s.F);
  auto log = [&](int level, const std::string& m) { if (opt.log) opt.log(level, m); };

  Segmentation out;
  Eigen::VectorXi& label = out.label;
  label.resize(nf);
  for (int f = 0; f < nf; ++f) label(f) = nearest_label(geo.normal.row(f).transpose());
  std::vector<char> fixed(nf, 0);

  const CadFaces cf = cad_faces(s, opt, out);
  if (out.respected_faces) {
    fix_planar_faces(cf, geo, opt, fixed, out);
    fix_uniform_faces(cf, geo, opt, fixed, out);
    log(0, "segment: " + std::to_string(out.faces) + " CAD faces: " + std::to_string(out.planar_faces) +
               " planar and " + std::to_string(out.uniform_faces) + " curved ones keep one label");
  }
  apply_manual_labels(opt, nf, label, fixed);

  const Sweep sw{geo, TT, label, fixed};
  classical_pass(sw, opt, out);
  out.classical = label;
  if (opt.edge_weight > 0 && opt.edge_sweeps > 0) edge_weighted_pass(sw, opt, out.respected_faces ? &cf.face : nullptr, out);
  log(0, "segment: classical CVT " + std::to_string(out.classical_sweeps) + " sweeps (" +
             std::to_string(out.classical_moves) + " moves), edge-weighted " + std::to_string(out.edge_sweeps) +
             " sweeps (" + std::to_string(out.edge_moves) + " moves)");
  return out;
}

}  // namespace hexdom::segmentation
