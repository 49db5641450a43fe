// generate(): the steps in order (steps.h), then the relaxation and untangling of the nodes.
#include "hexdom/generation/generate.h"

#include <algorithm>
#include <cstdio>

#include "hexdom/common/parallel_for.h"
#include "hexdom/generation/steps.h"
#include "hexdom/mesh/adjacency.h"
#include "hexdom/optimize/relax_nodes.h"

namespace hexdom::generation {

using optimize::NodeFreedom;

GenerationState::GenerationState(const mesh::SurfaceMesh& surface, const mesh::Mesh& structure, const GenerateOptions& options)
    : S(surface), T(structure), opt(options), t_last_(std::chrono::steady_clock::now()) {
  if (opt.level < 0 || opt.level > 6) throw GeometryError("level " + std::to_string(opt.level) + " is outside 0..6");
  n = 1 << opt.level;
  n1 = n + 1;
  N3 = static_cast<long long>(n) * n * n;
  nthreads = thread_count(opt.threads);
}

void GenerationState::log(const std::string& m) const {
  if (opt.log) opt.log(0, m);
}

// Wall-clock stage times: the patch maps run on several threads, where CPU time would add up.
void GenerationState::tick(const char* stage) {
  const auto now = std::chrono::steady_clock::now();
  char buf[64];
  std::snprintf(buf, sizeof buf, " %s %.1f", stage, std::chrono::duration<double, std::milli>(now - t_last_).count());
  timing += buf;
  t_last_ = now;
}

namespace {

// How surface nodes move in the relaxation: on their curve or patch, parameters kept within the
// domain (1e-6 inside it, a triangle's hypotenuse included).
void set_surface_moves(GenerationState& g) {
  NodeFreedom& freedom = g.freedom;
  freedom.now = freedom.param;
  freedom.place = [&g](int v, const double* q, double* x) {
    Vec3 p = g.freedom.kind[v] == optimize::NodeKind::Curve ? g.on_curve[v]->at(q[0]) : evaluate(*g.on_patch[v], g.S, q[0], q[1]);
    x[0] = p(0);
    x[1] = p(1);
    x[2] = p(2);
  };
  freedom.clamp = [&g](int v, double* q) {
    const double e = 1e-6;
    if (g.freedom.kind[v] == optimize::NodeKind::Curve) {
      q[0] = std::clamp(q[0], e, 1 - e);
      return;
    }
    q[0] = std::clamp(q[0], e, 1 - e);
    q[1] = std::clamp(q[1], e, 1 - e);
    if (g.on_patch[v]->domain.size() == 3 && q[0] + q[1] > 1 - e) {
      const double shift = 0.5 * (q[0] + q[1] - (1 - e));
      q[0] -= shift;
      q[1] -= shift;
    }
  };
}

// The plain relaxation, then the untangling of the cells it leaves inverted: first with surface
// nodes within a fifth of a lattice step of where they were made, then, for what is left, within
// 0.45 of a step. Nodes away from inverted cells keep the plain relaxation's positions exactly.
void relax(GenerationState& g) {
  if (g.opt.relax_sweeps <= 0) return;
  set_surface_moves(g);
  std::vector<int> left;
  const mesh::NodeCells cells = mesh::node_cells(g.result);
  g.log(optimize::relax_poor(g.result, cells, g.freedom.kind, g.opt.relax_sweeps, 0.2, g.nthreads,
                             g.opt.untangle ? &left : nullptr, 0.0));
  if (!g.opt.untangle) return;
  for (double box : {0.2, 0.45}) {
    if (left.empty()) break;
    const std::vector<int> candidates = left;
    g.log(optimize::untangle_nodes(g.result, cells, g.freedom, g.opt.relax_sweeps, 0.0, 0.2, 0.0, box / g.n, &candidates, &left));
  }
}

}  // namespace

mesh::Mesh generate(const mesh::SurfaceMesh& S, const mesh::Mesh& T, const GenerateOptions& opt, GenerateStats* stats_out) {
  GenerationState g(S, T, opt);
  layout_surface(g);
  g.tick("surface layout");
  snap_structure(g);
  match_faces(g);
  map_patches(g);
  g.tick("patch maps");
  g.log("matched " + std::to_string(g.stats.boundary_faces) + " boundary faces to patches (" +
        std::to_string(g.stats.cotangent_patches) + " cotangent, " + std::to_string(g.stats.mean_value_patches) +
        " mean-value maps)");
  number_nodes(g);
  g.tick("node ids");
  place_boundary_nodes(g);
  g.tick("boundary nodes");
  fill_interior_faces(g);
  g.tick("interior faces");
  fill_block_interiors(g);
  g.tick("block interiors");
  make_cells(g);
  g.tick("cells");
  relax(g);
  g.tick("relaxation");
  g.log(g.timing);
  if (stats_out) *stats_out = g.stats;
  return std::move(g.result);
}

}  // namespace hexdom::generation
