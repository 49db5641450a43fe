#include "hexdom/segmentation/patch_graph.h"

#include "hexdom/segmentation/axis_labels.h"

namespace hexdom::segmentation {

const std::vector<int>& PatchGraph::patch_curves(int r) const {
  static const std::vector<int> none;
  return loops[r].empty() ? none : loops[r][0].curves;
}

PatchGraph patch_graph(const mesh::SurfaceMesh& s) {
  PatchGraph g;
  static_cast<polycube::BoundaryGraph&>(g) = polycube::boundary_graph(s);
  g.layout = polycube::patch_layout(g);
  const int nf = static_cast<int>(s.F.rows()), nv = static_cast<int>(s.V.rows());
  const int np = g.num_patches();

  // Geometry per patch.
  const TriangleGeometry geo = triangle_geometry(s);
  g.normal = Eigen::MatrixXd::Zero(np, 3);
  g.centroid = Eigen::MatrixXd::Zero(np, 3);
  g.area = Eigen::VectorXd::Zero(np);
  g.axis.resize(np);
  for (int f = 0; f < nf; ++f) {
    const int r = g.region(f);
    g.normal.row(r) += geo.area(f) * geo.normal.row(f);
    g.centroid.row(r) += geo.area(f) * geo.centroid.row(f);
    g.area(r) += geo.area(f);
  }
  for (int r = 0; r < np; ++r) {
    if (g.area(r) > 0) g.centroid.row(r) /= g.area(r);
    const double n = g.normal.row(r).norm();
    if (n > 0) g.normal.row(r) /= n;
    g.axis(r) = nearest_label(g.normal.row(r).transpose());
  }

  // Euler characteristic per patch: V - E + F, each boundary edge counted once, inner edges twice.
  g.euler.assign(np, 0);
  std::vector<int> stamp(nv, -1), boundary_edges(np, 0), vertices(np, 0), tris(np, 0);
  for (int r = 0; r < np; ++r) {
    for (int f : g.triangles[r]) {
      ++tris[r];
      for (int k = 0; k < 3; ++k) {
        const int v = s.F(f, k);
        if (stamp[v] != r) { stamp[v] = r; ++vertices[r]; }
      }
    }
    for (int c : g.region_curves[r]) boundary_edges[r] += static_cast<int>(g.curves[c].vertices.size()) - 1;
  }
  for (int r = 0; r < np; ++r) g.euler[r] = vertices[r] - (3 * tris[r] + boundary_edges[r]) / 2 + tris[r];
  return g;
}

}  // namespace hexdom::segmentation
