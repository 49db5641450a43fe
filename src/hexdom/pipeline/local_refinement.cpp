#include "hexdom/pipeline/local_refinement.h"

#include <algorithm>
#include <chrono>

#include "hexdom/common/format.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/closest_point.h"
#include "hexdom/mesh/refine.h"
#include "hexdom/overlay/local_size.h"
#include "hexdom/pipeline/stretch.h"

namespace hexdom::pipeline {

double cell_for_local_sizes(const overlay::LocalSizeField& field, double size, const MeshSurfaceOptions& opt) {
  if (field.empty()) return size;
  const overlay::LocalLevels l = overlay::local_levels(size, {overlay::LocalSize{0, field.smallest(), {}}}, opt.min_size);
  if (l.factor != 1 && opt.log) opt.log(0, fmt("local sizes: the polycube's cell %g made %g", size, size * l.factor));
  return size * l.factor;
}

optimize::ImproveOptions polycube_improvement(const mesh::SurfaceMesh& patches, const MeshSurfaceOptions& opt) {
  optimize::ImproveOptions io = opt.improvement;
  io.max_edge_ratio = opt.target_edge_ratio;
  io.surface = patches;
  io.deadline = opt.deadline;  // stops early with its best so far: the generated mesh is a result
  io.threads = opt.threads;
  io.log = opt.verbose ? opt.log : LogCallback();
  return io;
}

void refine_to_local_sizes(const overlay::LocalSizeField& field, const mesh::SurfaceMesh& patches,
                           const MeshSurfaceOptions& opt, MeshSurfaceRun& r) {
  constexpr int kMaxLocalLevels = 4;  // as overlay::local_levels'
  if (field.empty()) return;
  r.stage = "refine";
  const auto t = std::chrono::steady_clock::now();
  const int old_nodes = r.mesh.num_nodes();  // refine_by_thirds keeps them first, in their order
  std::vector<char> plain(r.mesh.num_cells(), 1);  // cells that may be split again (no template's piece)
  int levels = 0, split = 0, templates = 0;
  const auto [edges, ne] = mesh::cell_edges(mesh::CellType::Hex);
  for (; levels < kMaxLocalLevels; ++levels) {
    const mesh::Mesh& m = r.mesh;
    std::vector<char> marked(m.num_nodes(), 0), fixed(m.num_nodes(), 0);
    for (int c = 0; c < m.num_cells(); ++c)
      if (!plain[c])
        for (int i = 0; i < mesh::node_count(m.type(c)); ++i) fixed[m.cells(c, i)] = 1;
    bool any = false;
    for (int c = 0; c < m.num_cells(); ++c) {
      if (m.type(c) != mesh::CellType::Hex || !plain[c]) continue;
      Eigen::Matrix<double, 8, 3> P;
      for (int b = 0; b < 8; ++b) P.row(b) = m.V.row(m.cells(c, b));
      const Eigen::Vector3d lo = P.colwise().minCoeff().transpose(), hi = P.colwise().maxCoeff().transpose();
      // The cell's side: its mean edge in real lengths (a stretched run measures positions
      // stretched); the longest would count a cell the map shears as a larger one.
      if (opt.stretched_by) P = unstretched(P, *opt.stretched_by);
      double side = 0;
      for (int e = 0; e < ne; ++e) side += (P.row(edges[e][0]) - P.row(edges[e][1])).norm() / ne;
      if (!field.split(lo, hi - lo, side)) continue;
      for (int b = 0; b < 8; ++b)
        if (!fixed[m.cells(c, b)]) marked[m.cells(c, b)] = any = true;
    }
    if (!any) break;
    mesh::Refinement ref = mesh::refine_by_thirds(m, std::move(marked), &fixed);
    if (ref.split + ref.templates == 0) break;
    std::vector<char> next(ref.mesh.num_cells());
    for (int c = 0; c < ref.mesh.num_cells(); ++c) next[c] = plain[ref.parent[c]] && ref.plain[c];
    plain = std::move(next);
    r.mesh = std::move(ref.mesh);
    split += ref.split;
    templates += ref.templates;
  }
  if (levels == 0) return;
  // The new boundary nodes lie on the coarse cells' faces, chords of the surface (a rod's across a
  // cell of its diameter): put on the surface before the optimiser, which then keeps them there,
  // rather than left to the snap's one move.
  const mesh::TriangleProjector onto(patches.V, patches.F);
  for (const mesh::BoundaryFace& f : mesh::boundary_faces(r.mesh))
    for (int v : mesh::face_nodes(r.mesh, f))
      if (v >= old_nodes) r.mesh.V.row(v) = onto.project(r.mesh.V.row(v).transpose()).transpose();
  // The mesh was pillowed (or not) and optimised before it was refined: the optimiser's stages
  // alone now, not the recommended sequence, which would lay a second layer over the first.
  optimize::ImproveOptions io = polycube_improvement(patches, opt);
  io.pillow = false;
  io.smooth = 1;
  io.optimize = io.max_rounds;
  io.mean_after = true;
  optimize::ImproveResult ir = optimize::improve(r.mesh, io);
  r.mesh = std::move(ir.mesh);
  r.quality = ir.after;
  r.budget_passed = r.budget_passed || ir.stopped;
  if (opt.log)
    opt.log(0, fmt("local sizes: %.0f levels by thirds (%.0f cells split, ", double(levels), double(split)) +
                   fmt("%.0f transition templates), %.0f cells, ", double(templates), double(r.mesh.num_cells())) +
                   worst_by_type(r.quality) + fmt(", in %.2f s", std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count()));
}

}  // namespace hexdom::pipeline
