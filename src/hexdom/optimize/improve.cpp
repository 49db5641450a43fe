#include "hexdom/optimize/improve.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "hexdom/common/format.h"
#include "hexdom/common/interrupt.h"
#include "hexdom/common/parallel_for.h"
#include "hexdom/common/stopwatch.h"
#include "hexdom/optimize/improver.h"
#include "hexdom/optimize/node_kinds.h"
#include "hexdom/optimize/pillow.h"
#include "hexdom/quality/metrics.h"

namespace hexdom::optimize {

using quality::QualityReport;
using quality::quality_report;
using quality::TypeStats;
using Vec = Eigen::Vector3d;

namespace {

// Whether cell c, changed since the input was optimised (ImproveOptions::optimised_at: the nodes
// were at `was`, they are at `now`), needs the smoothing: inverted, fallen below `worst_was` (the
// worst cell of `was`: it would lower the mesh's worst), or its edge ratio risen above `max_ratio`
// (when > 0). The optimisation rounds and the mean stage raise the others; smoothing them would
// only undo what the mean stage reached (and cost its passes again).
bool poor_cell(const mesh::Mesh& was, const mesh::Mesh& now, int c, double sj_now, double worst_was, double max_ratio) {
  if (sj_now <= 0 || sj_now < worst_was) return true;
  if (!(max_ratio > 0)) return false;
  const double r_now = quality::edge_ratio(now.type(c), quality::cell_points(now, c));
  return r_now > max_ratio && r_now > quality::edge_ratio(was.type(c), quality::cell_points(was, c));
}

// One candidate mesh on its way through the stages: `input`, pillowed or not, with its topology
// and the improver working on it.
class Run {
 public:
  // `input_kinds`: node_kinds of the input (with `sharp_in`). `layer`: the boundary faces to pillow
  // (smooth_layer_faces); null or empty: all of them. Throws GeometryError when the layer cannot be made.
  Run(const mesh::Mesh& input, const NodeKinds& input_kinds, const ImproveOptions& opt, bool with_pillow,
      const std::vector<char>* sharp_in, const BoundaryConstraints& cons, const std::function<void(const std::string&)>& log,
      const std::vector<char>* layer = nullptr)
      : with_pillow_(with_pillow), deadline_(opt.deadline), log_(log) {
    m_ = input;
    std::vector<char> sharp;
    if (sharp_in) sharp = *sharp_in;
    std::vector<int> copy;
    const bool partial = with_pillow && layer && !layer->empty();
    partial_ = partial;
    // The layer's edge nodes go back onto the surface after pillow_faces has checked the layer
    // (below), and that can invert a cell pillow_faces found valid. Where it does, the depth is halved at that cell's moved nodes and the layer made
    // again, as pillow_faces does for its own check.
    std::vector<double> scale(input.num_nodes(), 1.0);
    for (int attempt = 0;; ++attempt) {
      if (with_pillow) {
        m_ = pillow_faces(input, opt.pillow_depth, partial ? layer : nullptr, &copy, &scale, opt.pillow_share);
        r_.pillow_cells = m_.num_cells() - input.num_cells();
        sharp.clear();
        if (sharp_in) {  // the copies take the flags; old nodes under the layer are no longer on the boundary
          sharp.assign(m_.num_nodes(), 0);
          for (int v = 0; v < input.num_nodes(); ++v)
            if ((*sharp_in)[v]) sharp[copy[v] >= 0 ? copy[v] : v] = 1;
        }
      }
      // The pillowed boundary has the original geometry, so the angle test finds the same features.
      t_ = with_pillow ? node_kinds(m_, opt.feature_angle, sharp_in ? &sharp : nullptr) : input_kinds;
      if (!with_pillow && !opt.kinds.empty()) {
        t_.kind = opt.kinds;
        t_.curve_nbrs = opt.curve_neighbours;
      }
      if (!partial) break;
      std::vector<char> inverted_before(m_.num_cells(), 0);
      for (int c = 0; c < m_.num_cells(); ++c) inverted_before[c] = cell_sj(m_, c) <= 0;
      // Old nodes on the edge of the layer moved along the faces left out, in straight lines: back
      // onto the surface (and onto their feature curve when they moved along one).
      for (int v = 0; v < input.num_nodes(); ++v) {
        if (copy[v] < 0 || t_.node_faces[v].empty()) continue;
        Vec x = m_.V.row(v).transpose();
        if (t_.kind[v] == Curve && !cons.curves.empty()) x = cons.curves.project(x);
        if (t_.kind[v] != Interior) m_.V.row(v) = cons.surface.project(x).transpose();
      }
      if (attempt == 8) break;
      bool shrunk = false;
      for (int c = 0; c < m_.num_cells(); ++c) {
        if (inverted_before[c] || cell_sj(m_, c) > 0) continue;
        for (int i = 0; i < mesh::node_count(m_.type(c)); ++i) {
          const int v = m_.cells(c, i);
          if (v < input.num_nodes() && copy[v] >= 0 && scale[v] > 1.0 / 256) { scale[v] *= 0.5; shrunk = true; }
        }
      }
      if (!shrunk) break;
    }
    for (auto k : t_.kind) {
      r_.feature_nodes += k == Curve;
      r_.corner_nodes += k == Corner;
    }
    for (int v : opt.fixed_nodes) t_.kind[!copy.empty() && copy[v] >= 0 ? copy[v] : v] = Corner;  // never moved
    if (with_pillow && cons.project) {  // node numbers changed: the projection hook no longer applies
      unhooked_ = std::make_unique<BoundaryConstraints>(cons);
      unhooked_->project = nullptr;
    }
    imp_ = std::make_unique<Improver>(m_, t_, unhooked_ ? *unhooked_ : cons, thread_count(opt.threads));
    imp_->set_keep(opt.floor);
    if (!with_pillow && opt.optimised_at.rows() > 0) {
      // Where the input was optimised before: its passes start from the cells changed since.
      // Each node once in each list (mark_only marks around it).
      mesh::Mesh was = input;
      was.V = opt.optimised_at;
      std::vector<char> listed(m_.num_nodes(), 0), listed_poor(m_.num_nodes(), 0);
      std::vector<int> poor_start;  // nodes of the changed cells poor_cell finds, and changed_nodes
      auto add = [&](int v, std::vector<char>& seen, std::vector<int>& to) {
        if (!seen[v]) { seen[v] = 1; to.push_back(v); }
      };
      std::vector<double> sj_was(m_.num_cells());
      for (int c = 0; c < m_.num_cells(); ++c) sj_was[c] = cell_sj(was, c);
      const double worst_was = sj_was.empty() ? 1.0 : *std::min_element(sj_was.begin(), sj_was.end());
      for (int c = 0; c < m_.num_cells(); ++c) {
        const double sj_now = imp_->sj(c);
        if (!(std::abs(sj_was[c] - sj_now) > 1e-3)) continue;
        const bool poor = poor_cell(was, m_, c, sj_now, worst_was, opt.max_edge_ratio);
        for (int i = 0; i < mesh::node_count(m_.type(c)); ++i) {
          add(m_.cells(c, i), listed, start_);
          if (poor) add(m_.cells(c, i), listed_poor, poor_start);
        }
      }
      for (int v : opt.changed_nodes) add(v, listed, start_), add(v, listed_poor, poor_start);
      imp_->mark_only(poor_start);  // the first smoothing pass
      from_start_ = true;
    }
    log_(name() + (with_pillow ? " (" + std::to_string(r_.pillow_cells) + " cells added)" : "") +
         ": worst scaled Jacobian " + std::to_string(imp_->worst()) + "; " + std::to_string(r_.feature_nodes) +
         " feature-curve nodes, " + std::to_string(r_.corner_nodes) + " corners");
  }
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;

  std::string name() const {
    return with_pillow_ ? (partial_ ? "pillowed (smooth regions)" : "pillowed") : "without pillowing";
  }
  double worst() const { return imp_->worst(); }
  double worst_hex() const { return imp_->worst_hex(); }
  int rounds() const { return r_.rounds; }
  int inverted() const { return imp_->inverted(); }

  // Floors of the worst stage: none while cells are inverted (they would only slow untangling),
  // then each type's worst unless that type is (nearly) the worst of the mesh.
  void update_floors() {
    if (imp_->inverted() == 0) imp_->set_floors(-2, 0.05);
    else imp_->clear_floors();
  }

  // Smoothing and optimisation rounds until the worst cell stops improving.
  void worst_stage(int max_rounds) {
    const int stale_limit = 2;  // rounds without gain before stopping
    const auto t0 = std::chrono::steady_clock::now();
    double worst = imp_->worst();
    int stale = 0;
    // Untangling gets one more stale round: its gains are small but decisive.
    for (int round = 0; round < max_rounds && stale < stale_limit + (imp_->inverted() > 0); ++round) {
      update_floors();
      // Untangling: every node may help; on an input optimised before (optimised_at), the nodes
      // around its changes and around every node moved since. After the first round the smoothing
      // visits only the nodes whose neighbourhood a move changed (marked by the passes; the others
      // would be refused again, see climb_all), and every node may climb.
      if (imp_->inverted() > 0) {
        if (from_start_) imp_->mark_only(start_);
        else if (round == 0) imp_->mark_all();
        else imp_->climb_all();
      }
      imp_->smooth_pass();
      const double thr = std::max(worst + 0.2, 0.3);
      for (int k = 0; k < 4; ++k) imp_->optimize_round(thr);
      const double w = imp_->worst();
      // While cells are inverted every gain counts; after that, gains below 1e-3 do not show.
      stale = w > worst + (worst <= 0 ? 1e-4 : 1e-3) ? 0 : stale + 1;
      worst = std::max(worst, w);
      r_.rounds = round + 1;
      if (out_of_time()) break;
    }
    log_(name() + ": worst scaled Jacobian " + std::to_string(imp_->worst()) + imp_->worst_place() + " after " + std::to_string(r_.rounds) +
         " rounds (" + std::to_string(seconds_since(t0)) + " s)" + (r_.stopped ? ", stopped by the time budget" : ""));
  }

  // Mean-stage passes, each revisiting only the nodes near a move of the pass before, until a pass
  // raises the mean scaled Jacobian by less than `min_gain`. The worst cell is kept.
  void mean_stage(int max_passes, double min_gain) {
    const auto t0 = std::chrono::steady_clock::now();
    imp_->set_floors(0.0);
    if (from_start_) imp_->mark_only(start_);
    else imp_->mark_all();
    const double mean0 = imp_->mean();
    double mean = mean0;
    int passes = 0;
    while (passes < max_passes && !out_of_time()) {
      const int moved = imp_->mean_pass();
      ++passes;
      const double m1 = imp_->mean();
      const bool done = moved == 0 || m1 < mean + min_gain;
      mean = m1;
      if (done) break;
    }
    log_(name() + ": mean scaled Jacobian " + std::to_string(mean0) + " -> " + std::to_string(mean) + " in " +
         std::to_string(passes) + " passes (" + std::to_string(seconds_since(t0)) + " s)");
  }

  // Edge-ratio rounds (ImproveOptions::max_edge_ratio) in three steps of the scaled Jacobian bar,
  // each until no cell is above `target`, a round moves no node, or `max_rounds`: first each type's
  // worst scaled Jacobian is kept, then half its margin above `sj_floor`, then `sj_floor` alone
  // (a cell at or above it is not pushed below it; a cell below it gets no worse). The worst cell
  // gives way to the ratio one step at a time, never below the SJ target. A lower bar that leaves
  // the ratio above the target is kept too: above the SJ target the choice of meshes ranks a
  // smaller largest ratio before a higher worst SJ (pipeline::better_run), and a later run (the
  // snap's restoration) goes on from it.
  void ratio_stage(double target, double sj_floor, int max_rounds) {
    const double r0 = imp_->max_ratio();
    if (!(r0 > target)) return;
    const auto t0 = std::chrono::steady_clock::now();
    double worst[3];
    imp_->worst_by_type(worst);
    int rounds = 0;
    for (double keep : {1.0, 0.5, 0.0}) {
      double bar[3];
      for (int k = 0; k < 3; ++k) bar[k] = sj_floor + keep * std::max(0.0, worst[k] - sj_floor);
      for (int i = 0; i < max_rounds && !out_of_time(); ++i) {
        ++rounds;
        if (imp_->ratio_round(target, bar) == 0) break;
      }
      if (!(imp_->max_ratio() > target) || out_of_time()) break;
    }
    log_(name() + ": largest edge ratio " + fmt("%.3g", r0) + " -> " + fmt("%.3g", imp_->max_ratio()) + " in " +
         std::to_string(rounds) + " rounds (" + std::to_string(seconds_since(t0)) + " s)");
  }

  // The explicit stages: at least one pass or round, then as many as the time budget allows.
  int smooth(int passes) {
    int i = 0;
    for (; i < passes && (i == 0 || !out_of_time()); ++i) {
      update_floors();
      imp_->smooth_pass();
    }
    return i;
  }
  int optimize(int rounds) {
    int i = 0;
    for (; i < rounds && (i == 0 || !out_of_time()); ++i) {
      update_floors();
      imp_->optimize_round(std::max(imp_->worst() + 0.2, 0.3));
    }
    return i;
  }
  // Whether the time budget has passed (remembered in the result's `stopped`).
  bool out_of_time() {
    if (deadline_.passed()) r_.stopped = true;
    return r_.stopped;
  }
  bool stopped() const { return r_.stopped; }
  void set_rounds(int n) { r_.rounds = n; }
  // The optimisation rounds also search a pattern of directions around the worst cells (see
  // Improver::optimize_round). The run without a layer: where a polycube edge lies on a round, its
  // worst cell has two faces there, and their corners tie (docs/tuning-notes.md). A pillowed run turns it on only after its gradient rounds miss the bar (improve()).
  void search_pattern() { imp_->set_pattern(true); }

  ImproveResult finish() {
    r_.mesh = std::move(m_);
    r_.after = quality_report(r_.mesh, imp_->threads());
    return std::move(r_);
  }

 private:
  bool with_pillow_, partial_ = false;
  Deadline deadline_;
  std::function<void(const std::string&)> log_;
  ImproveResult r_;
  mesh::Mesh m_;
  NodeKinds t_;
  std::unique_ptr<BoundaryConstraints> unhooked_;  // a copy without the projection hook, for a pillowed mesh
  std::unique_ptr<Improver> imp_;
  bool from_start_ = false;  // ImproveOptions::optimised_at applies: passes start from start_
  std::vector<int> start_;   // nodes of the cells changed since the input was optimised
};

double worst_of(const QualityReport& q) {
  double w = 2;
  for (const TypeStats* s : {&q.hex, &q.prism, &q.tet})
    if (s->count) w = std::min(w, s->sj_min);
  return w;
}

}  // namespace

ImproveResult improve(const mesh::Mesh& input, const ImproveOptions& opt) {
  mesh::require_first_order(input, "improving a mesh");
  for (int c = 0; c < input.num_cells(); ++c)
    if (!mesh::is_volume(input.type(c)))
      throw GeometryError("cell " + std::to_string(c + 1) + " is a " + mesh::type_name(input.type(c)) +
                          ": improvement takes hex, prism and tet cells only");
  auto log = [&](const std::string& s) { if (opt.log) opt.log(0, s); };
  const bool recommended = !opt.pillow && opt.smooth == 0 && opt.optimize == 0;
  std::vector<char> sharp;
  const bool have_sharp = !opt.sharp_nodes.empty();
  if (have_sharp) {
    sharp.assign(input.num_nodes(), 0);
    for (int v : opt.sharp_nodes) {
      if (v < 0 || v >= input.num_nodes())
        throw GeometryError("sharp node " + std::to_string(v) + " is outside the mesh's " + std::to_string(input.num_nodes()) + " nodes");
      sharp[v] = 1;
    }
  }
  if (!opt.kinds.empty() && (static_cast<int>(opt.kinds.size()) != input.num_nodes() ||
                             opt.curve_neighbours.size() != opt.kinds.size()))
    throw GeometryError("node kinds given for " + std::to_string(opt.kinds.size()) + " nodes, curve neighbours for " +
                        std::to_string(opt.curve_neighbours.size()) + ", the mesh has " + std::to_string(input.num_nodes()));
  if (opt.optimised_at.rows() > 0 && (opt.optimised_at.rows() != input.num_nodes() || opt.optimised_at.cols() != 3))
    throw GeometryError("optimised_at has " + std::to_string(opt.optimised_at.rows()) + " x " + std::to_string(opt.optimised_at.cols()) +
                        " entries for a mesh of " + std::to_string(input.num_nodes()) + " nodes (#V x 3 expected)");
  for (const auto& [nodes, what] : {std::pair(&opt.fixed_nodes, "fixed"), std::pair(&opt.changed_nodes, "changed")})
    for (int v : *nodes)
      if (v < 0 || v >= input.num_nodes())
        throw GeometryError(std::string(what) + " node " + std::to_string(v) + " is outside the mesh's " +
                            std::to_string(input.num_nodes()) + " nodes");
  // The surface and feature curves come from the input, before pillowing renumbers nodes.
  const NodeKinds t0 = node_kinds(input, opt.feature_angle, have_sharp ? &sharp : nullptr);
  BoundaryConstraints cons = boundary_constraints(input, t0, opt.surface);
  cons.project = opt.project;
  cons.project_concurrent = opt.project_concurrent;
  const QualityReport before = quality_report(input, thread_count(opt.threads));
  const std::vector<char>* sp = have_sharp ? &sharp : nullptr;
  const std::vector<char> layer = opt.kinds.empty() ? smooth_layer_faces(input, t0) : std::vector<char>();

  ImproveResult r;
  if (!recommended) {
    Run run(input, t0, opt, opt.pillow, sp, cons, log);
    const int smoothed = run.smooth(opt.smooth);
    const int optimised = run.stopped() ? 0 : run.optimize(opt.optimize);
    run.set_rounds(std::max(smoothed, optimised));
    if (opt.mean_after && opt.mean_passes > 0) run.mean_stage(opt.mean_passes, 3e-3);
    if (opt.max_edge_ratio > 0) run.ratio_stage(opt.max_edge_ratio, opt.ratio_sj_floor, opt.ratio_rounds);
    r = run.finish();
    if (r.stopped) log("improve: stopped after the time budget of " + fmt("%g", opt.deadline.budget()) + " s");
  } else {
    // Pillowing is preferred (no hex keeps two faces on the boundary). Where a polycube edge lies
    // on a smooth surface, a layer over those smooth regions only comes first (smooth_layer_faces),
    // then the layer everywhere, then no layer: where the boundary is pinched or a layer cannot be
    // made valid it can end worse. The first run with no inverted cell whose worst hex reaches 0.4
    // (and the input's) is kept without trying the next; otherwise the best of the runs made is:
    // fewer inverted cells first, then the better worst hex (the worst cell when there are no
    // hexes), near ties (0.02) going to the earlier run unless it ends below the input's worst.
    const double worst_hex_before = before.hex.count ? before.hex.sj_min : worst_of(before);
    auto good_enough = [&](const Run& x) { return x.inverted() == 0 && x.worst_hex() >= std::max(0.4, worst_hex_before); };
    std::vector<std::unique_ptr<Run>> runs;
    std::vector<int> plain_rounds;  // each run's rounds before the pattern search
    bool plain_good = false;  // a pillowed run reached the bar with the gradient alone
    std::vector<Run*> pattern_later;  // pillowed runs below the bar: their pattern search (below)
    Run* without_layer = nullptr;
    for (const std::vector<char>* faces : {&layer, static_cast<const std::vector<char>*>(nullptr)}) {
      if (!opt.kinds.empty()) break;  // given kinds are the input's nodes': no layer
      if (faces && faces->empty()) continue;
      if (!runs.empty() && opt.deadline.passed()) break;
      try {
        runs.push_back(std::make_unique<Run>(input, t0, opt, true, sp, cons, log, faces));
        runs.back()->worst_stage(opt.max_rounds);
      } catch (const GeometryError& e) {
        if (opt.log) opt.log(1, std::string(faces ? "layer on the smooth regions skipped: " : "pillowing skipped: ") + e.what());
        continue;
      }
      plain_rounds.push_back(runs.back()->rounds());
      if (good_enough(*runs.back())) { plain_good = true; break; }
      if (runs.back()->stopped()) break;
      pattern_later.push_back(runs.back().get());
    }
    if (!plain_good && (runs.empty() || !opt.deadline.passed())) {
      // Against a valid pillowed mesh, the run without a layer gets twice the rounds of the best
      // pillowed one (at least 10): untangling that creeps on beyond that would not win.
      int rival_rounds = -1;
      for (size_t i = 0; i < runs.size(); ++i)
        if (runs[i]->inverted() == 0) rival_rounds = std::max(rival_rounds, plain_rounds[i]);
      runs.push_back(std::make_unique<Run>(input, t0, opt, false, sp, cons, log));
      without_layer = runs.back().get();
      runs.back()->search_pattern();
      runs.back()->worst_stage(rival_rounds >= 0 ? std::min(opt.max_rounds, std::max(10, 2 * rival_rounds)) : opt.max_rounds);
    }
    // Below the bar, a pillowed run goes on with the pattern search (Improver::optimize_round).
    // Where a polycube corner lies on a round edge of a face under the layer, the layer cell's
    // corner there is capped by the angle between the face's two edges on the arc, which the
    // gradient alone does not open and the pattern does; it takes part in the final choice. It is
    // made after the run without a layer, and only when that one misses the bar too: otherwise the
    // pillowed run would have to climb from below the bar to within 0.02 of a run above it to be
    // kept. Figures: docs/tuning-notes.md.
    for (Run* x : pattern_later) {
      if ((without_layer && good_enough(*without_layer)) || opt.deadline.passed()) break;
      x->search_pattern();
      x->worst_stage(opt.max_rounds);
    }
    Run* kept = runs.front().get();
    for (const auto& x : runs)
      if (x->inverted() < kept->inverted() ||
          (x->inverted() == kept->inverted() &&
           (kept->worst_hex() < x->worst_hex() - 0.02 || (kept->worst_hex() < worst_hex_before && x->worst_hex() > kept->worst_hex()))))
        kept = x.get();
    Run& best = *kept;
    if (kept != runs.front().get()) log("kept the result " + best.name() + ": its worst cell is better");
    if (opt.deadline.passed())
      log("improve: stopped after the time budget of " + fmt("%g", opt.deadline.budget()) + " s with " +
          std::to_string(runs.size()) + " run" + (runs.size() == 1 ? "" : "s") + " made; kept the result " + best.name());
    // The mean only on the mesh kept: it never changes the worst cell the choice was made on.
    best.mean_stage(opt.mean_passes, 3e-3);
    if (opt.max_edge_ratio > 0) best.ratio_stage(opt.max_edge_ratio, opt.ratio_sj_floor, opt.ratio_rounds);
    r = best.finish();
    r.stopped = r.stopped || opt.deadline.passed();
  }
  check_interrupt("improve");  // stopped early by an interrupt: no result
  r.before = before;
  return r;
}

}  // namespace hexdom::optimize
