#include "hexdom/autopolycube/repair/plane_groups.h"

#include "hexdom/common/disjoint_sets.h"

namespace hexdom::autopolycube {

PlaneGroups plane_groups(const mesh::SurfaceMesh& s, const ChartGraph& g) {
  const int nc = g.num_charts(), nv = static_cast<int>(s.V.rows());
  DisjointSets groups(nc);
  Eigen::MatrixXi first = Eigen::MatrixXi::Constant(nv, 3, -1);  // first chart met per vertex and axis
  for (int f = 0; f < s.F.rows(); ++f) {
    const int c = g.region(f), a = (g.label[c] - 1) / 2;
    for (int k = 0; k < 3; ++k) {
      int& m = first(s.F(f, k), a);
      if (m < 0) m = c;
      else groups.unite(m, c);
    }
  }
  PlaneGroups p;
  p.of_chart.assign(nc, -1);
  std::vector<int> id_of_root(nc, -1);
  for (int c = 0; c < nc; ++c) {
    const int r = groups.find(c);
    if (id_of_root[r] < 0) {
      id_of_root[r] = p.num_groups();
      p.axis.push_back((g.label[c] - 1) / 2);
      p.charts.emplace_back();
    }
    p.of_chart[c] = id_of_root[r];
    p.charts[id_of_root[r]].push_back(c);
  }
  p.of_vertex = Eigen::MatrixXi::Constant(nv, 3, -1);
  for (int v = 0; v < nv; ++v)
    for (int a = 0; a < 3; ++a)
      if (first(v, a) >= 0) p.of_vertex(v, a) = p.of_chart[first(v, a)];
  return p;
}

}  // namespace hexdom::autopolycube
