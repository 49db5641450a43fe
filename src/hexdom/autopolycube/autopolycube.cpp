#include "hexdom/autopolycube/autopolycube.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "hexdom/autopolycube/blocks/apex_blocks.h"
#include "hexdom/autopolycube/repair/chart_graph.h"
#include "hexdom/autopolycube/blocks/collapse_slivers.h"
#include "hexdom/autopolycube/blocks/cut_along_grid.h"
#include "hexdom/autopolycube/blocks/grid_structure.h"
#include "hexdom/autopolycube/repair/plane_groups.h"
#include "hexdom/autopolycube/blocks/polycube_grid.h"
#include "hexdom/autopolycube/map/polycube_map.h"
#include "hexdom/autopolycube/repair/repair_labels.h"
#include "hexdom/autopolycube/repair/split_chords.h"
#include "hexdom/autopolycube/repair/split_oblique_faces.h"
#include "hexdom/quality/metrics.h"
#include "hexdom/segmentation/axis_labels.h"
#include "hexdom/segmentation/cube_frame.h"

namespace hexdom::autopolycube {

namespace {

// autopolycube of the labels turned into opt.frame; the results turned back (x = frame^T x_frame).
AutoPolycube autopolycube_in_frame(const mesh::SurfaceMesh& labels, const AutoPolycubeOptions& opt, AutoPolycube* progress) {
  AutoPolycubeOptions in_frame = opt;
  in_frame.frame.setIdentity();
  if (in_frame.size <= 0)  // the default size of the input, not of the turned box
    in_frame.size = segmentation::frame_diagonal(labels, Eigen::Matrix3d::Identity()) / 30.0;
  AutoPolycube local;
  AutoPolycube& r = progress ? *progress : local;
  auto back = [&] {
    for (Eigen::MatrixXd* V : {&r.structure.V, &r.patches.V, &r.labels.V, &r.polycube.V})
      if (V->rows()) *V = *V * opt.frame;
  };
  try {
    autopolycube(segmentation::rotated(labels, opt.frame), in_frame, &r);
  } catch (...) {
    back();
    throw;
  }
  back();
  return r;
}

/// The sliver strips, then (when no strip collapsed) the apexes of `gp` collapsed to prism and tet
/// blocks, with their counts and the blocks' quality in `r`.
void collapse_blocks(GridPolycube& gp, const mesh::SurfaceMesh& s, const std::vector<Eigen::Vector3d>& apexes,
                     const AutoPolycubeOptions& opt, AutoPolycube& r) {
  auto log = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  // The worst block and the inverted ones after a collapse changed the blocks.
  auto measure_blocks = [&]() {
    r.min_block_quality = 1.0;
    r.inverted_blocks = 0;
    for (int b = 0; b < gp.structure.num_cells(); ++b) {
      const double q = quality::signed_sj(gp.structure.type(b), quality::cell_points(gp.structure, b));
      r.min_block_quality = std::min(r.min_block_quality, q);
      r.inverted_blocks += q <= 0;
    }
  };
  if (opt.sliver_ratio > 0) {
    CollapseSliversOptions co;
    co.max_ratio = opt.sliver_ratio;
    co.deadline = opt.deadline;
    co.log = opt.log;
    const int before = gp.structure.num_nodes();
    const CollapseSlivers cs = collapse_slivers(gp, co);
    r.slivers = cs.collapsed;
    r.prism_blocks = cs.prisms;
    r.tet_blocks = cs.tets;
    if (cs.collapsed > 0) {
      r.boundary_vertices -= before - gp.structure.num_nodes();
      measure_blocks();
      log("slivers: " + std::to_string(cs.collapsed) + " strips collapsed, " + std::to_string(cs.prisms) + " prism and " +
          std::to_string(cs.tets) + " tet blocks, " + std::to_string(cs.merged_squares) + " squares joined a neighbouring patch");
    }
  }
  if (!apexes.empty() && opt.collapse_apexes) {
    // Apex vertices keep their indices in the patch surface (cut_along_grid).
    std::vector<int> apex_vertices;
    for (const Eigen::Vector3d& p : apexes) {
      int best = -1;
      double bd = 1e300;
      for (int v = 0; v < s.V.rows(); ++v) {
        const double dd = (s.V.row(v).transpose() - p).squaredNorm();
        if (dd < bd) { bd = dd; best = v; }
      }
      apex_vertices.push_back(best);
    }
    if (r.slivers > 0) {
      log("apexes: left as hex blocks under their caps (sliver strips collapsed)");
    } else {
      const int before = gp.structure.num_nodes();
      const CollapseApexes ca = collapse_apexes(gp, apex_vertices, opt.log);
      r.apexes_collapsed = ca.collapsed;
      if (ca.collapsed > 0) {
        r.tet_blocks += ca.tets;
        r.prism_blocks += ca.prisms;
        r.boundary_vertices -= before - gp.structure.num_nodes();
        measure_blocks();
      }
    }
  }
}

// The first six of `charts` by name, for a message.
std::string chart_names(const ChartGraph& g, const std::vector<int>& charts) {
  std::string names;
  for (size_t i = 0; i < charts.size() && i < 6; ++i) names += (i ? ", " : "") + chart_name(g, charts[i]);
  if (charts.size() > 6) names += ", ...";
  return names;
}

}  // namespace

AutoPolycube autopolycube(const mesh::SurfaceMesh& labels, const AutoPolycubeOptions& opt, AutoPolycube* progress) {
  if (opt.frame != Eigen::Matrix3d::Identity()) return autopolycube_in_frame(labels, opt, progress);
  segmentation::check_surface(labels);
  if (opt.level < 0 || opt.level > 6) throw GeometryError("level " + std::to_string(opt.level) + " is outside 0..6");
  if (opt.size < 0) throw GeometryError("the element size must not be negative");
  auto log = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  const double diag = (labels.V.colwise().maxCoeff() - labels.V.colwise().minCoeff()).norm();
  const double size = opt.size > 0 ? opt.size : diag / 30.0;
  AutoPolycube local;
  AutoPolycube& r = progress ? *progress : local;
  r = AutoPolycube{};
  r.cell = size * std::ldexp(1.0, opt.level);

  mesh::SurfaceMesh s = mesh::drop_unused_vertices(labels);
  r.labels = s;
  std::vector<Eigen::Vector3d> apexes;
  // The labellings mapped so far: the repair is deterministic, so meeting one again means it cycles.
  std::vector<std::pair<Eigen::MatrixXi, Eigen::VectorXi>> mapped;
  std::string last_problem;  // the problem the last round ended in, and how many rounds in a row
  int same_problem = 0;
  for (int attempt = 0;; ++attempt) {
    opt.deadline.check("autopolycube");
    if (attempt == 0 && opt.repaired) {
      if (opt.repaired->labels.F.rows() < s.F.rows() || opt.repaired->labels.V.rows() < s.V.rows())
        throw GeometryError("the repaired labelling given has fewer triangles or vertices than the labels");
      s = opt.repaired->labels;
      r.relabelled = opt.repaired->relabelled;
      r.chords = opt.repaired->chords;
      r.oblique_faces = opt.repaired->oblique_faces;
      apexes = opt.repaired->apexes;
      log("labels: the repair of an earlier run (" + std::to_string(r.relabelled) + " charts relabelled, " +
          std::to_string(r.chords) + " chords split)");
    } else {
      if (attempt == 0 && opt.oblique_faces) {
        ObliqueFaceOptions oo;
        oo.min_side = 2 * size;
        oo.log = opt.log;
        r.oblique_faces = static_cast<int>(split_oblique_faces(s, oo).size());
      }
      if (attempt == 0 && opt.apex_caps) {
        ApexCapOptions ao;
        ao.log = opt.log;
        ao.radius = opt.apex_cap_radius * size;
        for (int v : add_apex_caps(s, ao)) apexes.push_back(s.V.row(v).transpose());
      }
      RepairOptions ro;
      ro.max_relabels = std::max(0, opt.max_relabels - r.relabelled);
      ro.band_width = size;
      ro.deadline = opt.deadline;
      ro.log = opt.log;
      RepairResult rep = repair_labels(s, ro);
      s.patch = rep.label;
      r.labels = s;
      r.relabelled += rep.relabelled;
      if (!rep.remaining.empty()) {
        std::string m = std::to_string(rep.remaining.size()) + " problem" + (rep.remaining.size() == 1 ? "" : "s") +
                        " of the labelling remain after relabelling " + std::to_string(r.relabelled) + " charts:";
        for (size_t i = 0; i < rep.remaining.size() && i < 5; ++i) m += "\n  " + rep.remaining[i].message;
        throw GeometryError(m);
      }
      const ChartGraph g0 = chart_graph(s);
      int chords = 0;
      s = split_chords(s, g0, &chords);
      r.chords += chords;
    }
    r.labels = s;
    if (attempt == 0) r.repaired = RepairedLabels{s, r.relabelled, r.chords, apexes, r.oblique_faces};
    r.apexes = static_cast<int>(apexes.size());
    const ChartGraph g = chart_graph(s);
    const PlaneGroups pg = plane_groups(s, g);
    r.charts = g.num_charts();
    r.planes = pg.num_groups();

    PolycubeMapOptions mo;
    mo.cell = r.cell;
    mo.keep_widths = opt.keep_widths;
    mo.deadline = opt.deadline;
    mo.log = opt.log;
    // Curves whose spans only touch are separated too, unless that orders the planes in a cycle.
    PolycubeMap map;
    try {
      map = polycube_map(s, g, pg, mo);
    } catch (const GeometryError& e) {
      mo.separate_touching = false;
      log(std::string(e.what()) + ": again without separating curves whose spans only touch");
      map = polycube_map(s, g, pg, mo);
      r.widened += opt.keep_widths;  // the failed map's widths are not known: counted as used
    }
    r.widened += map.widened;
    r.polycube = polycube_surface(s, map);
    r.pushed = map.pushed;

    // Charts to blame: folds of the map first, then mismatches of the grid.
    std::vector<int> bad;
    std::string why;
    int folds = 0;
    for (int c = 0; c < g.num_charts(); ++c)
      if (map.flipped[c] > 0) { bad.push_back(c); folds += map.flipped[c]; }
    PolycubeGrid grid;
    if (bad.empty()) {
      grid = polycube_grid(s, g, pg, map);
      bad = grid.bad_charts;
      why = grid.problem;
    } else {
      why = "the polycube map folds " + std::to_string(folds) + " triangles";
    }
    if (!bad.empty()) {
      std::sort(bad.begin(), bad.end(), [&](int a, int b) { return g.area[a] < g.area[b]; });
      const std::string names = chart_names(g, bad);
      const double total = std::accumulate(g.area.begin(), g.area.end(), 0.0);
      if (attempt + 1 >= opt.max_attempts || r.relabelled >= opt.max_relabels || g.area[bad.front()] > opt.max_relabel_area * total)
        throw GeometryError(why + "; charts: " + names + " (after relabelling " + std::to_string(r.relabelled) + " charts)");
      for (const auto& [F, patch] : mapped)
        if (F.rows() == s.F.rows() && patch.size() == s.patch.size() && patch == s.patch && F == s.F)
          throw GeometryError(why + "; charts: " + names + " (the label repair came back to a labelling it had mapped, after " +
                              std::to_string(attempt + 1) + " rounds: it cycles)");
      same_problem = why == last_problem ? same_problem + 1 : 1;
      last_problem = why;
      if (same_problem >= opt.max_same_problem)
        throw GeometryError(why + "; charts: " + names + " (the same problem after " + std::to_string(same_problem) +
                            " rounds of relabelling: the label repair is not converging)");
      mapped.emplace_back(s.F, s.patch);
      log(why + ": relabelling " + chart_name(g, bad.front()));
      s.patch = relabel_chart(s, g, bad.front());
      ++r.relabelled;
      continue;
    }
    r.squares = static_cast<int>(grid.squares.size());
    r.blocks = static_cast<int>(grid.cells.size());
    log("polycube: " + std::to_string(r.charts) + " charts, " + std::to_string(r.planes) + " planes, " +
        std::to_string(r.squares) + " boundary squares, " + std::to_string(r.blocks) + " cells of " + std::to_string(r.cell));

    GridCut cut = cut_along_grid(s, g, map, grid);
    GridStructureOptions so;
    so.untangle_rounds = opt.untangle_rounds;
    so.log = opt.log;
    GridStructure st = grid_structure(grid, cut.grid_vertex, cut.patches.V, so);
    GridPolycube gp{std::move(grid), std::move(st.structure), std::move(st.grid), std::move(cut.patches),
                    std::move(cut.grid_vertex), std::move(cut.D)};
    r.boundary_vertices = st.boundary_vertices;
    r.interior_vertices = st.interior_vertices;
    r.min_block_quality = st.min_quality;
    r.inverted_blocks = st.inverted;
    collapse_blocks(gp, s, apexes, opt, r);
    r.patches = std::move(gp.patches);
    r.structure = std::move(gp.structure);
    break;
  }
  return progress ? *progress : local;
}

}  // namespace hexdom::autopolycube
