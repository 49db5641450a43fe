#include "hexdom/pipeline/local_refinement.h"

#include <algorithm>
#include <array>
#include <chrono>

#include "hexdom/common/format.h"
#include "hexdom/common/stopwatch.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/closest_point.h"
#include "hexdom/mesh/edge_key.h"
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

void refine_to_local_sizes(const overlay::LocalSizeField& field, const mesh::SurfaceMesh& patches,
                           const MeshSurfaceOptions& opt, mesh::Mesh& generated) {
  constexpr int kMaxLocalLevels = 4;  // as overlay::local_levels'
  if (field.empty()) return;
  const auto t = std::chrono::steady_clock::now();
  const int old_nodes = generated.num_nodes();  // refine_by_thirds keeps them first, in their order
  std::vector<char> plain(generated.num_cells(), 1);  // cells that may be split again (no template's piece)
  int levels = 0, split = 0, templates = 0;
  const auto [edges, ne] = mesh::cell_edges(mesh::CellType::Hex);
  for (; levels < kMaxLocalLevels; ++levels) {
    const mesh::Mesh& m = generated;
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
    generated = std::move(ref.mesh);
    split += ref.split;
    templates += ref.templates;
  }
  if (levels == 0) return;
  // The new boundary nodes lie on the coarse cells' faces, chords of the surface (a rod's across a
  // cell of its diameter): put on the surface before the optimiser, which then keeps them there,
  // rather than left to the snap's one move.
  const mesh::TriangleProjector onto(patches.V, patches.F);
  for (const mesh::BoundaryFace& f : mesh::boundary_faces(generated))
    for (int v : mesh::face_nodes(generated, f))
      if (v >= old_nodes) generated.V.row(v) = onto.project(generated.V.row(v).transpose()).transpose();
  if (opt.log)
    opt.log(0, fmt("local sizes: %.0f levels by thirds (%.0f cells split, ", double(levels), double(split)) +
                   fmt("%.0f transition templates), %.0f cells", double(templates), double(generated.num_cells())) +
                   fmt(", in %.2f s", seconds_since(t)));
}

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const size_t k = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

}  // namespace

LocalSizeFit local_size_fit(const mesh::Mesh& mesh, const mesh::SurfaceMesh& surface,
                            const std::vector<overlay::LocalSize>& sizes) {
  LocalSizeFit fit;
  if (sizes.empty()) return fit;
  const std::vector<mesh::BoundaryFace> faces = mesh::boundary_faces(mesh);
  auto corner = [&](int v) -> Eigen::Vector3d { return mesh.V.row(v).transpose(); };
  std::vector<int> patch;              // per boundary face, its nearest triangle's patch (when asked)
  std::vector<mesh::EdgeKey> edges;    // the boundary edges, each once (when asked)
  for (const overlay::LocalSize& l : sizes) {
    std::vector<double> measured;
    if (l.polyline.rows() > 0) {
      if (edges.empty()) {
        for (const auto& f : faces)
          for (int i = 0; i < f.n; ++i) edges.push_back(mesh::undirected_edge(f.v[i], f.v[(i + 1) % f.n]));
        std::sort(edges.begin(), edges.end());
        edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
      }
      std::vector<std::array<int, 2>> segments;
      for (int i = 0; i + 1 < l.polyline.rows(); ++i) segments.push_back({i, i + 1});
      const mesh::TriangleProjector line = mesh::segment_projector(l.polyline, segments);
      const double near = 0.1 * l.size;
      auto on_line = [&](const Eigen::Vector3d& x) { return (line.project(x) - x).norm() <= near; };
      for (const mesh::EdgeKey e : edges) {
        const Eigen::Vector3d a = corner(mesh::edge_from(e)), b = corner(mesh::edge_to(e));
        if (on_line(a) && on_line(b) && on_line(0.5 * (a + b))) measured.push_back((a - b).norm());
      }
    } else {
      if (patch.empty()) {
        const std::vector<int> t = mesh::nearest_triangles(mesh::TriangleProjector(surface.V, surface.F), mesh.V, faces);
        patch.resize(faces.size(), -1);
        for (size_t k = 0; k < faces.size(); ++k)
          if (t[k] >= 0 && surface.patch.size() > t[k]) patch[k] = surface.patch(t[k]);
      }
      for (size_t k = 0; k < faces.size(); ++k) {
        if (patch[k] != l.patch) continue;
        const auto& f = faces[k];
        double sum = 0;
        for (int i = 0; i < f.n; ++i) sum += (corner(f.v[i]) - corner(f.v[(i + 1) % f.n])).norm();
        measured.push_back(sum / f.n);
      }
    }
    const double ratio = median(std::move(measured)) / l.size;
    fit.ratio.push_back(ratio);
    if (LocalSizeFit::within(ratio)) ++fit.met;
  }
  return fit;
}

std::string local_fit_text(const LocalSizeFit& fit, const std::vector<overlay::LocalSize>& sizes) {
  std::string text = "local sizes: cells";
  for (size_t k = 0; k < fit.ratio.size() && k < sizes.size(); ++k)
    text += (k ? ", " : " ") + fmt("%.2f of the size ", fit.ratio[k]) +
            (sizes[k].polyline.rows() > 0 ? std::string("along an edge") : fmt("on Face%.0f", double(sizes[k].patch)));
  return text + fmt(" (%.0f of ", double(fit.met)) + fmt("%.0f within 20%%)", double(fit.ratio.size()));
}

}  // namespace hexdom::pipeline
