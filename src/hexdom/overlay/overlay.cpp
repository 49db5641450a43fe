#include "hexdom/overlay/overlay.h"

#include <chrono>
#include <cmath>

#include "hexdom/common/format.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/optimize/improve.h"
#include "hexdom/overlay/buffer.h"
#include "hexdom/overlay/core.h"
#include "hexdom/overlay/grid.h"

namespace hexdom::overlay {

namespace {

int inverted(const quality::QualityReport& q) { return quality::inverted_cells(q); }

// One grid of spacing h over `s` (in the frame): core, buffer layer, placement, optimiser. Throws
// GeometryError when the core is empty or in pieces.
OverlayResult mesh_with_grid(const mesh::SurfaceMesh& s, const SurfaceFeatures& feat, const Eigen::Vector3d& h,
                             const OverlayOptions& opt) {
  OverlayResult r;
  const Grid grid = grid_around(s.V, h);
  r.spacing = grid.h.maxCoeff();
  r.thinnest = grid.h.minCoeff();
  if (double(grid.num_cells()) > opt.max_grid_cells)
    throw GeometryError(fmt("a grid of spacing %g would have %.0f cells, more than %.0f", h.maxCoeff(),
                            double(grid.num_cells()), opt.max_grid_cells));
  const double margin = opt.margin * grid.h.minCoeff();
  const NodeField field = classify_nodes(grid, s, margin * 1.001);
  const Core core = core_cells(grid, field, margin);
  if (core.cells == 0) throw GeometryError(fmt("no grid cell of spacing %g lies inside with its margin", h.maxCoeff()));
  if (core.components > 1 && opt.log)
    opt.log(0, fmt("overlay: the cells of spacing %g inside fall into %.0f pieces; the largest kept, %.0f cells dropped",
                   h.maxCoeff(), core.components, core.apart));
  r.core_cells = core.cells;
  r.dropped = core.dropped;
  std::vector<std::array<int, 4>> outer;
  mesh::Mesh m = add_buffer_layer(core_mesh(grid, core), &outer);
  r.buffer_cells = static_cast<int>(outer.size());
  const Placement place_of = place_outer_nodes(m, outer, feat, 1.5 * h.maxCoeff());
  spread(m, outer, place_of, feat, opt.spread_passes, 0.25 * grid.h.minCoeff());
  r.curve_nodes = place_of.curve;
  r.corner_nodes = place_of.corner;
  r.corners_missed = place_of.corners_missed;
  r.demoted = place_of.demoted;
  optimize::ImproveOptions io;
  io.max_rounds = opt.max_rounds;
  io.mean_passes = opt.mean_passes;
  io.surface = s;
  io.kinds = place_of.kind;
  io.curve_neighbours = curve_neighbours(place_of, outer, feat);
  io.project = [&](int v, const Eigen::Vector3d& x) { return place(place_of, feat, v, x); };
  optimize::ImproveResult ir = optimize::improve(m, io);
  r.mesh = std::move(ir.mesh);
  r.quality = ir.after;
  return r;
}

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
  const Eigen::Vector3d h0 = grid_spacing(extent, size, opt.across, opt.max_cell_ratio);
  const double reference = mesh::enclosed_volume(s.V, s.F);
  auto volume_off = [&](const OverlayResult& r) {
    return reference != 0 && std::abs(r.quality.total_volume - reference) > opt.target_volume * std::abs(reference);
  };
  const SurfaceFeatures feat(s, opt.features);
  OverlayResult best;
  bool have = false;
  std::string why;
  int grids = 0, finer_for_quality = 0;
  for (int k = 0; k <= opt.refinements; ++k) {
    const Eigen::Vector3d h = h0 / std::pow(2.0, k);
    OverlayResult r;
    try {
      ++grids;
      r = mesh_with_grid(s, feat, h, opt);
    } catch (const GeometryError& e) {
      why = e.what();
      say("overlay: " + why + (k < opt.refinements ? "; halving the spacing" : ""));
      if (why.find("more than") != std::string::npos) break;
      continue;
    }
    // The better: a mesh of the whole part first (a grid too coarse for a thin part drops it:
    // volume off by more than lost_volume), and of two that both lost part of it the one that lost
    // less; then fewer inverted cells; then, when either misses the volume target, the smaller
    // volume error; then the higher worst SJ.
    auto error = [&](const OverlayResult& x) { return std::abs(x.quality.total_volume - reference); };
    auto lost = [&](const OverlayResult& x) { return reference != 0 && error(x) > opt.lost_volume * std::abs(reference); };
    const bool better =
        !have || (lost(r) != lost(best) ? lost(best)
                  : lost(r) ? error(r) < error(best)
                  : inverted(r.quality) != inverted(best.quality)
                      ? inverted(r.quality) < inverted(best.quality)
                      : (volume_off(best) || volume_off(r) ? error(r) < error(best)
                                                           : r.quality.hex.sj_min > best.quality.hex.sj_min));
    say(fmt("overlay: spacing %g: %.0f core + %.0f buffer cells, ", h.maxCoeff(), double(r.core_cells), double(r.buffer_cells)) +
        fmt("%.0f inverted, worst SJ %.3f, volume %+.2f%%", double(inverted(r.quality)), r.quality.hex.sj_min,
            reference != 0 ? 100 * (r.quality.total_volume - reference) / reference : 0.0));
    if (better) {
      best = std::move(r);
      have = true;
    }
    const bool short_of = inverted(best.quality) > 0 || volume_off(best);
    if (!short_of || ++finer_for_quality > opt.refinements_for_quality || k == opt.refinements) break;
    say(inverted(best.quality) > 0 ? "overlay: inverted cells remain; halving the spacing"
                                   : "overlay: the volume is off by more than the target; halving the spacing");
  }
  if (!have) throw GeometryError("overlay: " + why);
  best.grids = grids;
  best.frame = frame;
  if (frame.turned()) best.mesh.V = best.mesh.V * frame.rotation;  // x = R^T x_frame, row-wise
  best.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return best;
}

std::string to_text(const OverlayResult& r) {
  return fmt("overlay: spacing %g (thinnest %g), ", r.spacing, r.thinnest) + fmt("%.0f core + %.0f buffer cells (%.0f dropped for a manifold core), ",
             double(r.core_cells), double(r.buffer_cells), double(r.dropped)) +
         fmt("%.0f curve and %.0f corner nodes (%.0f corners missed, %.0f staircase nodes let off their curve), ",
             double(r.curve_nodes), double(r.corner_nodes), double(r.corners_missed), double(r.demoted)) +
         fmt("%.0f grids, %.2f s", double(r.grids), r.seconds);
}

}  // namespace hexdom::overlay
