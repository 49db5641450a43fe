#include "hexdom/polycube/patch_layout.h"

namespace hexdom::polycube {

PatchLayout patch_layout(const BoundaryGraph& g) {
  PatchLayout out;
  out.region = g.region;
  out.corner_of = Eigen::VectorXi::Constant(g.corner_of.rows(), -1);
  for (size_t c = 0; c < g.corners.size(); ++c)
    if (g.corner_regions[c] >= 3) {
      out.corner_of(g.corners[c]) = static_cast<int>(out.corners.size());
      out.corners.push_back(g.corners[c]);
    }
  out.patches.resize(g.num_regions());
  for (int r = 0; r < g.num_regions(); ++r) {
    Patch& p = out.patches[r];
    p.label = g.label[r];
    p.triangles = g.triangles[r];
    p.num_loops = static_cast<int>(g.loops[r].size());
    if (g.loops[r].empty()) continue;
    for (int sc : g.loops[r][0].curves) {
      const std::vector<int>& vs = g.curves[sc < 0 ? ~sc : sc].vertices;
      if (sc >= 0) p.loop.insert(p.loop.end(), vs.begin(), vs.end() - 1);
      else p.loop.insert(p.loop.end(), vs.rbegin(), vs.rend() - 1);
    }
    for (int i = 0; i < static_cast<int>(p.loop.size()); ++i)
      if (out.corner_of(p.loop[i]) >= 0) p.corners.push_back(i);
  }
  return out;
}

PatchLayout patch_layout(const mesh::SurfaceMesh& surface) { return patch_layout(boundary_graph(surface)); }

}  // namespace hexdom::polycube
