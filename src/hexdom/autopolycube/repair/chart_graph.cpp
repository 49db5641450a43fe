#include "hexdom/autopolycube/repair/chart_graph.h"

#include "hexdom/common/error.h"
#include "hexdom/segmentation/axis_labels.h"

namespace hexdom::autopolycube {

ChartGraph chart_graph(const mesh::SurfaceMesh& s) { return chart_graph(s, Eigen::MatrixXi()); }

ChartGraph chart_graph(const mesh::SurfaceMesh& s, const Eigen::MatrixXi& adjacency) {
  const int nf = static_cast<int>(s.F.rows());
  if (s.patch.rows() != nf)
    throw GeometryError("the surface has " + std::to_string(nf) + " triangles but " + std::to_string(s.patch.rows()) + " labels");
  for (int f = 0; f < nf; ++f)
    if (s.patch(f) < 1 || s.patch(f) > 6)
      throw GeometryError("triangle " + std::to_string(f + 1) + " has label " + std::to_string(s.patch(f)) +
                          ": axis labels are 1..6 (+X, -X, +Y, -Y, +Z, -Z), as `hexdom segment` writes them");
  ChartGraph g;
  static_cast<polycube::BoundaryGraph&>(g) = adjacency.size() ? polycube::boundary_graph(s, adjacency) : polycube::boundary_graph(s);
  g.area.assign(g.num_charts(), 0.0);
  for (int c = 0; c < g.num_charts(); ++c)
    for (int f : g.triangles[c]) {
      const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), d = s.V.row(s.F(f, 2));
      g.area[c] += 0.5 * (b - a).cross(d - a).norm();
    }
  return g;
}

std::string chart_name(const ChartGraph& g, int c) {
  const int n = static_cast<int>(g.triangles[c].size());
  return "chart " + std::to_string(c + 1) + " (" + segmentation::label_name(g.label[c]) + ", " + std::to_string(n) +
         " triangle" + (n == 1 ? "" : "s") + ")";
}

}  // namespace hexdom::autopolycube
