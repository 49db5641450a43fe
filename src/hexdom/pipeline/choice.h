// The automatic choice between the two meshing paths (Method::Auto), written once for the runs on a
// triangle surface (mesh_surface) and on a CAD part (mesh_cad_part, each path's mesh snapped onto
// the B-rep before it is measured).
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>
#include <string>
#include <utility>

#include "hexdom/common/error.h"
#include "hexdom/common/format.h"
#include "hexdom/pipeline/mesh_surface.h"

namespace hexdom::pipeline {

/// Method::Auto on one surface, cheapest first:
///  1. the polycube path with its first candidate only (no further candidate: without the widths of
///     holes, hex blocks under apex caps, a finer level), within the options' deadline. A mesh that
///     meets every target (meets_path_targets) is kept; nothing else runs.
///  2. the overlay path. When its mesh meets every target, the better of the two (better_run) is kept.
///  3. otherwise, when neither mesh meets the targets the further candidates may mend (meets_targets:
///     no inverted cell, the worst SJ, the volume) and the deadline, moved later by the overlay's
///     run time (the polycube's budget does not pay for it), has not passed, the polycube path
///     again with its candidates (the labelling repaired once, taken from step 1), and the best of
///     the meshes kept. When step 1 gave no mesh because its labelling defeated the repair, step 3
///     segments again with the options' further edge weights (retry_edge_weights; step 1 tries the
///     first weight only).
/// `mesh_path(options, run)` meshes with options.method (Polycube or Overlay) into `run`, throwing
/// Error when the path gives no mesh; `run_of(run)` is its MeshSurfaceRun; `blank(run)` a fresh run
/// for the same surface; `unsnapped(run)` (a MeshSurfaceRun) the polycube run of step 1 as
/// mesh_surface made it, before any snap, from which step 3's candidates start instead of meshing
/// it again. The kept run is in `r`; its polycube_note says why the polycube mesh was not kept alone
/// (empty when it was), its polycube_meshed whether step 1 gave a mesh. Throws the overlay's error
/// when no path gives a mesh.
template <class Run, class MeshPath, class RunOf, class Blank, class Unsnapped>
void choose_path(const MeshSurfaceOptions& mo, double reference, MeshPath mesh_path, RunOf run_of, Blank blank,
                 Unsnapped unsnapped, Run& r) {
  auto say = [&](const std::string& m) { if (mo.log) mo.log(0, m); };
  MeshSurfaceOptions quick = mo;
  quick.method = Method::Polycube;
  quick.deadline = polycube_deadline(mo);
  quick.try_without_widths = quick.try_hex_apexes = quick.refine_when_inverted = false;
  quick.retry_edge_weights.clear();
  // The edge weights step 3 segments with when step 1's labelling defeats the repair.
  std::vector<double> weights;
  for (double w : mo.retry_edge_weights)
    if (w != mo.segment.edge_weight && std::find(weights.begin(), weights.end(), w) == weights.end()) weights.push_back(w);
  std::string note;
  bool have = false, labelling_failed = false;
  try {
    mesh_path(quick, r);
    have = true;
    if (meets_path_targets(run_of(r), reference, mo)) {
      run_of(r).polycube_meshed = true;
      return;
    }
    note = "the polycube mesh misses a target (" + run_summary(run_of(r), reference) + ")" +
           (run_of(r).budget_passed ? fmt(" (its time budget of %g s passed)", quick.deadline.budget()) : std::string());
  } catch (const TimeoutError& e) {  // the polycube path ran out of its time: no retry
    note = polycube_failure_note(e, run_of(r).stage);
  } catch (const Error& e) {
    note = polycube_failure_note(e, run_of(r).stage);
    labelling_failed = true;
  }
  const bool first_meshed = have;
  say(note + "; meshing with the overlay grid too");
  Run grid = blank(r);
  MeshSurfaceOptions overlay = mo;
  overlay.method = Method::Overlay;
  bool have_grid = false;
  const auto overlay_start = std::chrono::steady_clock::now();
  try {
    mesh_path(overlay, grid);
    have_grid = true;
  } catch (const Error& e) {
    if (!have) throw;
    say(std::string("overlay: ") + e.what());
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
  // The polycube's budget does not pay for the overlay's run.
  const Deadline rest = quick.deadline.extended(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - overlay_start).count());
  // The further candidates mend the worst SJ, inverted cells or the volume, seldom the edge ratio.
  const bool grid_enough = have_grid && meets_targets(run_of(grid), reference, mo);
  // Step 3: the polycube path again with `full` within the rest of the budget, kept when better;
  // `failed(e, run)` says why when it gives no mesh.
  auto polycube_again = [&](MeshSurfaceOptions full, auto failed) {
    full.method = Method::Polycube;
    full.deadline = rest;
    Run again = blank(r);
    try {
      mesh_path(full, again);
      keep(again, "polycube");
    } catch (const Error& e) {
      say(failed(e, again));
    }
  };
  if (have && !grid_enough && !meets_targets(run_of(r), reference, mo) && run_of(r).method == Method::Polycube &&
      !rest.passed() && (mo.try_without_widths || mo.try_hex_apexes || mo.refine_when_inverted)) {
    say("the polycube again with its further candidates");
    MeshSurfaceOptions full = mo;
    // The labelling (and lambda) of the first run: the repair is not run again.
    full.polycube.repaired = &run_of(r).polycube.repaired;
    full.segment.edge_weight = run_of(r).edge_weight;
    full.retry_edge_weights.clear();
    const MeshSurfaceRun first = unsnapped(r);
    full.first_run = &first;  // the first candidate is step 1's run
    polycube_again(full, [](const Error& e, Run&) {
      return std::string("the polycube's further candidates: ") + e.what() + "; keeping its first mesh";
    });
  } else if (!have && labelling_failed && !weights.empty() && !grid_enough && !rest.passed()) {
    say(fmt("the polycube again, segmenting with lambda %g", weights.front()) +
        (weights.size() > 1 ? " and then the further edge weights" : ""));
    MeshSurfaceOptions full = mo;
    full.segment.edge_weight = weights.front();
    full.retry_edge_weights.assign(weights.begin() + 1, weights.end());
    polycube_again(full, [&](const Error& e, Run& again) {
      return "the polycube with the further edge weights: " + polycube_failure_note(e, run_of(again).stage);
    });
  }
  const bool polycube_kept = have;
  if (have_grid && !keep(grid, "overlay") && polycube_kept)
    say("kept the polycube mesh: the overlay mesh is no better (" + run_summary(run_of(grid), reference) + ")");
  run_of(r).polycube_note = note;
  run_of(r).polycube_meshed = first_meshed;
}

}  // namespace hexdom::pipeline
