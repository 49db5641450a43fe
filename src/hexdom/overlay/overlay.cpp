#include "hexdom/overlay/overlay.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include "hexdom/common/format.h"
#include "hexdom/common/interrupt.h"
#include "hexdom/common/parallel_for.h"
#include "hexdom/common/stopwatch.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/optimize/improve.h"
#include "hexdom/overlay/buffer.h"
#include "hexdom/overlay/core.h"
#include "hexdom/overlay/grid.h"
#include "hexdom/overlay/octree.h"
#include "hexdom/mesh/closest_point.h"
#include "hexdom/mesh/triangle_adjacency.h"
#include "hexdom/quality/metrics.h"

namespace hexdom::overlay {

namespace {

int inverted(const quality::QualityReport& q) { return quality::inverted_cells(q); }

// The real surface and its features when the grid is laid over a stretched copy (see overlay_mesh).
struct Stretch {
  Eigen::Vector3d factor;
  const mesh::SurfaceMesh* surface;
  const SurfaceFeatures* features;
};

// The local sizes' refinement of each grid (OverlayOptions::local_sizes).
struct Local {
  const LocalSizeField* field = nullptr;
  int levels = 0;
};

// Whether the octree splits cell c: where a local size asks for smaller cells near it, or (up to
// opt.octree_levels) where the wall under it is thinner than opt.wall_cells of its cells; never
// into children shorter than opt.min_size.
bool split_cell(const Grid& grid, const OctreeCell& c, const mesh::TriangleProjector& proj, const OverlayOptions& opt,
                const Stretch* stretch, const Local& local) {
  const Eigen::Vector3d size = octree_cell_size(grid, c), lo = octree_cell_origin(grid, c), centre = lo + size / 2;
  // The children's real sides (the grid may be laid over a stretched copy).
  const Eigen::Vector3d real = stretch ? Eigen::Vector3d(size.cwiseQuotient(stretch->factor)) : size;
  if (opt.min_size > 0 && real.minCoeff() / 3 < opt.min_size * (1 - 1e-9)) return false;
  if (local.field && c.level < local.levels && local.field->split(lo, size, real.maxCoeff())) return true;
  if (c.level >= opt.octree_levels) return false;
  int t = -1;
  const Eigen::Vector3d q = proj.project(centre, &t);
  if ((q - centre).norm() > size.norm() / 2) return false;
  const Eigen::Vector3d n = proj.normal(t);
  const double r = opt.wall_cells * size.minCoeff() / 2;
  const Eigen::Vector3d ball = q - r * n;
  int t2 = -1;
  const Eigen::Vector3d q2 = proj.project(ball, &t2);
  return (q2 - ball).norm() < 0.9 * r && proj.normal(t2).dot(n) < -0.5;
}

// The octree's cells whose centre is inside by the margin of their own size, less those facing a
// kept neighbour across a slot (across_surface), made manifold.
Core octree_core(const OctreeMesh& tree, const mesh::SurfaceMesh& s, const mesh::TriangleProjector& proj, double hmin,
                 const OverlayOptions& opt) {
  const mesh::Mesh& cells = tree.mesh;
  std::vector<Eigen::Vector3d> centres(cells.num_cells());
  std::vector<double> size(cells.num_cells());
  for (int c = 0; c < cells.num_cells(); ++c) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int i = 0; i < 8; ++i) x += cells.V.row(cells.cells(c, i)).transpose() / 8;
    centres[c] = x;
    size[c] = hmin / std::pow(3.0, tree.level[c]) / (tree.plain[c] ? 1 : 3);
  }
  const NodeField f = classify_points(centres, s);
  std::vector<char> keep(cells.num_cells(), 0);
  for (int c = 0; c < cells.num_cells(); ++c) keep[c] = f.inside[c] && f.distance[c] >= opt.centre_margin * size[c];
  int parted = 0;
  for (const auto& [a, b] : mesh::face_neighbours(cells)) {
    if (!keep[a] || !keep[b] || !across_surface(centres[a], f.distance[a], centres[b], f.distance[b], proj)) continue;
    keep[f.distance[a] < f.distance[b] ? a : b] = 0;
    ++parted;
  }
  Core core = manifold_core(cells, std::move(keep), f.distance);
  core.parted = parted;
  return core;
}

// The nodes at both ends of the shortest edge of each cell above `max_ratio` whose two ends are
// both held on a curve or at a corner (the cells measured on `threads` threads).
std::vector<int> held_short_edges(const mesh::Mesh& m, const Placement& place_of, double max_ratio, int threads) {
  const quality::CellMetrics metrics = quality::compute_metrics(m, threads);
  auto held = [&](int v) { return place_of.kind[v] == optimize::Curve || place_of.kind[v] == optimize::Corner; };
  std::vector<int> out;
  for (int c = 0; c < m.num_cells(); ++c) {
    if (!(metrics.edge_ratio(c) > max_ratio)) continue;
    const auto [edges, n] = mesh::cell_edges(m.type(c));
    int a = -1, b = -1;
    double shortest = std::numeric_limits<double>::infinity();
    for (int e = 0; e < n; ++e) {
      const int u = m.cells(c, edges[e][0]), v = m.cells(c, edges[e][1]);
      const double l = (m.V.row(u) - m.V.row(v)).squaredNorm();
      if (l < shortest) shortest = l, a = u, b = v;
    }
    if (a >= 0 && held(a) && held(b)) out.insert(out.end(), {a, b});
  }
  return out;
}

// One grid of spacing h over `s` (in the frame): core, buffer layer, placement, optimiser. With
// `stretch`, s and feat are the stretched copies: the mesh is optimised there, stretched back and
// optimised again on the real surface, its nodes kept on the same regions, curves and corners.
// Throws GeometryError when the core is empty or in pieces. With `lost_at` > 0, a mesh whose volume
// is off that of s by more than that fraction is returned as the optimiser left it, without the
// rounds that let nodes off their features to mend inverted or needle cells: the caller ranks it
// below any mesh that kept the part (Ranking::lost) and makes a finer grid.
OverlayResult mesh_with_grid(const mesh::SurfaceMesh& s, const SurfaceFeatures& feat, const Eigen::Vector3d& h,
                             const OverlayOptions& opt, const Stretch* stretch, const Local& local, double lost_at) {
  OverlayResult r;
  const Grid grid = grid_around(s.V, h);
  r.spacing = grid.h.maxCoeff();
  r.thinnest = grid.h.minCoeff();
  if (double(grid.num_cells()) > opt.max_grid_cells)
    throw GeometryError(fmt("a grid of spacing %g would have %.0f cells, more than %.0f", h.maxCoeff(),
                            double(grid.num_cells()), opt.max_grid_cells));
  const double hmin = grid.h.minCoeff();
  const double margin = (opt.core_by_centres ? opt.centre_margin : opt.margin) * hmin;
  std::vector<std::array<int, 4>> outer;
  std::vector<int> copy;
  mesh::Mesh m;  // the core, then with its buffer layer
  std::vector<double> depth{opt.buffer_depth * hmin};
  OctreeMesh tree;
  const mesh::TriangleProjector& proj = feat.triangles();  // over s: feat are its features
  const int levels = std::max(opt.octree_levels, local.levels);
  if (levels > 0 && opt.core_by_centres)
    tree = octree_mesh(grid, levels, [&](const OctreeCell& c) { return split_cell(grid, c, proj, opt, stretch, local); });
  Core core;
  if (tree.levels > 0) {
    core = octree_core(tree, s, proj, hmin, opt);
    if (core.cells == 0) throw GeometryError(fmt("no octree cell of spacing %g lies inside with its margin", h.maxCoeff()));
    m = core_mesh(tree.mesh, core);
    r.octree_levels = tree.levels;
    r.thinnest = hmin / std::pow(3.0, tree.levels);
  } else {
    core = opt.core_by_centres
               ? core_cells_by_centres(grid, classify_nodes(cell_centres(grid), s, std::max(margin, hmin) * 1.001), margin,
                                       &proj, std::max(margin, hmin) * 1.001)
               : core_cells(grid, classify_nodes(grid, s, margin * 1.001), margin);
    if (core.cells == 0) throw GeometryError(fmt("no grid cell of spacing %g lies inside with its margin", h.maxCoeff()));
    m = core_mesh(grid, core);
  }
  if (core.components > 1 && opt.log)
    opt.log(0, fmt("overlay: the cells of spacing %g inside fall into %.0f pieces; the largest kept, %.0f cells dropped",
                   h.maxCoeff(), core.components, core.apart));
  r.core_cells = core.cells;
  r.dropped = core.dropped;
  r.parted = core.parted;
  m = add_buffer_layer(m, &outer, &copy);
  if (tree.levels > 0) {
    // The buffer layer's depth from the size of the core cells at each node.
    depth.assign(m.num_nodes(), std::numeric_limits<double>::infinity());
    for (int c = 0; c < m.num_cells(); ++c) {
      if (m.region(c) != 1) continue;
      const double cs = std::cbrt(std::abs(quality::volume(mesh::CellType::Hex, quality::cell_points(m, c))));
      for (int i = 0; i < 8; ++i) depth[m.cells(c, i)] = std::min(depth[m.cells(c, i)], opt.buffer_depth * cs);
    }
  }
  r.buffer_cells = static_cast<int>(outer.size());
  check_interrupt("overlay");
  Placement place_of = place_outer_nodes(m, outer, feat, 1.5 * h.maxCoeff(), !opt.pillow_curves);
  if (opt.core_by_centres) pull_inner_nodes(m, outer, copy, feat, depth);
  spread(m, outer, place_of, feat, opt.spread_passes, 0.25 * grid.h.minCoeff());
  if (opt.pillow_curves) {
    const CurvePillow pc = pillow_curves(m, outer, place_of, feat, opt.pillow_offset);
    r.prisms = pc.prisms;
  }
  r.curve_nodes = place_of.curve;
  r.corner_nodes = place_of.corner;
  r.corners_missed = place_of.corners_missed;
  r.demoted = place_of.demoted;
  check_interrupt("overlay");
  optimize::ImproveOptions io;
  io.max_rounds = opt.max_rounds;
  io.max_edge_ratio = opt.max_edge_ratio;
  io.mean_passes = opt.mean_passes;
  io.surface = s;
  io.kinds = place_of.kind;
  io.curve_neighbours = curve_neighbours(place_of, outer, feat);
  std::vector<int> hints(m.num_nodes(), -1);  // per node its last triangle (any is a valid bound: place)
  io.project = [&](int v, const Eigen::Vector3d& x) { return place(place_of, feat, v, x, &hints[v]); };
  io.project_concurrent = true;  // closest points on the surface's regions and curves: reads only
  io.threads = opt.threads;
  io.deadline = opt.deadline;
  optimize::ImproveResult ir = optimize::improve(m, io);
  opt.deadline.check("overlay");
  const double enclosed = lost_at > 0 ? mesh::enclosed_volume(s.V, s.F) : 0.0;
  const bool mend = !(lost_at > 0 && std::abs(ir.after.total_volume - enclosed) > lost_at * std::abs(enclosed));
  if (!mend && inverted(ir.after) > 0 && opt.log)
    opt.log(0, fmt("overlay: spacing %g lost %.0f%% of the solid: its %.0f inverted cells are left as they are, a finer "
                   "grid follows", h.maxCoeff(), 100 * std::abs(ir.after.total_volume / enclosed - 1), double(inverted(ir.after))));
  // The optimiser once more after `nodes` were let off their features (loosen_nodes): its
  // passes start around them, the rest of the mesh is where the run before left it.
  auto improve_again = [&](std::vector<int> nodes) {
    io.kinds = place_of.kind;
    io.curve_neighbours = curve_neighbours(place_of, outer, feat);
    io.optimised_at = ir.mesh.V;
    io.changed_nodes = std::move(nodes);
    optimize::ImproveResult again = optimize::improve(ir.mesh, io);
    io.optimised_at.resize(0, 0);
    io.changed_nodes.clear();
    opt.deadline.check("overlay");
    return again;
  };
  // Cells the optimiser could not make valid with their nodes held on curves, corners and regions:
  // those nodes let off one level (loosen_nodes), the optimiser again, the better kept; three times
  // at most (a corner node can end anywhere on the surface).
  for (int round = 0; mend && round < 3 && inverted(ir.after) > 0; ++round) {
    const quality::CellMetrics metrics = quality::compute_metrics(ir.mesh, thread_count(opt.threads));
    std::vector<int> bad;  // the nodes of the cells left inverted
    for (int c = 0; c < ir.mesh.num_cells(); ++c)
      if (!(metrics.scaled_jacobian(c) > 0))
        for (int i = 0; i < mesh::node_count(ir.mesh.type(c)); ++i) bad.push_back(ir.mesh.cells(c, i));
    const int freed = loosen_nodes(place_of, bad, feat);
    if (freed == 0) break;
    optimize::ImproveResult again = improve_again(std::move(bad));
    if (opt.log)
      opt.log(0, fmt("overlay: %.0f inverted cells: %.0f of their nodes let off their curves or corners, ",
                     double(inverted(ir.after)), double(freed)) + fmt("%.0f inverted after", double(inverted(again.after))));
    if (inverted(again.after) > inverted(ir.after)) break;
    ir = std::move(again);
  }
  // Cells above the edge-ratio target whose shortest edge joins two nodes held on curves or
  // corners (a ledge, a CAD edge or a small hole far shorter than the cells: no move of either
  // can lengthen it): those two nodes let off one level, the optimiser again, kept when the
  // largest ratio goes down with no cell inverted and the worst cell not below the lower of its
  // SJ and refine_below_sj; twice at most (a corner goes to a curve, then to a face).
  for (int round = 0; mend && round < 2 && opt.max_edge_ratio > 0 && inverted(ir.after) == 0; ++round) {
    const double ratio = quality::max_edge_ratio(ir.after);
    if (!(ratio > opt.max_edge_ratio)) break;
    const std::vector<int> held = held_short_edges(ir.mesh, place_of, opt.max_edge_ratio, thread_count(opt.threads));
    if (held.empty() || loosen_nodes(place_of, held, feat) == 0) break;
    optimize::ImproveResult again = improve_again(held);
    if (opt.log)
      opt.log(0, fmt("overlay: largest edge ratio %.1f: %.0f nodes on the ends of the shortest edges let off their curves or "
                     "corners, %.1f after", ratio, double(held.size()), quality::max_edge_ratio(again.after)));
    if (inverted(again.after) > 0 || !(quality::max_edge_ratio(again.after) < ratio) ||
        quality::worst_sj(again.after) < std::min(quality::worst_sj(ir.after), opt.refine_below_sj))
      break;
    ir = std::move(again);
  }
  if (stretch) {
    const SurfaceFeatures& real = *stretch->features;
    ir.mesh.V = ir.mesh.V * stretch->factor.cwiseInverse().asDiagonal();
    for (int v = 0; v < ir.mesh.num_nodes(); ++v)
      if (place_of.kind[v] != optimize::Interior) ir.mesh.V.row(v) = place(place_of, real, v, ir.mesh.V.row(v).transpose()).transpose();
    io.surface = *stretch->surface;
    io.project = [&](int v, const Eigen::Vector3d& x) { return place(place_of, real, v, x, &hints[v]); };
    optimize::ImproveResult again = optimize::improve(ir.mesh, io);
    // Stretching back keeps every cell valid; the second run only raises the worst cell.
    if (quality::inverted_cells(again.after) <= quality::inverted_cells(again.before)) ir = std::move(again);
    else ir.after = again.before;
  }
  r.mesh = std::move(ir.mesh);
  r.quality = ir.after;
  r.node_kind = place_of.kind;
  return r;
}

// Meshes of one part compared against its surface's volume `reference`.
struct Ranking {
  double reference;
  const OverlayOptions& opt;
  double error(const OverlayResult& x) const { return std::abs(x.quality.total_volume - reference); }
  bool volume_off(const OverlayResult& x) const {
    return reference != 0 && error(x) > opt.target_volume * std::abs(reference);
  }
  bool lost(const OverlayResult& x) const { return reference != 0 && error(x) > opt.lost_volume * std::abs(reference); }
  // The better of two meshes: a mesh of the whole part first (a grid too coarse for a thin part
  // drops it: volume off by more than lost_volume), and of two that both lost part of it the one
  // that lost less; then fewer inverted cells; then, when either misses the volume target, the
  // smaller volume error; then the higher worst SJ.
  bool better(const OverlayResult& r, const OverlayResult& b) const {
    return lost(r) != lost(b) ? lost(b)
           : lost(r)          ? error(r) < error(b)
           : inverted(r.quality) != inverted(b.quality)
               ? inverted(r.quality) < inverted(b.quality)
               : (volume_off(b) || volume_off(r) ? error(r) < error(b) : quality::worst_sj(r.quality) > quality::worst_sj(b.quality));
  }
  std::string summary(const OverlayResult& r) const {
    return fmt("%.0f core + %.0f buffer cells, ", double(r.core_cells), double(r.buffer_cells)) +
           fmt("%.0f inverted, worst SJ %.3f, volume %+.2f%%", double(inverted(r.quality)), quality::worst_sj(r.quality),
               reference != 0 ? 100 * (r.quality.total_volume - reference) / reference : 0.0) +
           fmt(", %.2f s", r.seconds);
  }
};

// After a grid of `cells` cells (`kept`: it became `best`) left `best` short of the targets
// (Ranking): whether the spacing is halved again (saying why not, or why), counting the halvings
// for quality alone in `finer_for_quality`. Without local sizes (`no_local`), an octree grid ends
// the halvings.
bool halve_again(const OverlayResult& best, double cells, bool kept, bool no_local, const Ranking& rank,
                 const OverlayOptions& opt, int& finer_for_quality) {
  auto say = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  // An octree grid is already refined where the part is thin: halving it as well would multiply
  // its cells (up to a million) by 8.
  if (best.octree_levels > 0 && no_local) {
    say("overlay: the octree's grid is kept; no halving after it");
    return false;
  }
  // A finer grid for quality alone (the part is whole) costs 8 times the cells: not beyond
  // max_cells_for_quality, nor beyond max_cells_for_extra for the worst SJ alone.
  // A grid halved for the SJ alone that did no better ends the halvings.
  const double finer_cells = 8.0 * cells;
  const bool for_sj = inverted(best.quality) == 0 && !rank.volume_off(best);
  const double cap = for_sj ? opt.max_cells_for_extra : opt.max_cells_for_quality;
  if (for_sj && !kept) return false;
  if (!rank.lost(best) && (++finer_for_quality > opt.refinements_for_quality || finer_cells > cap)) {
    if (finer_for_quality <= opt.refinements_for_quality)
      say(fmt("overlay: a finer grid would have about %.0f cells, more than %.0f; keeping this one", finer_cells, cap));
    return false;
  }
  say(inverted(best.quality) > 0 ? "overlay: inverted cells remain; halving the spacing"
      : rank.volume_off(best)    ? "overlay: the volume is off by more than the target; halving the spacing"
                                 : fmt("overlay: worst SJ %.3f, below %.2f; halving the spacing", quality::worst_sj(best.quality),
                                       opt.refine_below_sj));
  return true;
}

// Local sizes (opt.local_sizes) on a grid of spacing h: h scaled so that the smallest is met at
// some octree level (local_levels; idempotent), said in the log, and the refinement it needs.
Local local_refinement(Eigen::Vector3d& h, const OverlayOptions& opt, const LocalSizeField& field) {
  if (field.empty()) return {};
  // (Only the sizes on this surface: a solid of several meshed alone may have none of the faces.)
  const LocalLevels l = local_levels(h.maxCoeff(), {LocalSize{0, field.smallest(), {}}}, opt.min_size);
  if (l.factor != 1 && opt.log)
    opt.log(0, fmt("overlay: local sizes: spacing %g made %g, ", h.maxCoeff(), h.maxCoeff() * l.factor) +
                   fmt("refined %.0f times by thirds near the faces asking for smaller cells", double(l.levels)));
  h *= l.factor;
  return {&field, l.levels};
}

// The factor (< 1) of h0 that gives walls `across` cells (measured on s, where the cells are
// cubes): every spacing made smaller alike, within max_wall_refinement, the min size and
// max_grid_cells; 1 when the walls have that many already. Says so.
double walls_factor(const mesh::SurfaceMesh& s, const Eigen::Vector3d& h0, const Eigen::Vector3d& extent, double across,
                    const OverlayOptions& opt) {
  const double wall = wall_thickness(s, opt.wall_quantile);
  double f = std::max(wall / across / h0.maxCoeff(), 1 / opt.max_wall_refinement);
  if (opt.min_size > 0) f = std::max(f, opt.min_size / h0.minCoeff());
  const Eigen::Vector3d n = extent.cwiseQuotient(h0).array() + 3;  // grid_around's cells, about
  f = std::min(1.0, std::max(f, 1.01 * std::cbrt(n.prod() / opt.max_grid_cells)));
  if (f < 1 && opt.log)
    opt.log(0, fmt("overlay: walls of %.2f cells of spacing %g across (%g%% of the surface on thinner ones); the spacing "
                   "made %.2f times smaller", wall / h0.maxCoeff(), h0.maxCoeff(), 100 * opt.wall_quantile, 1 / f));
  return f;
}

// `s` scaled per axis by `factor`.
mesh::SurfaceMesh scaled(mesh::SurfaceMesh s, const Eigen::Vector3d& factor) {
  s.V = s.V * factor.asDiagonal();
  return s;
}

// The surface's features and, with FeatureOptions::patch_edges, the same without the curves it
// adds (`plain`; none when it adds none); each also on the stretched copy of the surface when the
// grid is stretched (sfeat, splain, with the same regions).
struct FeatureSets {
  std::unique_ptr<SurfaceFeatures> feat, sfeat, plain, splain;
  mesh::TriangleProjector added;  // the curves patch_edges adds, as segments (a, b, b)

  FeatureSets(const mesh::SurfaceMesh& s, const mesh::SurfaceMesh* stretched, const FeatureOptions& options) {
    feat = std::make_unique<SurfaceFeatures>(s, options);
    if (options.patch_edges) {
      FeatureOptions fo = options;
      fo.patch_edges = false;
      plain = std::make_unique<SurfaceFeatures>(s, fo);
      if (plain->region() == feat->region()) plain.reset();
    }
    if (stretched) {
      FeatureOptions fo = options;
      fo.regions = feat->region();
      sfeat = std::make_unique<SurfaceFeatures>(*stretched, fo);
      if (plain) {
        fo.regions = plain->region();
        splain = std::make_unique<SurfaceFeatures>(*stretched, fo);
      }
    }
    if (!plain) return;
    const Eigen::MatrixXi TT = mesh::triangle_adjacency(s.F);
    std::vector<std::array<int, 2>> segments;
    for (int f = 0; f < s.F.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int g = TT(f, k);
        if (g > f && feat->region()[f] != feat->region()[g] && plain->region()[f] == plain->region()[g])
          segments.push_back({s.F(f, k), s.F(f, (k + 1) % 3)});
      }
    added = mesh::segment_projector(s.V, segments);
  }

  // Whether a cell of r (a mesh of s) is inverted within a spacing of the curves patch_edges adds.
  bool inverted_near_added(const OverlayResult& r) const {
    if (added.empty() || inverted(r.quality) == 0) return false;
    const quality::CellMetrics metrics = quality::compute_metrics(r.mesh);
    for (int c = 0; c < r.mesh.num_cells(); ++c) {
      if (metrics.scaled_jacobian(c) > 0) continue;
      for (int i = 0; i < mesh::node_count(r.mesh.type(c)); ++i) {
        const Eigen::Vector3d x = r.mesh.V.row(r.mesh.cells(c, i)).transpose();
        if ((added.project(x) - x).norm() <= r.spacing) return true;
      }
    }
    return false;
  }
};

// The grids of one overlay_mesh run over the surface `s` (in the frame; `ss` its stretched copy
// when the spacings differ by `stretch`), with its features, local sizes and ranking.
class Grids {
 public:
  Grids(const mesh::SurfaceMesh& s, const mesh::SurfaceMesh& ss, const Eigen::Vector3d& stretch, const FeatureSets& fs,
        const LocalSizeField& field, const Ranking& rank, const OverlayOptions& opt)
      : s_(s), ss_(ss), stretch_(stretch), stretched_((stretch.array() != 1.0).any()), fs_(fs), field_(field), rank_(rank),
        opt_(opt) {}

  int made() const { return grids_; }

  // One grid of spacing h with the core rule `o` asks for and the features `f` (`sf`: theirs on
  // the stretched surface), stretched when the spacings differ; h is first made to meet the local
  // sizes. A mesh that lost part of the solid is not mended when `unmended_if_lost`
  // (mesh_with_grid).
  OverlayResult features_grid(Eigen::Vector3d& h, const OverlayOptions& o, const SurfaceFeatures& f,
                              const SurfaceFeatures* sf, bool unmended_if_lost) {
    ++grids_;
    const auto t0 = std::chrono::steady_clock::now();
    const Local local = local_refinement(h, o, field_);
    const double lost_at = unmended_if_lost ? o.lost_volume : 0.0;
    OverlayResult r;
    if (!stretched_) {
      r = mesh_with_grid(s_, f, h, o, nullptr, local, lost_at);
    } else {
      const Stretch st{stretch_, &s_, &f};
      r = mesh_with_grid(ss_, *sf, Eigen::Vector3d::Constant(h.maxCoeff()), o, &st, local, lost_at);
      const Eigen::Vector3d spacing = Eigen::Vector3d::Constant(r.spacing).cwiseQuotient(stretch_);
      r.spacing = spacing.maxCoeff();
      r.thinnest = spacing.minCoeff() / std::pow(3.0, r.octree_levels);
    }
    r.seconds = seconds_since(t0);  // this grid's
    return r;
  }

  // The grid with the surface's features; where cells stay inverted within a spacing of a curve
  // patch_edges added, the same grid without those curves too (an extra mesh: up to
  // max_cells_for_extra cells), the better kept (fewer CAD edges followed, rather than
  // inversions). With `finer_follows` (a finer grid is made after this one when it lost part of
  // the solid), a mesh that lost part of the solid is neither mended nor made again without the
  // curves: mending changes no ranking among such meshes (Ranking::better).
  OverlayResult one_grid(Eigen::Vector3d& h, const OverlayOptions& o, bool finer_follows) {
    const Eigen::Vector3d asked = h;
    OverlayResult r = features_grid(h, o, *fs_.feat, fs_.sfeat.get(), finer_follows);
    r.patch_edges = fs_.plain != nullptr;
    if (r.core_cells + r.buffer_cells > o.max_cells_for_extra || !fs_.inverted_near_added(r)) return r;
    if (finer_follows && rank_.lost(r)) return r;
    Eigen::Vector3d h2 = asked;
    try {
      // Beside a mesh that kept the part, one that lost some never wins: it is not mended then.
      OverlayResult r2 = features_grid(h2, o, *fs_.plain, fs_.splain.get(), !rank_.lost(r));
      say(fmt("overlay: spacing %g without the edges between tangent or coplanar faces: ", h2.maxCoeff()) + rank_.summary(r2));
      if (rank_.better(r2, r)) r = std::move(r2);
    } catch (const GeometryError& e) {
      say(std::string("overlay: without the edges between tangent or coplanar faces: ") + e.what());
    }
    return r;
  }

  // One more grid of spacing h with options o (`what` says which in the log), kept in `into` when
  // better; not mended when it lost part of the solid and `into` did not (it cannot win then).
  void extra_grid(Eigen::Vector3d h, const OverlayOptions& o, const char* what, OverlayResult& into) {
    opt_.deadline.check("overlay");
    try {
      OverlayResult r = one_grid(h, o, !rank_.lost(into));
      say(fmt("overlay: spacing %g", h.maxCoeff()) + what + ": " + rank_.summary(r));
      if (rank_.better(r, into)) into = std::move(r);
    } catch (const GeometryError& e) {
      say(fmt("overlay: spacing %g", h.maxCoeff()) + what + ": " + e.what());
    }
  }

 private:
  void say(const std::string& m) const {
    if (opt_.log) opt_.log(0, m);
  }
  const mesh::SurfaceMesh& s_;
  const mesh::SurfaceMesh& ss_;
  const Eigen::Vector3d stretch_;
  const bool stretched_;
  const FeatureSets& fs_;
  const LocalSizeField& field_;
  const Ranking& rank_;
  const OverlayOptions& opt_;
  int grids_ = 0;
};

}  // namespace

OverlayResult overlay_mesh(const mesh::SurfaceMesh& surface, const OverlayOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  auto say = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  if (surface.F.rows() == 0) throw GeometryError("the surface has no triangles");
  segmentation::CubeFrame frame;
  if (opt.align) frame = segmentation::cube_frame(surface, opt.frame_options);
  const mesh::SurfaceMesh s = frame.turned() ? segmentation::rotated(surface, frame.rotation) : surface;
  const double size = opt.size > 0 ? opt.size : segmentation::frame_diagonal(surface, frame.rotation) / 30.0;
  if (!(size > 0) || !std::isfinite(size)) throw GeometryError("the surface has no extent");
  const Eigen::Vector3d extent = (s.V.colwise().maxCoeff() - s.V.colwise().minCoeff()).transpose();
  Eigen::Vector3d h0 = grid_spacing(extent, size, opt.across, opt.max_cell_ratio, opt.min_size);
  const double reference = mesh::enclosed_volume(s.V, s.F);
  const Ranking rank{reference, opt};
  // A grid of unequal spacings (a plate, a rod) is laid as cubes over the surface stretched per
  // axis by hmax / h: closest points, the buffer's depth and the optimiser then see the cells as
  // cubes, and the mesh, stretched back, stays valid (the map is affine with a positive determinant).
  const Eigen::Vector3d stretch = Eigen::Vector3d::Constant(h0.maxCoeff()).cwiseQuotient(h0);
  const bool stretched = (stretch.array() != 1.0).any();
  const mesh::SurfaceMesh ss = stretched ? scaled(s, stretch) : mesh::SurfaceMesh{};
  auto wall_factor = [&](double across) { return walls_factor(stretched ? ss : s, h0, extent, across, opt); };
  if (opt.wall_across > 0) h0 *= wall_factor(opt.wall_across);
  const FeatureSets fs(s, stretched ? &ss : nullptr, opt.features);
  // The polylines of local sizes on edges go where the surface went: into the frame, stretched.
  const Eigen::Matrix3d to_grid = (frame.turned() ? Eigen::Matrix3d(frame.rotation.transpose()) : Eigen::Matrix3d::Identity()) *
                                  Eigen::Matrix3d(stretch.asDiagonal());
  const LocalSizeField field = opt.local_sizes.empty() ? LocalSizeField()
                                                       : LocalSizeField(stretched ? ss : s, opt.local_sizes, opt.growth_rate, to_grid);
  Grids grid(s, ss, stretch, fs, field, rank, opt);
  OverlayResult best;
  bool have = false;
  std::string why;
  int finer_for_quality = 0;
  // The spacings asked of the halvings so far: a grid for the walls of one of them (its factor cut
  // at 1 / max_wall_refinement, a power of 2) would be the same mesh again.
  std::vector<Eigen::Vector3d> halvings;
  // Cells left inverted on a part with thin walls: one more grid, whose spacing gives the walls
  // wall_fallback cells across (wall_f times h0, measured once), the better kept; made once. With
  // `next` (the spacing of the halving that would follow), only when it is finer than that
  // halving by at most kWallsFirst (the halving would leave the walls fewer cells across for a
  // saving of at most kWallsFirst^3 in cells), or coarser (fewer cells: cheapest first). After a
  // halving (`now`, the spacing of the grid that kept inverted cells; 0 before the first), only
  // when it saves at least a quarter of the halving's cells (kWallsFirst) and is finer than `now`
  // by kWallsFirst too (not nearly the grid that failed). walls_due says whether it is to be made
  // (`next` 0: after the halvings); walls_grid makes it and returns its longest spacing (also when
  // it had been made as a halving).
  double wall_f = 0;
  bool walls_made = false;
  constexpr double kWallsFirst = 0.75;
  auto walls_due = [&](double next, double now) {
    if (wall_f == 0) wall_f = opt.wall_across == 0 && opt.wall_fallback > 0 ? wall_factor(opt.wall_fallback) : 1.0;
    const double hw = wall_f * h0.maxCoeff();
    const bool in_place = hw >= kWallsFirst * next && hw <= (1 + 1e-9) * next;
    const bool cheaper = hw > (1 + 1e-9) * next &&
                         (now == 0 || (std::pow(next / hw, 3) <= kWallsFirst && hw <= kWallsFirst * now));
    return !walls_made && wall_f < 1 && (next == 0 || in_place || cheaper);
  };
  auto walls_grid = [&]() {
    walls_made = true;
    const Eigen::Vector3d h = h0 * wall_f;
    const double hw = h.maxCoeff();
    for (const Eigen::Vector3d& made : halvings)
      if ((made - h).norm() <= 1e-9 * h.norm()) {
        say(fmt("overlay: the grid for the walls has the spacing %g, already meshed", h.maxCoeff()));
        return hw;
      }
    grid.extra_grid(h, opt, " for the walls", best);
    return hw;
  };
  std::optional<Eigen::Vector3d> unmended;  // the spacing of `best` when it was not mended
  auto above_min_size = [&](const Eigen::Vector3d& x) { return x.minCoeff() >= opt.min_size * (1 - 1e-9); };
  for (int k = 0; k <= opt.refinements; ++k) {
    Eigen::Vector3d h = h0 / std::pow(2.0, k);
    if (k > 0 && !above_min_size(h)) {
      why += fmt("; halving the spacing would give cells shorter than the min size %g", opt.min_size);
      if (have) say(fmt("overlay: a finer grid would have cells shorter than the min size %g; keeping this one", opt.min_size));
      break;
    }
    opt.deadline.check("overlay");
    halvings.push_back(h);
    // Whether a grid that lost part of the solid is halved (halve_again); then it is not mended.
    const bool finer_follows = k < opt.refinements && above_min_size(h / 2) && !(opt.octree_levels > 0 && field.empty());
    OverlayResult r;
    try {
      r = grid.one_grid(h, opt, finer_follows);
    } catch (const GeometryError& e) {
      why = e.what();
      say("overlay: " + why + (k < opt.refinements ? "; halving the spacing" : ""));
      if (why.find("more than") != std::string::npos) break;
      continue;
    }
    say(fmt("overlay: spacing %g: ", h.maxCoeff()) + rank.summary(r));
    // Cells left inverted by the core by centres: the same grid with the core by corners too (its
    // buffer layer is thicker where the surface turns sharply), the better kept.
    if (opt.core_by_centres && field.empty() && inverted(r.quality) > 0 && !(finer_follows && rank.lost(r)) &&
        r.core_cells + r.buffer_cells <= opt.max_cells_for_extra) {
      OverlayOptions corners = opt;
      corners.core_by_centres = false;
      grid.extra_grid(h, corners, ", core by corners", r);
    }
    const double cells = r.core_cells + r.buffer_cells;
    const bool kept = !have || rank.better(r, best);
    if (kept) {
      unmended = finer_follows && rank.lost(r) ? std::optional<Eigen::Vector3d>(h) : std::nullopt;
      best = std::move(r);
      have = true;
    }
    // The grid kept left cells inverted: the grid for thin walls before the next halving when it
    // is not much finer, or coarser (fewer cells; cheapest first); in place of the halvings when
    // finer (the last grid, as when it follows them). Made coarser after a halving, it ends the
    // halvings only when it meets every target they are for: else the next halving is judged by
    // the grid kept before it (its inverted cells), so that a walls' grid that is merely valid
    // does not stop the finer grid that would raise the worst cell.
    std::optional<OverlayResult> before_walls;
    if (inverted(best.quality) > 0 && k < opt.refinements) {
      const double next = h.maxCoeff() / 2;
      if (walls_due(next, k == 0 ? 0.0 : h.maxCoeff())) {
        if (k > 0) before_walls = best;
        if (walls_grid() <= (1 + 1e-9) * next) break;
      }
    }
    const bool short_of = inverted(best.quality) > 0 || rank.volume_off(best) || quality::worst_sj(best.quality) < opt.refine_below_sj;
    if (!short_of || k == opt.refinements) break;
    if (before_walls) say("overlay: the grid for the walls misses a target; the halving follows");
    if (!halve_again(before_walls ? *before_walls : best, cells, kept, field.empty(), rank, opt, finer_for_quality)) break;
  }
  // The finer grids lost more of the solid (or were not made): the one kept, mended after all;
  // kept when better. Not when the mesh kept is whole (the walls' grid, made after it, may be):
  // a mesh that lost part of the solid never outranks it.
  if (have && unmended && inverted(best.quality) > 0 && rank.lost(best)) {
    try {
      OverlayResult mended = grid.one_grid(*unmended, opt, false);
      if (rank.better(mended, best)) best = std::move(mended);
    } catch (const GeometryError&) {  // it was made once: the same again
    }
  }
  // Cells still inverted after the halvings: the grid for thin walls, finer than a halving.
  if (have && inverted(best.quality) > 0 && walls_due(0, 0)) walls_grid();
  if (!have) throw GeometryError("overlay: " + why);
  best.grids = grid.made();
  best.frame = frame;
  if (frame.turned()) best.mesh.V = best.mesh.V * frame.rotation;  // x = R^T x_frame, row-wise
  best.seconds = seconds_since(t0);
  return best;
}

std::string to_text(const OverlayResult& r) {
  return fmt("overlay: spacing %g (thinnest %g", r.spacing, r.thinnest) +
         (r.octree_levels > 0 ? fmt(", %.0f octree levels), ", double(r.octree_levels)) : std::string("), ")) + fmt("%.0f core + %.0f buffer cells (%.0f dropped for a manifold core, %.0f facing another across the surface), ",
             double(r.core_cells), double(r.buffer_cells), double(r.dropped), double(r.parted)) +
         fmt("%.0f curve and %.0f corner nodes (%.0f corners missed, %.0f staircase nodes let off their curve), ",
             double(r.curve_nodes), double(r.corner_nodes), double(r.corners_missed), double(r.demoted)) +
         (r.prisms > 0 ? fmt("%.0f wedges along the curves, ", double(r.prisms)) : std::string()) +
         fmt("%.0f grids, %.2f s", double(r.grids), r.seconds);
}

}  // namespace hexdom::overlay
