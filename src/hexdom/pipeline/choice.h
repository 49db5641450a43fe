// The automatic choice between the two meshing paths (Method::Auto), written once for the runs on a
// triangle surface (mesh_surface) and on a CAD part (mesh_cad_part, each path's mesh snapped onto
// the B-rep before it is measured).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "hexdom/common/error.h"
#include "hexdom/common/format.h"
#include "hexdom/common/interrupt.h"
#include "hexdom/common/parallel_for.h"
#include "hexdom/common/thread_grant.h"
#include "hexdom/pipeline/mesh_surface.h"

namespace hexdom::pipeline {

/// Messages kept to be said later, in order (a path run beside another, whose lines are said as if
/// it had run after it).
struct KeptMessages {
  std::vector<std::pair<int, std::string>> lines;
  /// A log that keeps the lines here; none when `like` is none (nothing would be said).
  LogCallback sink(const LogCallback& like) {
    if (!like) return LogCallback();
    return [this](int level, const std::string& m) { lines.emplace_back(level, m); };
  }
  void say(const LogCallback& log) const {
    if (log)
      for (const auto& [level, m] : lines) log(level, m);
  }
};

/// The moment polycube_seconds_overlay_met after the choice's start, and what the two threads of
/// choose_path tell each other about it.
struct PathCut {
  std::chrono::steady_clock::time_point at;
  bool on = false;  ///< a cut at all (polycube_seconds_overlay_met > 0)
  /// Set by the thread that ran it (polycube_done: the polycube's steps 1 and 3 are over).
  std::atomic<bool> step1_done{false}, overlay_done{false}, polycube_done{false};
  /// Set by the thread that stopped it.
  std::atomic<bool> step1_stopped{false}, step3_stopped{false}, overlay_stopped{false};
  explicit PathCut(double seconds)
      : at(std::chrono::steady_clock::now() +
           std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds))),
        on(seconds > 0) {}
  /// Waits until the cut unless `done` is set or `until` passes first; true when the other path
  /// still runs at the cut (and is to be stopped).
  bool wait(const std::atomic<bool>& done, const Deadline& until) const {
    while (on && !done.load() && !until.passed() && std::chrono::steady_clock::now() < at)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return on && !done.load() && !until.passed();
  }
  /// The overlay's thread, its mesh meeting the targets: waits until the cut unless the polycube's
  /// steps end (polycube_done) or `until` passes first; at the cut, step 1 is stopped if it runs
  /// (its deadline `step1` cancelled: it keeps what it has) and step 3 (`step3`), unfinished or
  /// not yet begun, too: then it counts for nothing.
  void stop_polycube(const Deadline& until, const Deadline& step1, const Deadline& step3) {
    if (!wait(polycube_done, until)) return;
    if (!step1_done.load()) {
      step1_stopped.store(true);
      step1.cancel();
    }
    step3_stopped.store(true);
    step3.cancel();
  }
};

/// Sets a flag when it goes out of scope (a path's thread ends, by return or throw).
struct SetOnExit {
  std::atomic<bool>& flag;
  ~SetOnExit() { flag.store(true); }
};

/// Cancels `deadline` (unless `cancel` was cleared) and joins `thread` when it goes out of scope.
struct JoinOnExit {
  std::thread& thread;
  const Deadline& deadline;
  bool cancel = true;
  ~JoinOnExit() {
    if (cancel) deadline.cancel();
    if (thread.joinable()) thread.join();
  }
};

/// Step 3's options (see choose_path) from `mo`: with `further`, the polycube's further candidates
/// from step 1's run `step1` (its repaired labelling and lambda; `first`, its run before any snap,
/// as their first candidate); otherwise the segmentation with `weights` in turn. `heading` says
/// which.
inline MeshSurfaceOptions step3_options(const MeshSurfaceOptions& mo, bool further, const MeshSurfaceRun& step1,
                                        const MeshSurfaceRun* first, const std::vector<double>& weights,
                                        std::string& heading) {
  MeshSurfaceOptions full = mo;
  full.method = Method::Polycube;
  if (further) {
    heading = "the polycube again with its further candidates";
    full.polycube.repaired = &step1.polycube.repaired;  // the repair is not run again
    full.segment.edge_weight = step1.edge_weight;
    full.retry_edge_weights.clear();
    full.first_run = first;
  } else {
    heading = fmt("the polycube again, segmenting with lambda %g", weights.front()) +
              (weights.size() > 1 ? " and then the further edge weights" : "");
    full.segment.edge_weight = weights.front();
    full.retry_edge_weights.assign(weights.begin() + 1, weights.end());
  }
  return full;
}

/// Step 1's options (see choose_path): the polycube path with its first candidate only, on
/// `threads` threads, within `deadline`.
inline MeshSurfaceOptions step1_options(const MeshSurfaceOptions& mo, int threads, const Deadline& deadline) {
  MeshSurfaceOptions quick = mo;
  quick.method = Method::Polycube;
  quick.deadline = deadline;
  quick.threads = threads;
  quick.try_without_widths = quick.try_hex_apexes = quick.refine_when_inverted = false;
  quick.retry_edge_weights.clear();
  return quick;
}

/// The edge weights step 3 segments with when step 1's labelling defeats the repair: the options'
/// retry_edge_weights without the first one's and without repeats.
inline std::vector<double> further_edge_weights(const MeshSurfaceOptions& mo) {
  std::vector<double> weights;
  for (double w : mo.retry_edge_weights)
    if (w != mo.segment.edge_weight && std::find(weights.begin(), weights.end(), w) == weights.end()) weights.push_back(w);
  return weights;
}

/// Why step 1 was stopped at the cut (see choose_path): what the overlay's mesh `grid` meets.
inline std::string overlay_met(const MeshSurfaceRun& grid, double reference, const MeshSurfaceOptions& mo) {
  return std::string("the overlay mesh meets every target") + (meets_path_targets(grid, reference, mo) ? "" : " but the edge ratio");
}

/// Why step 1's mesh `first` (see choose_path) did not end the choice: it misses a target, or (`met`)
/// it meets every one but local sizes are asked for; and when its time budget passed, whether it
/// was stopped at the cut (`stopped`, the overlay's mesh `grid` meeting the targets) or not.
inline std::string step1_note(bool met, const MeshSurfaceRun& first, double reference, const MeshSurfaceOptions& mo,
                              bool stopped, const MeshSurfaceRun& grid, double budget) {
  return std::string(met ? "local sizes: the polycube mesh meets every target (" : "the polycube mesh misses a target (") +
         run_summary(first, reference) + ")" +
         (!first.budget_passed ? std::string()
          : stopped ? fmt(" (stopped after %g s: ", mo.polycube_seconds_overlay_met) + overlay_met(grid, reference, mo) + ")"
                    : fmt(" (its time budget of %g s passed)", budget));
}

/// Method::Auto on one surface, cheapest first:
///  1. the polycube path with its first candidate only (no further candidate: without the widths of
///     holes, hex blocks under apex caps, a finer level), within the options' deadline. A mesh that
///     meets every target (meets_path_targets) is kept, unless local sizes are asked for (both
///     paths' meshes are then weighed); the overlay's run is called off.
///  2. the overlay path, run beside step 1 on a thread of its own (the machine's second core; its
///     messages are said after step 1's, as if it had run after it). The better of the two
///     (better_run) is kept. When its mesh meets every target, the edge ratio aside (meets_targets),
///     step 1, if it still runs polycube_seconds_overlay_met after the start, is stopped then
///     (keeping what it has): a polycube mesh that late seldom meets the ratio where the overlay's
///     does not, and the whole run is to end within seconds.
///  3. when step 1's mesh misses the targets the further candidates may mend (meets_targets: no
///     inverted cell, the worst SJ, the volume) and the polycube's deadline has not passed, the
///     polycube path again with its candidates (the labelling repaired once, taken from step 1),
///     started beside the overlay as soon as step 1 ends; when step 1 gave no mesh because its
///     labelling defeated the repair, the segmentation with the options' further edge weights
///     (retry_edge_weights; step 1 tries the first weight only). When the overlay's mesh meets
///     those targets, it is called off if it still runs (or has not begun) polycube_seconds_overlay_met
///     after the start, and then counts for nothing; ended before, it is weighed with the others (the
///     overlay's speed does not decide between a mesh that meets the targets and a better one that
///     ends within the cut). When its own mesh meets every target
///     and the overlay still runs polycube_seconds_overlay_met after the start, the overlay is
///     called off then. The best of the meshes is kept. Where both paths end within
///     polycube_seconds_overlay_met, the mesh kept does not depend on which thread ends first.
/// `mesh_path(options, run)` meshes with options.method (Polycube or Overlay) into `run`, throwing
/// Error when the path gives no mesh; `run_of(run)` is its MeshSurfaceRun; `blank(run)` a fresh run
/// for the same surface; `unsnapped(run)` (a MeshSurfaceRun) the polycube run of step 1 as
/// mesh_surface made it, before any snap, from which step 3's candidates start instead of meshing
/// it again. The kept run is in `r`; its polycube_note says why the polycube mesh was not kept alone
/// (empty when it was), its polycube_meshed whether step 1 gave a mesh. Throws the overlay's error
/// when no path gives a mesh. `mesh_path` must be callable from two threads at once on different
/// runs (the two paths share only what they read), and say its messages through the options' log.
/// Each path's optimisers (and snap) get half of the options' threads, at least one: the paths
/// already run beside each other, and the meshes do not depend on the number. Once a path's thread
/// is done (the overlay's, or the polycube's steps 1 and 3), the other runs on all of them (a
/// ThreadGrant, common/thread_grant.h).
template <class Run, class MeshPath, class RunOf, class Blank, class Unsnapped>
void choose_path(const MeshSurfaceOptions& mo, double reference, MeshPath mesh_path, RunOf run_of, Blank blank,
                 Unsnapped unsnapped, Run& r) {
  auto say = [&](const std::string& m) { if (mo.log) mo.log(0, m); };
  // Step 1's and step 3's deadlines: the polycube's one budget, each called off by the overlay's
  // thread (see below).
  const Deadline budget = polycube_deadline(mo);
  PathCut cut(mo.polycube_seconds_overlay_met);  // see polycube_seconds_overlay_met
  // The two paths run beside each other on half the threads each (the mesh does not depend on it);
  // a path's threads go to the other once it ends (thread_grant.h).
  const int all_threads = thread_count(mo.threads);
  const int half = std::max(1, all_threads / 2);
  const ThreadGrant polycube_grant(half), overlay_grant(half);
  const ThreadGrantScope polycube_scope(&polycube_grant);
  MeshSurfaceOptions quick = step1_options(mo, half, Deadline::cancellable(budget));
  const std::vector<double> weights = further_edge_weights(mo);
  // Step 2 starts now on its own thread, with its messages kept; it is called off (its deadline
  // cancelled) when step 1's mesh is kept, and always joined before this returns or throws.
  Run grid = blank(r);
  MeshSurfaceOptions overlay = mo;
  overlay.method = Method::Overlay;
  overlay.deadline = Deadline::cancellable();
  overlay.threads = half;
  KeptMessages overlay_said;
  overlay.log = overlay_said.sink(mo.log);
  bool have_grid = false;
  std::exception_ptr grid_error;
  // Step 3's deadline: the polycube's, called off by the overlay's thread (see below).
  const Deadline step3 = Deadline::cancellable(budget);
  const Interrupt* interrupt = current_interrupt();  // the overlay's thread runs under the caller's
  std::thread worker([&] {
    const InterruptScope scope(interrupt);
    const ThreadGrantScope granted(&overlay_grant);
    try {
      mesh_path(overlay, grid);
      polycube_grant.set(all_threads);
      have_grid = true;
      cut.overlay_done.store(true);
      // Every target met, the edge ratio aside: the polycube's steps stopped at the cut if they run.
      if (meets_targets(run_of(grid), reference, mo)) cut.stop_polycube(overlay.deadline, quick.deadline, step3);
    } catch (...) {
      polycube_grant.set(all_threads);
      grid_error = std::current_exception();
      cut.overlay_done.store(true);
    }
  });
  JoinOnExit join{worker, overlay.deadline};
  std::string note;
  bool have = false, labelling_failed = false;
  try {
    {
      const SetOnExit done{cut.step1_done};
      mesh_path(quick, r);
    }
    have = true;
    // With local sizes both paths' meshes are made and measured (the sizes met, then the quality).
    const bool met = meets_path_targets(run_of(r), reference, mo);
    if (met && mo.overlay.local_sizes.empty()) {
      run_of(r).polycube_meshed = true;
      return;  // the overlay's run called off
    }
    note = step1_note(met, run_of(r), reference, mo, cut.step1_stopped.load(), run_of(grid), quick.deadline.budget());
  } catch (const TimeoutError& e) {  // the polycube path ran out of its time: no retry
    note = cut.step1_stopped.load() ? fmt("the polycube path was stopped after %g s at stage ", mo.polycube_seconds_overlay_met) +
                                      run_of(r).stage + ": " + overlay_met(run_of(grid), reference, mo)
                                : polycube_failure_note(e, run_of(r).stage);
  } catch (const Error& e) {
    note = polycube_failure_note(e, run_of(r).stage);
    labelling_failed = true;
  }
  const bool first_meshed = have;
  say(note + "; meshing with the overlay grid too");
  // Step 3, decided on step 1's result, starts at once beside the overlay (its messages kept): its
  // deadline is the polycube's, cancelled by the overlay's thread once the overlay's mesh meets
  // the targets the further candidates could mend; it then counts for nothing (whether it finished
  // or not), so the mesh kept does not depend on which thread was faster.
  const bool further = have && !meets_targets(run_of(r), reference, mo) && run_of(r).method == Method::Polycube &&
                       (mo.try_without_widths || mo.try_hex_apexes || mo.refine_when_inverted);
  const bool reweigh = !have && labelling_failed && !weights.empty();
  std::string again_heading, again_failed;
  KeptMessages again_said;
  Run again = blank(r);
  bool have_again = false;
  if ((further || reweigh) && !step3.passed()) {
    const MeshSurfaceRun first = further ? unsnapped(r) : MeshSurfaceRun{};
    MeshSurfaceOptions full = step3_options(mo, further, run_of(r), &first, weights, again_heading);
    full.deadline = step3;
    full.threads = half;
    full.log = again_said.sink(mo.log);
    try {
      mesh_path(full, again);
      have_again = true;
      // A mesh that meets every target: the overlay is called off at the cut if it runs then.
      if (!step3.passed() && meets_path_targets(run_of(again), reference, mo) &&
          cut.wait(cut.overlay_done, overlay.deadline)) {
        cut.overlay_stopped.store(true);
        overlay.deadline.cancel();
      }
    } catch (const Error& e) {
      again_failed = further ? std::string("the polycube's further candidates: ") + e.what() + "; keeping its first mesh"
                             : "the polycube with the further edge weights: " + polycube_failure_note(e, run_of(again).stage);
    }
  }
  cut.polycube_done.store(true);
  overlay_grant.set(all_threads);
  join.cancel = false;
  worker.join();
  check_interrupt("auto");
  overlay_said.say(mo.log);
  if (grid_error) {
    try {
      std::rethrow_exception(grid_error);
    } catch (const Error& e) {
      if (!have && !have_again) throw;
      say(cut.overlay_stopped.load() ? fmt("overlay: called off after %g s, the polycube mesh meets every target",
                                       mo.polycube_seconds_overlay_met)
                                 : std::string("overlay: ") + e.what());
    }
  }
  auto keep = [&](Run& other, const char* name) {
    if (!have || better_run(run_of(other), run_of(r), reference, mo)) {
      if (have) say(std::string("kept the ") + name + " mesh (" + run_summary(run_of(other), reference) + ")");
      r = std::move(other);
      have = true;
      return true;
    }
    return false;
  };
  if (!again_heading.empty()) {
    if (cut.step3_stopped.load()) {  // what it kept when stopped counts for nothing
      say(again_heading + fmt(": called off after %g s, the overlay mesh meets the targets", mo.polycube_seconds_overlay_met));
    } else {
      say(again_heading);
      again_said.say(mo.log);
      if (have_again) keep(again, "polycube");
      else say(again_failed);
    }
  }
  const bool polycube_kept = have;
  if (have_grid) keep_polycube_attempt(run_of(r), run_of(grid));
  if (have_grid && !keep(grid, "overlay") && polycube_kept)
    say("kept the polycube mesh: the overlay mesh is no better (" + run_summary(run_of(grid), reference) + ")");
  run_of(r).polycube_note = note;
  run_of(r).polycube_meshed = first_meshed;
}

}  // namespace hexdom::pipeline
