#include "hexdom/segmentation/axis_labels.h"

#include <stdexcept>

#include "hexdom/common/error.h"
#include "hexdom/polycube/boundary_graph.h"

namespace hexdom::segmentation {

Eigen::Vector3d label_axis(int label) {
  if (label < 1 || label > 6) throw std::invalid_argument("axis label must be 1..6, got " + std::to_string(label));
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  a((label - 1) / 2) = (label % 2 == 1) ? 1.0 : -1.0;
  return a;
}

std::string label_name(int label) {
  static const char* names[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
  return label >= 1 && label <= 6 ? names[label - 1] : "?";
}

int nearest_label(const Eigen::Vector3d& n) {
  int best = 1;
  double best_dot = -1e300;
  for (int k = 0; k < 3; ++k)
    for (int s = 0; s < 2; ++s) {
      double d = s == 0 ? n(k) : -n(k);
      if (d > best_dot) {
        best_dot = d;
        best = 2 * k + s + 1;
      }
    }
  return best;
}

TriangleGeometry triangle_geometry(const mesh::SurfaceMesh& s) {
  const int nf = static_cast<int>(s.F.rows());
  TriangleGeometry g;
  g.normal.resize(nf, 3);
  g.area.resize(nf);
  g.centroid.resize(nf, 3);
  for (int f = 0; f < nf; ++f) {
    Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    Eigen::Vector3d n = (b - a).cross(c - a);
    double len = n.norm();
    g.area(f) = 0.5 * len;
    g.normal.row(f) = len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
    g.centroid.row(f) = (a + b + c) / 3.0;
  }
  return g;
}

void check_surface(const mesh::SurfaceMesh& s) {
  if (s.F.rows() == 0) throw GeometryError("the surface has no triangles");
  if (s.patch.rows() != s.F.rows())
    throw GeometryError("the surface has " + std::to_string(s.F.rows()) + " triangles but " +
                        std::to_string(s.patch.rows()) + " patch ids");
  polycube::check_closed_manifold(s);
  const double diag2 = (s.V.colwise().maxCoeff() - s.V.colwise().minCoeff()).squaredNorm();
  for (int f = 0; f < s.F.rows(); ++f) {
    Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    if (!(0.5 * (b - a).cross(c - a).norm() > 1e-12 * diag2))
      throw GeometryError("triangle " + std::to_string(f + 1) + " (vertices " + std::to_string(s.F(f, 0) + 1) +
                          ", " + std::to_string(s.F(f, 1) + 1) + ", " + std::to_string(s.F(f, 2) + 1) +
                          ") is degenerate: zero area, no normal");
  }
}

}  // namespace hexdom::segmentation
