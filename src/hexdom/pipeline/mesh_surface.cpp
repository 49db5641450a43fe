#include "hexdom/pipeline/mesh_surface.h"


#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>

#include "hexdom/common/format.h"
#include "hexdom/common/interrupt.h"
#include "hexdom/common/stopwatch.h"
#include "hexdom/common/time_limit.h"
#include "hexdom/generation/generate.h"
#include "hexdom/mesh/surface_check.h"
#include "hexdom/pipeline/choice.h"
#include "hexdom/pipeline/local_refinement.h"
#include "hexdom/pipeline/stretch.h"

namespace hexdom::pipeline {

namespace {
using quality::inverted_cells;
using quality::worst_sj;
// "turned by 45.0 degrees about (0, 0, 1)"
std::string frame_text(const segmentation::CubeFrame& f) {
  return fmt("turned by %.1f degrees about ", f.angle_degrees) + fmt("(%.3f, %.3f, %.3f)", f.axis.x(), f.axis.y(), f.axis.z());
}

using Clock = std::chrono::steady_clock;

// Relative volume error of a run against the input surface's enclosed volume.
double volume_error(const MeshSurfaceRun& r, double reference) {
  return reference != 0 ? std::abs(r.quality.total_volume - reference) / std::abs(reference) : 0.0;
}


bool edge_ratio_met(const MeshSurfaceRun& r, const MeshSurfaceOptions& opt) {
  return opt.target_edge_ratio <= 0 || quality::max_edge_ratio(r.quality) <= opt.target_edge_ratio;
}

// Whether run b is better than run a: fewer inverted cells; then the one whose worst SJ meets the
// target; then the one whose volume does; then the one whose edge ratio does; when both miss the
// edge-ratio target (and meet the SJ one), the smaller largest edge ratio; then the higher worst SJ.
bool better(const MeshSurfaceRun& b, const MeshSurfaceRun& a, double reference, const MeshSurfaceOptions& opt) {
  const int ib = inverted_cells(b.quality), ia = inverted_cells(a.quality);
  if (ib != ia) return ib < ia;
  const bool sb = worst_sj(b.quality) >= opt.target_sj, sa = worst_sj(a.quality) >= opt.target_sj;
  if (sb != sa) return sb;
  const bool vb = volume_error(b, reference) <= opt.target_volume, va = volume_error(a, reference) <= opt.target_volume;
  if (vb != va) return vb;
  if (b.local_fit.met != a.local_fit.met) return b.local_fit.met > a.local_fit.met;
  const bool eb = edge_ratio_met(b, opt), ea = edge_ratio_met(a, opt);
  if (eb != ea) return eb;
  if (!eb && sb) {
    const double rb = quality::max_edge_ratio(b.quality), ra = quality::max_edge_ratio(a.quality);
    if (rb != ra) return rb < ra;
  }
  return worst_sj(b.quality) > worst_sj(a.quality);
}

// The time and the segmentations another candidate cost, added to the run that is kept (and whether
// the time budget cut either short).
void add_costs(MeshSurfaceRun& kept, const MeshSurfaceRun& other) {
  for (int k = 0; k < 4; ++k) kept.seconds[k] += other.seconds[k];
  kept.segmentations += other.segmentations;
  kept.budget_passed = kept.budget_passed || other.budget_passed;
}

// segment -> autopolycube -> generate -> improve at one level, one polycube option set.
void mesh_once(const mesh::SurfaceMesh& surface, const MeshSurfaceOptions& opt, MeshSurfaceRun& r);


// Meshes `surface` once more with `other` (set to r's repaired labelling and lambda here) and keeps
// the better of that and `r` in `r` (see `better`), saying which with `kept_other` / `kept_r`; when
// the other candidate throws, says "`failed`: why; `keeping`" and keeps `r`. Returns whether
// `other` won.
bool try_candidate(const mesh::SurfaceMesh& surface, MeshSurfaceOptions other, const MeshSurfaceOptions& opt, double reference,
                   MeshSurfaceRun& r, const char* kept_other, const char* kept_r, const char* failed, const char* keeping) {
  auto say = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  other.polycube.repaired = &r.polycube.repaired;  // the same labelling: repaired once
  other.segment.edge_weight = r.edge_weight;
  other.retry_edge_weights.clear();
  other.first_run = nullptr;
  MeshSurfaceRun again;
  try {
    mesh_once(surface, other, again);
  } catch (const Error& e) {
    say(std::string(failed) + ": " + e.what() + "; " + keeping);
    if (dynamic_cast<const TimeoutError*>(&e)) r.budget_passed = true;
    return false;
  }
  if (better(again, r, reference, opt)) {
    say(kept_other);
    add_costs(again, r);
    r = std::move(again);
    return true;
  }
  say(kept_r);
  add_costs(r, again);
  return false;
}


// mesh_surface in the frame opt.segment.frame / opt.polycube.frame: the candidates.
MeshSurfaceRun mesh_candidates(const mesh::SurfaceMesh& surface, const MeshSurfaceOptions& opt, MeshSurfaceRun* progress) {
  MeshSurfaceRun local;
  MeshSurfaceRun& r = progress ? *progress : local;
  r = MeshSurfaceRun{};
  auto say = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  if (opt.first_run) r = *opt.first_run;
  else mesh_once(surface, opt, r);
  const double reference = mesh::enclosed_volume(surface.V, surface.F);
  // Before each further candidate: once the time budget has passed, the run so far is kept.
  bool said = false;
  auto out_of_time = [&] {
    if (!opt.deadline.passed()) return false;
    if (!said) say("time budget passed: keeping " + run_summary(r, reference));
    said = r.budget_passed = true;
    return true;
  };
  // A polycube that keeps the widths of holes is tried first; when its mesh misses a target, the one
  // with the least-squares plane offsets is tried too and the better kept (see `better`), unless
  // keeping the widths changed nothing (no hole: the same polycube again).
  bool widths = opt.polycube.keep_widths;
  if (opt.polycube.keep_widths && opt.try_without_widths && r.polycube.widened > 0 && !meets_targets(r, reference, opt) &&
      !out_of_time()) {
    say(run_summary(r, reference) + ": again without keeping the widths of holes");
    MeshSurfaceOptions other = opt;
    other.polycube.keep_widths = false;
    if (try_candidate(surface, other, opt, reference, r, "kept the polycube without the widths of holes: its mesh is better",
                      "kept the polycube with the widths of holes: its mesh is better", "without the widths of holes",
                      "keeping the first polycube"))
      widths = false;
  }
  // Tet and prism blocks at apexes first; when that mesh misses a target, the hex blocks under the
  // caps are meshed too and the better kept (a blunt tip's hex corner can beat the tets' prisms).
  if (r.polycube.apexes_collapsed > 0 && opt.try_hex_apexes && !meets_targets(r, reference, opt) && !out_of_time()) {
    say(run_summary(r, reference) + " with tet blocks at the apexes: again with hex blocks under the caps");
    MeshSurfaceOptions other = opt;
    other.polycube.keep_widths = widths;
    other.polycube.collapse_apexes = false;
    try_candidate(surface, other, opt, reference, r, "kept the hex blocks under the caps: their mesh is better",
                  "kept the tet blocks at the apexes: their mesh is better", "hex blocks under the caps",
                  "keeping the tet blocks");
  }
  const int inverted = inverted_cells(r.quality);
  const bool nearly = inverted == 0 && worst_sj(r.quality) < opt.refine_below_sj;
  if ((inverted > 0 || nearly) && opt.level > 0 && opt.refine_when_inverted && !out_of_time()) {
    if (nearly)
      say(fmt("worst SJ %.3f at level %.0f (below %.2f): again with level %.0f (grid of half the spacing), the better kept", worst_sj(r.quality),
              opt.level, opt.refine_below_sj, opt.level - 1));
    else
      say(fmt("%.0f inverted cells at level %.0f: again with level %.0f (grid of half the spacing)", inverted, opt.level,
              opt.level - 1));
    MeshSurfaceOptions finer = opt;
    finer.first_run = nullptr;
    finer.level = opt.level - 1;
    finer.segment.edge_weight = r.edge_weight;
    finer.polycube.repaired = &r.polycube.repaired;  // the repair does not depend on the level
    MeshSurfaceRun again;
    try {
      mesh_candidates(surface, finer, &again);
    } catch (const Error& e) {
      say(std::string("level ") + std::to_string(finer.level) + ": " + e.what() + "; keeping level " + std::to_string(opt.level));
      if (dynamic_cast<const TimeoutError*>(&e)) r.budget_passed = true;
      return progress ? *progress : local;
    }
    const int inverted2 = inverted_cells(again.quality);
    if (better(again, r, reference, opt)) {
      add_costs(again, r);
      r = std::move(again);
    } else {
      say(fmt("level %.0f is no better (%.0f inverted, worst SJ %.3f); keeping level %.0f", finer.level, inverted2,
              worst_sj(again.quality), opt.level));
      r.budget_passed = r.budget_passed || again.budget_passed;
    }
  }
  return progress ? *progress : local;
}

}  // namespace

bool meets_targets(const MeshSurfaceRun& r, double reference, const MeshSurfaceOptions& opt) {
  return inverted_cells(r.quality) == 0 && worst_sj(r.quality) >= opt.target_sj && volume_error(r, reference) <= opt.target_volume;
}

std::string run_summary(const MeshSurfaceRun& r, double reference) {
  return (r.method == Method::Overlay ? std::string("overlay") : fmt("level %.0f", r.level)) +
         fmt(": worst SJ %.3f, %.0f inverted, volume %+.2f%%", worst_sj(r.quality), inverted_cells(r.quality),
             100.0 * (r.quality.total_volume - reference) / (reference != 0 ? reference : 1.0)) +
         fmt(", max edge ratio %.1f", quality::max_edge_ratio(r.quality)) +
         (r.local_fit.ratio.empty() ? std::string()
                                    : fmt(", local sizes met %.0f of ", double(r.local_fit.met)) +
                                          fmt("%.0f", double(r.local_fit.ratio.size())));
}

bool meets_path_targets(const MeshSurfaceRun& r, double reference, const MeshSurfaceOptions& opt) {
  return meets_targets(r, reference, opt) && edge_ratio_met(r, opt) && r.local_fit.all_met();
}

bool better_run(const MeshSurfaceRun& b, const MeshSurfaceRun& a, double reference, const MeshSurfaceOptions& options) {
  return better(b, a, reference, options);
}

namespace {

// The overlay path on `surface` into r (everything in r replaced).
void run_overlay(const mesh::SurfaceMesh& surface, const MeshSurfaceOptions& opt, MeshSurfaceRun& r) {
  r = MeshSurfaceRun{};
  r.method = Method::Overlay;
  r.stage = "overlay";
  overlay::OverlayOptions oo = opt.overlay;
  oo.size = opt.size;
  oo.min_size = opt.min_size;
  if (opt.across_thin > 0) oo.across = opt.across_thin + 1;
  oo.align = opt.align;
  oo.max_edge_ratio = opt.target_edge_ratio;
  oo.log = opt.verbose ? opt.log : LogCallback();
  oo.deadline = opt.deadline;
  oo.threads = opt.threads;
  r.overlay = overlay::overlay_mesh(surface, oo);
  r.mesh = std::move(r.overlay.mesh);
  r.overlay.mesh = mesh::Mesh{};
  r.quality = r.overlay.quality;
  r.frame = r.overlay.frame;
  r.seconds[3] = r.overlay.seconds;
  r.stage = "done";
  if (opt.log) opt.log(0, overlay::to_text(r.overlay));
}

MeshSurfaceRun mesh_polycube(const mesh::SurfaceMesh& surface, const MeshSurfaceOptions& opt, MeshSurfaceRun* progress);

}  // namespace

void keep_polycube_attempt(const MeshSurfaceRun& attempt, MeshSurfaceRun& overlay) {
  overlay.labels = attempt.labels;
  overlay.polycube = attempt.polycube;
  overlay.edge_weight = attempt.edge_weight;
  overlay.level = attempt.level;
  overlay.keep_widths = attempt.keep_widths;
  overlay.collapse_apexes = attempt.collapse_apexes;
  overlay.stretch = attempt.stretch;
}

std::string method_name(Method m) { return m == Method::Auto ? "auto" : m == Method::Polycube ? "polycube" : "overlay"; }

Method method_from_name(const std::string& name) {
  for (Method m : {Method::Auto, Method::Polycube, Method::Overlay})
    if (method_name(m) == name) return m;
  throw InputError("unknown meshing method '" + name + "': auto, polycube or overlay");
}

std::vector<char> snap_face_only(const MeshSurfaceRun& run) {
  std::vector<char> out;
  const std::vector<optimize::NodeKind>& kind = run.overlay.node_kind;
  if (run.method != Method::Overlay || static_cast<int>(kind.size()) != run.mesh.num_nodes()) return out;
  out.assign(kind.size(), 0);
  for (size_t v = 0; v < kind.size(); ++v) out[v] = kind[v] == optimize::Surface;
  return out;
}

void check_size_bounds(const MeshSurfaceOptions& opt) {
  if (opt.min_size < 0 || opt.max_size < 0)
    throw InputError(fmt("the min size (%g) and the max size (%g) must not be negative", opt.min_size, opt.max_size));
  if (opt.min_size > 0 && opt.max_size > 0 && opt.min_size > opt.max_size)
    throw InputError(fmt("the min size %g is larger than the max size %g", opt.min_size, opt.max_size));
  overlay::check_growth_rate(opt.overlay.growth_rate);
}

double bounded_size(double size, const MeshSurfaceOptions& opt) {
  check_size_bounds(opt);
  if (opt.max_size > 0) size = std::min(size, opt.max_size);
  if (opt.min_size > 0) size = std::max(size, opt.min_size);
  return size;
}

double element_size(const mesh::SurfaceMesh& surface, const MeshSurfaceOptions& opt) {
  double size = opt.size;
  if (size <= 0) {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    if (opt.align && surface.F.rows() > 0) {
      const segmentation::CubeFrame frame = segmentation::cube_frame(surface, opt.frame_options);
      if (frame.turned()) rotation = frame.rotation;
    }
    size = segmentation::frame_diagonal(surface, rotation) / 30.0;
  }
  return bounded_size(size, opt);
}

Deadline polycube_deadline(const MeshSurfaceOptions& opt) {
  if (opt.deadline) return opt.deadline;
  return opt.method == Method::Auto ? Deadline::in(opt.polycube_seconds) : Deadline();
}

std::string polycube_failure_note(const Error& e, const std::string& stage) {
  if (const auto* t = dynamic_cast<const TimeoutError*>(&e))
    return fmt("the polycube path stopped after its time budget of %g s at stage ", t->budget()) + stage;
  const std::string what = e.what();
  return "the polycube path failed at stage " + stage + ": " + what.substr(0, what.find('\n'));
}

void check_order(int order) {
  if (order != 1 && order != 2) throw InputError(fmt("element order %g: the order is 1 or 2", order));
}

MeshSurfaceRun mesh_surface(const mesh::SurfaceMesh& input, const MeshSurfaceOptions& opt, MeshSurfaceRun* progress) {
  if (opt.time_limit > 0) {
    MeshSurfaceOptions inner = opt;
    inner.time_limit = 0;
    MeshSurfaceRun local;
    MeshSurfaceRun& r = progress ? *progress : local;
    run_with_time_limit(opt.time_limit, [&] { mesh_surface(input, inner, &r); });
    return r;
  }
  check_order(opt.order);
  if (opt.order == 2) {
    MeshSurfaceOptions first = opt;
    first.order = 1;
    MeshSurfaceRun local;
    MeshSurfaceRun& r = progress ? *progress : local;
    mesh_surface(input, first, &r);
    r.stage = "second order";
    r.mesh = optimize::second_order_on_surface(r.mesh, input, opt.curve, &r.second_order);
    r.quality = quality::quality_report(r.mesh);
    if (opt.log) opt.log(0, second_order_text(r.second_order));
    check_interrupt("mesh");
    r.stage = "done";
    return r;
  }
  MeshSurfaceRun local;
  MeshSurfaceRun& r = progress ? *progress : local;
  r.stage = "check";
  // The input checked before any stage: closed, one orientation, facing out of the solid (an
  // inside-out shell turned around, with a warning), not crossing itself.
  mesh::SurfaceMesh checked;
  if (opt.check_input) {
    checked = input;
    mesh::SurfaceCheckOptions co;
    co.several_solids = true;
    const mesh::SurfaceCheck check = mesh::check_solid_surface(checked, opt.input_name, co);
    for (const std::string& w : check.warnings)
      if (opt.log) opt.log(1, w);
    if (check.solids > 1) {
      overlay::check_local_sizes(opt.overlay.local_sizes, checked, opt.input_name);  // the faces asked for are on some solid
      // Each solid on its own, then put together; the checks are done.
      MeshSurfaceOptions so = opt;
      so.check_input = false;
      std::vector<mesh::SurfaceMesh> parts = mesh::split_solids(checked, check);
      std::vector<MeshSurfaceRun> runs(parts.size());
      for (size_t k = 0; k < parts.size(); ++k) {
        const std::string which = fmt("solid %.0f of ", k + 1.0) + fmt("%.0f", static_cast<double>(parts.size()));
        if (opt.log) opt.log(0, which + fmt(" (%.0f triangles)", static_cast<double>(parts[k].F.rows())));
        so.input_name = opt.input_name + ", " + which;
        try {
          mesh_surface(parts[k], so, &runs[k]);
        } catch (const Error&) {
          r = std::move(runs[k]);
          if (opt.log) opt.log(1, opt.input_name + ": " + which + " gave no mesh");
          throw;
        }
      }
      merge_solid_runs(std::move(runs), r);
      r.touching = check.touching;
      return r;
    }
  }
  const mesh::SurfaceMesh& surface = opt.check_input ? checked : input;
  MeshSurfaceOptions so = opt;  // the element size fixed within its bounds
  if (opt.check_input) overlay::check_local_sizes(opt.overlay.local_sizes, surface, opt.input_name);
  if (opt.max_size != 0 || opt.min_size != 0) {
    so.size = element_size(surface, opt);
    if (opt.log) opt.log(0, fmt("size: %g (min size %g, max size %g; 0: none)", so.size, opt.min_size, opt.max_size));
  }
  MeshSurfaceOptions po = so;  // the polycube path's options: its deadline fixed now
  po.deadline = polycube_deadline(so);
  // One path into `run`, with how it meets the local sizes.
  auto mesh_path = [&](const MeshSurfaceOptions& o, MeshSurfaceRun& run) {
    if (o.method == Method::Overlay) run_overlay(surface, o, run);
    else mesh_polycube(surface, o, &run);
    if (!o.overlay.local_sizes.empty()) {
      run.local_fit = local_size_fit(run.mesh, surface, o.overlay.local_sizes);
      if (o.log) o.log(0, local_fit_text(run.local_fit, o.overlay.local_sizes));
    }
  };
  if (so.method == Method::Overlay) {
    mesh_path(so, r);
  } else if (so.method == Method::Polycube) {
    mesh_path(po, r);
  } else {
    const double reference = mesh::enclosed_volume(surface.V, surface.F);
    choose_path(
        so, reference, mesh_path,
        [](MeshSurfaceRun& run) -> MeshSurfaceRun& { return run; }, [](const MeshSurfaceRun&) { return MeshSurfaceRun{}; },
        [](const MeshSurfaceRun& run) { return run; }, r);
  }
  check_interrupt("mesh");  // interrupted after the stages' last look: no result
  r.surface_volume = mesh::enclosed_volume(surface.V, surface.F);
  return r;
}

namespace {

MeshSurfaceRun mesh_polycube(const mesh::SurfaceMesh& surface, const MeshSurfaceOptions& opt, MeshSurfaceRun* progress) {
  MeshSurfaceOptions o = opt;
  segmentation::CubeFrame frame;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  if (opt.segment.frame != I || opt.polycube.frame != I) {
    if (opt.segment.frame != opt.polycube.frame)
      throw GeometryError("mesh_surface: the segmentation's frame and the polycube's differ");
    frame = segmentation::frame_of(opt.segment.frame);
  } else if (opt.align && surface.F.rows() > 0) {
    frame = segmentation::cube_frame(surface, opt.frame_options);
    if (frame.turned()) {
      o.segment.frame = o.polycube.frame = frame.rotation;
      // The default size of the part square to the frame, as if it had been modelled so.
      if (o.size <= 0) o.size = segmentation::frame_diagonal(surface, frame.rotation) / 30.0;
      if (opt.log)
        opt.log(0, "frame: the faces fit the axes " + frame_text(frame) +
                       fmt(" (fit %.3f, %.3f in the model's axes): segmenting and building the polycube in that frame",
                           frame.fit, frame.fit_identity));
    }
  }
  MeshSurfaceRun local;
  MeshSurfaceRun& r = progress ? *progress : local;
  const double diag = surface.V.rows() ? (surface.V.colwise().maxCoeff() - surface.V.colwise().minCoeff()).norm() : 0.0;
  const std::optional<Stretch> st =
      thin_stretch(surface, frame.rotation, o.size > 0 ? o.size : diag / 30.0, opt.across_thin, opt.max_cell_ratio,
                   opt.min_size);
  // A block of level s spans 2^s cells: a part fewer cells thick than that (the stretch's cells
  // across it, or its thinnest extent over the min size) gets a lower level, so that its block
  // across is not split into cells thinner than asked.
  double across = st ? st->across : std::numeric_limits<double>::infinity();
  if (opt.min_size > 0 && surface.V.rows() > 0) {
    const Eigen::MatrixXd F = surface.V * frame.rotation.transpose();
    across = std::min(across, (F.colwise().maxCoeff() - F.colwise().minCoeff()).minCoeff() / opt.min_size);
  }
  while (o.level > 0 && std::pow(2.0, o.level) > across * (1 + 1e-9)) --o.level;
  if (o.level != opt.level && opt.log)
    opt.log(0, fmt("thin part: %.3g cells across, level %.0f", across, double(o.level)));
  if (st) {  // thin along a frame axis: meshed stretched along it, in its frame
    if (opt.log)
      opt.log(0, fmt("thin part: cells of %.4g x %.4g x %.4g along the frame's axes", st->spacing(0), st->spacing(1),
                     st->spacing(2)) +
                     fmt(" (at least %g across, at most %g to 1): meshed stretched by ", opt.across_thin, opt.max_cell_ratio) +
                     fmt("(%.4g, %.4g, %.4g)", st->factor(0), st->factor(1), st->factor(2)));
    o.size = st->size;
    o.align = false;
    o.stretched_by = &*st;
    o.segment.frame = o.polycube.frame = I;
    mesh::SurfaceMesh s = surface;
    s.V = stretched(surface.V, *st);
    MeshSurfaceRun first;
    if (opt.first_run) {  // a run of this path: mapped back when it returned
      first = *opt.first_run;
      map_run(first, *st, true);
      o.first_run = &first;
    }
    try {
      mesh_candidates(s, o, &r);
    } catch (...) {
      map_run(r, *st, false);
      r.frame = frame;
      r.stretch = st->factor;
      throw;
    }
    map_run(r, *st, false);
    r.frame = frame;
    r.stretch = st->factor;
    return r;
  }
  try {
    mesh_candidates(surface, o, &r);
  } catch (...) {
    r.frame = frame;
    throw;
  }
  r.frame = frame;
  return r;
}

void mesh_once(const mesh::SurfaceMesh& surface, const MeshSurfaceOptions& opt, MeshSurfaceRun& r) {
  auto say = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  const LogCallback inner = opt.verbose ? opt.log : LogCallback();
  const double diag = surface.V.rows() ? (surface.V.colwise().maxCoeff() - surface.V.colwise().minCoeff()).norm() : 0.0;
  // Local sizes on the surface's faces: the polycube's cell chosen for them, its mesh refined there.
  const overlay::LocalSizeField field(surface, opt.overlay.local_sizes, opt.overlay.growth_rate);
  const double size = cell_for_local_sizes(field, opt.size > 0 ? opt.size : diag / 30.0, opt);

  // Segment, then build the polycube; when the labelling defeats autopolycube, segment again with
  // the next edge weight. The first failure is the one reported when none succeeds.
  std::vector<double> weights{opt.segment.edge_weight};
  for (double w : opt.retry_edge_weights)
    if (std::find(weights.begin(), weights.end(), w) == weights.end()) weights.push_back(w);
  autopolycube::AutoPolycubeOptions ao = opt.polycube;
  ao.size = size;
  ao.level = opt.level;
  ao.deadline = opt.deadline;
  ao.log = inner;
  std::exception_ptr first_error;
  mesh::SurfaceMesh first_labels;
  autopolycube::AutoPolycube first_polycube;
  std::vector<std::pair<double, Eigen::VectorXi>> defeated;  // labellings that failed, by edge weight
  auto fail_as_first = [&] {  // no weight left: the first failure, with its labels and polycube
    r.labels = std::move(first_labels);
    r.polycube = std::move(first_polycube);
    r.stage = "autopolycube";
    std::rethrow_exception(first_error);
  };
  for (size_t attempt = 0; attempt < weights.size(); ++attempt) {
    r.stage = "segment";
    opt.deadline.check("segment");  // also between the retries: each is a whole segmentation and polycube
    auto t = Clock::now();
    segmentation::CvtOptions so = opt.segment;
    so.edge_weight = weights[attempt];
    so.log = inner;
    r.labels = surface;
    r.labels.patch = segmentation::segment_cvt(surface, so).label;
    r.seconds[0] += seconds_since(t);
    ++r.segmentations;
    r.edge_weight = weights[attempt];
    say(fmt("segment: %.0f triangles labelled (lambda %g) in %.2f s", static_cast<double>(surface.F.rows()), weights[attempt],
            seconds_since(t)));
    // A labelling that an earlier weight gave and the polycube failed on fails the same way again
    // (autopolycube depends on the labels alone): not built twice.
    const auto same = std::find_if(defeated.begin(), defeated.end(), [&](const auto& d) { return d.second == r.labels.patch; });
    if (same != defeated.end()) {
      const bool last = attempt + 1 == weights.size();
      say(fmt("autopolycube: lambda %g labels the triangles as lambda %g did", weights[attempt], same->first) +
          (last ? std::string("; no further edge weight") : fmt("; segmenting again with lambda %g", weights[attempt + 1])));
      if (!last) continue;
      fail_as_first();
    }

    r.stage = "autopolycube";
    t = Clock::now();
    // A repair handed down by the caller belongs to the first edge weight's labelling only.
    ao.repaired = attempt == 0 && opt.polycube.repaired && opt.polycube.repaired->labels.F.rows() > 0 ? opt.polycube.repaired
                                                                                                      : nullptr;
    try {
      autopolycube::autopolycube(r.labels, ao, &r.polycube);
    } catch (const TimeoutError&) {  // no retry: the time is up
      r.seconds[1] += seconds_since(t);
      throw;
    } catch (const Error& e) {  // GeometryError (labelling) or MeshingError (cutting)
      r.seconds[1] += seconds_since(t);
      if (!first_error) {
        first_error = std::current_exception();
        first_labels = r.labels;
        first_polycube = r.polycube;
      }
      defeated.emplace_back(weights[attempt], r.labels.patch);
      if (attempt + 1 == weights.size()) fail_as_first();
      say(std::string("autopolycube: ") + e.what() + "; segmenting again with lambda " + fmt("%g", weights[attempt + 1]));
      continue;
    }
    r.seconds[1] += seconds_since(t);
    break;
  }
  say(fmt("autopolycube: %.0f charts (%.0f relabelled), %.0f blocks of %g", r.polycube.charts, r.polycube.relabelled,
          r.polycube.blocks, r.polycube.cell) +
      (r.polycube.prism_blocks + r.polycube.tet_blocks > 0
           ? fmt(" (%.0f prism, %.0f tet)", r.polycube.prism_blocks, r.polycube.tet_blocks)
           : std::string()) +
      fmt(", worst block SJ %.3f, in %.2f s", r.polycube.min_block_quality, r.seconds[1]));

  if (opt.stretched_by) {  // the polycube as the run will report it, mapped back, stretched again
    const Stretch& st = *opt.stretched_by;
    auto through_model = [&](const Eigen::MatrixXd& V) { return stretched(unstretched(V, st), st); };
    mesh::SurfaceMesh patches = r.polycube.patches;
    mesh::Mesh structure = r.polycube.structure;
    patches.V = through_model(patches.V);
    structure.V = through_model(structure.V);
    generate_and_improve(patches, structure, opt, r, &field);
  } else {
    generate_and_improve(r.polycube.patches, r.polycube.structure, opt, r, &field);
  }
  r.keep_widths = opt.polycube.keep_widths;
  r.collapse_apexes = opt.polycube.collapse_apexes;
  r.stage = "done";
}

}  // namespace

std::string worst_by_type(const quality::QualityReport& q) {
  std::string s;
  const std::pair<const char*, const quality::TypeStats*> types[] = {{"hex", &q.hex}, {"prism", &q.prism}, {"tet", &q.tet}};
  for (const auto& [name, t] : types)
    if (t->count > 0) s += (s.empty() ? std::string("worst ") + name + " SJ" : std::string(", ") + name) + fmt(" %.3f", t->sj_min);
  if (s.empty()) s = "no cells";
  return s + fmt(", %.0f inverted", quality::inverted_cells(q));
}


void generate_and_improve(const mesh::SurfaceMesh& patches, const mesh::Mesh& structure, const MeshSurfaceOptions& opt,
                          MeshSurfaceRun& r, const overlay::LocalSizeField* local) {
  auto say = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  const LogCallback inner = opt.verbose ? opt.log : LogCallback();
  r.stage = "generate";
  opt.deadline.check("generate");
  auto t = Clock::now();
  generation::GenerateOptions go;
  go.level = opt.level;
  go.relax_sweeps = opt.relax_sweeps;
  go.threads = opt.threads;
  go.log = inner;
  r.generated = generation::generate(patches, structure, go);
  if (local) refine_to_local_sizes(*local, patches, opt, r.generated);
  r.generated_quality = quality::quality_report(r.generated);
  r.seconds[2] = seconds_since(t);
  say(fmt("generate: %.0f cells, ", r.generated.num_cells()) + worst_by_type(r.generated_quality) +
      fmt(", in %.2f s", r.seconds[2]));

  r.stage = "improve";
  t = Clock::now();
  bool stopped = false;
  if (opt.improve) {
    optimize::ImproveOptions io = opt.improvement;
    io.max_edge_ratio = opt.target_edge_ratio;
    io.surface = patches;
    io.deadline = opt.deadline;  // stops early with its best so far: the generated mesh is a result
    io.threads = opt.threads;
    io.log = inner;
    optimize::ImproveResult ir = optimize::improve(r.generated, io);
    r.mesh = std::move(ir.mesh);
    r.quality = ir.after;
    stopped = ir.stopped;
    r.budget_passed = r.budget_passed || stopped;
  } else {
    r.mesh = r.generated;
    r.quality = r.generated_quality;
  }
  r.seconds[3] = seconds_since(t);
  say(fmt("improve: %.0f cells, ", r.mesh.num_cells()) + worst_by_type(r.quality) +
      (r.quality.hex.count > 0 ? fmt(", mean hex %.3f", r.quality.hex.sj_mean) : std::string()) +
      fmt(", in %.2f s", r.seconds[3]) + (stopped ? " (stopped early: time budget)" : ""));
  r.level = opt.level;
  r.stage = "done";
}

std::string to_text(const MeshSurfaceRun& r) {
  if (!r.solids.empty()) {
    std::string s;
    for (size_t k = 0; k < r.solids.size(); ++k) s += fmt("solid %.0f\n", k + 1.0) + to_text(r.solids[k]);
    return s;
  }
  if (r.method == Method::Overlay) return overlay::to_text(r.overlay) + "\nkept          " + choice_text(r) + "\n";
  std::string s;
  s += fmt("segment       %8.2f s\n", r.seconds[0]);
  s += fmt("autopolycube  %8.2f s  %5.0f charts, %5.0f blocks, h = %g\n", r.seconds[1], r.polycube.charts, r.polycube.blocks,
           r.polycube.cell);
  s += fmt("generate      %8.2f s  %8.0f cells\n", r.seconds[2], r.generated.num_cells());
  s += fmt("improve       %8.2f s  %8.0f cells\n", r.seconds[3], r.mesh.num_cells());
  s += "kept          " + choice_text(r) + "\n";
  return s;
}

std::string second_order_text(const optimize::SecondOrderReport& s) {
  const optimize::CurveReport& c = s.curve;
  return fmt("second order: %.0f boundary mid-edge nodes", s.boundary_mid_nodes) +
         (s.edge_targets ? fmt(" (%.0f on CAD edges, %.0f on faces)", s.edge_targets, s.face_targets) : std::string()) +
         fmt(", moved up to %.3g off their edges; %.0f placed", s.max_offset, c.placed) +
         fmt(", %.0f halfway or less, %.0f kept straight", c.shortened, c.straight) +
         fmt("; worst SJ %.4f, %.0f inverted", c.worst_sj, c.inverted) + fmt(" (%.2f s)", s.seconds);
}

std::string choice_text(const MeshSurfaceRun& r) {
  if (!r.solids.empty()) {
    std::string s = fmt("%.0f solids", static_cast<double>(r.solids.size()));
    for (size_t k = 0; k < r.solids.size(); ++k)
      s += fmt("; solid %.0f: ", k + 1.0) + method_name(r.solids[k].method) + ", " + choice_text(r.solids[k]);
    return s;
  }
  if (r.method == Method::Overlay)
    return fmt("overlay grid, spacing %g", r.overlay.spacing) + (r.frame.turned() ? ", frame: the axes " + frame_text(r.frame) : "");
  std::string s = fmt("level %.0f, lambda %g, ", r.level, r.edge_weight) +
                  (r.keep_widths ? "widths of holes kept" : "least-squares plane offsets");
  if (r.polycube.apexes > 0) s += r.collapse_apexes ? ", tet blocks at apexes" : ", hex blocks under the caps";
  if (r.frame.turned()) s += ", frame: the axes " + frame_text(r.frame);
  return s;
}

}  // namespace hexdom::pipeline
