// choose_path (Method::Auto) with fake paths whose meshes are only their quality figures: which run
// is kept, what the threads call off, and the order of the messages, independent of which thread
// finishes first.
#include "hexdom/pipeline/choice.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "hexdom/common/stopwatch.h"

using namespace hexdom;
using namespace hexdom::pipeline;

namespace {

constexpr double kReference = 1000;

// A run of one hex type with worst SJ `sj`, no inverted cell, the reference volume, edge ratio 2.
MeshSurfaceRun fake_run(Method method, double sj) {
  MeshSurfaceRun r;
  r.method = method;
  r.quality.hex.count = 10;
  r.quality.hex.sj_min = sj;
  r.quality.hex.edge_ratio_max = 2;
  r.quality.total_volume = kReference;
  r.stage = "done";
  return r;
}

struct Fake {
  double first_sj = 0.2, overlay_sj = 0.5, further_sj = 0.6;
  double overlay_ratio = 2;  // the overlay mesh's largest edge ratio
  int first_millis = 0, overlay_millis = 0, further_millis = 0;  // how long each pretends to work
  double seconds_overlay_met = 5;  // MeshSurfaceOptions::polycube_seconds_overlay_met
  std::atomic<bool> first_cancelled{false}, overlay_cancelled{false}, further_cancelled{false};
  std::mutex mutex;
  std::vector<std::string> said;  // everything said, in order

  MeshSurfaceOptions options() {
    MeshSurfaceOptions o;
    o.polycube_seconds_overlay_met = seconds_overlay_met;
    o.log = [this](int, const std::string& m) {
      std::lock_guard<std::mutex> lock(mutex);
      said.push_back(m);
    };
    return o;
  }
  // Works `millis` unless the deadline passes first (then says so in `cancelled`).
  static void work(int millis, const Deadline& d, std::atomic<bool>& cancelled) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(millis);
    while (std::chrono::steady_clock::now() < end) {
      if (d.cancelled()) {
        cancelled = true;
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  void mesh_path(const MeshSurfaceOptions& o, MeshSurfaceRun& run) {
    if (o.method == Method::Overlay) {
      o.log(0, "fake overlay");
      work(overlay_millis, o.deadline, overlay_cancelled);
      if (overlay_cancelled) o.deadline.check("overlay");
      run = fake_run(Method::Overlay, overlay_sj);
      run.quality.hex.edge_ratio_max = overlay_ratio;
    } else if (o.first_run == nullptr) {
      o.log(0, "fake first candidate");
      work(first_millis, o.deadline, first_cancelled);
      if (first_cancelled) o.deadline.check("autopolycube");  // no mesh yet: TimeoutError
      run = fake_run(Method::Polycube, first_sj);
    } else {
      o.log(0, "fake further candidates");
      work(further_millis, o.deadline, further_cancelled);
      run = fake_run(Method::Polycube, further_cancelled ? first_sj : further_sj);
    }
  }
  MeshSurfaceRun choose() {
    MeshSurfaceRun r;
    choose_path(
        options(), kReference, [this](const MeshSurfaceOptions& o, MeshSurfaceRun& run) { mesh_path(o, run); },
        [](MeshSurfaceRun& run) -> MeshSurfaceRun& { return run; }, [](const MeshSurfaceRun&) { return MeshSurfaceRun{}; },
        [](const MeshSurfaceRun& run) { return run; }, r);
    return r;
  }
  int index(const std::string& prefix) const {
    for (size_t i = 0; i < said.size(); ++i)
      if (said[i].rfind(prefix, 0) == 0) return static_cast<int>(i);
    return -1;
  }
};

}  // namespace

TEST(ChoosePath, AFirstCandidateThatMeetsEveryTargetCallsTheOverlayOff) {
  Fake f;
  f.first_sj = 0.7;
  f.overlay_millis = 20000;  // would take 20 s unless called off
  const MeshSurfaceRun r = f.choose();
  EXPECT_EQ(r.method, Method::Polycube);
  EXPECT_DOUBLE_EQ(r.quality.hex.sj_min, 0.7);
  EXPECT_TRUE(f.overlay_cancelled);  // it saw the cancellation and returned before its 20 s
  EXPECT_EQ(f.index("fake overlay"), -1);  // the overlay's messages are not said
}

TEST(ChoosePath, TheOverlaysMessagesFollowTheFirstCandidatesAndTheFurtherOnesFollowThem) {
  for (int overlay_millis : {0, 300}) {  // the overlay ends before or after the further candidates
    SCOPED_TRACE(overlay_millis);
    Fake f;
    f.overlay_sj = 0.25;  // misses the SJ target: the further candidates count
    f.overlay_millis = overlay_millis;
    f.further_millis = 300 - overlay_millis;
    const MeshSurfaceRun r = f.choose();
    EXPECT_EQ(r.method, Method::Polycube);
    EXPECT_DOUBLE_EQ(r.quality.hex.sj_min, 0.6);
    EXPECT_FALSE(f.further_cancelled);
    const int first = f.index("fake first candidate"), misses = f.index("the polycube mesh misses a target"),
              overlay = f.index("fake overlay"), heading = f.index("the polycube again with its further candidates"),
              further = f.index("fake further candidates"), kept = f.index("kept the polycube mesh");
    EXPECT_EQ(first, 0);
    EXPECT_LT(first, misses);
    EXPECT_LT(misses, overlay);
    EXPECT_LT(overlay, heading);
    EXPECT_LT(heading, further);
    EXPECT_LT(further, kept);
  }
}

TEST(ChoosePath, AnOverlayMeshThatMeetsTheTargetsCallsTheFurtherCandidatesOffAtTheCut) {
  // The further candidates give a better worst SJ (0.6 > 0.5). Ended before the cut (0.3 s after
  // the start), they are weighed with the overlay's mesh and kept, whichever thread ended first;
  // still running at the cut, they are stopped then and count for nothing (what they had is not
  // kept), their messages not said.
  for (int overlay_millis : {0, 200}) {
    SCOPED_TRACE(overlay_millis);
    Fake f;
    f.seconds_overlay_met = 0.3;
    f.overlay_millis = overlay_millis;
    f.further_millis = 100;
    const MeshSurfaceRun r = f.choose();
    EXPECT_EQ(r.method, Method::Polycube);
    EXPECT_DOUBLE_EQ(r.quality.hex.sj_min, 0.6);
    EXPECT_FALSE(f.further_cancelled.load());
    EXPECT_GE(f.index("kept the polycube mesh"), 0);
  }
  Fake f;
  f.seconds_overlay_met = 0.3;
  f.overlay_millis = 100;
  f.further_millis = 20000;
  const auto t0 = std::chrono::steady_clock::now();
  const MeshSurfaceRun r = f.choose();
  EXPECT_LT(seconds_since(t0), 10.0);
  EXPECT_EQ(r.method, Method::Overlay);
  EXPECT_DOUBLE_EQ(r.quality.hex.sj_min, 0.5);
  EXPECT_TRUE(f.further_cancelled.load());
  EXPECT_GE(f.index("the polycube again with its further candidates: called off after 0.3 s"), 0);
  EXPECT_EQ(f.index("fake further candidates"), -1);
}

TEST(ChoosePath, AnOverlayMeshThatMeetsEveryTargetStopsASlowFirstCandidateAtTheCut) {
  // The first candidate would take 20 s; the overlay's mesh meets every target at once, the edge
  // ratio aside (2, then 12 > 10): the first candidate is stopped 0.3 s after the start (no mesh
  // yet), the overlay's kept, the note says why.
  for (double ratio : {2.0, 12.0}) {
    Fake f;
    f.first_millis = 20000;
    f.overlay_ratio = ratio;
    f.seconds_overlay_met = 0.3;
    const auto t0 = std::chrono::steady_clock::now();
    const MeshSurfaceRun r = f.choose();
    EXPECT_LT(seconds_since(t0), 10.0);
    EXPECT_TRUE(f.first_cancelled.load());
    EXPECT_EQ(r.method, Method::Overlay);
    EXPECT_NE(r.polycube_note.find("stopped after 0.3 s at stage"), std::string::npos) << r.polycube_note;
    EXPECT_EQ(r.polycube_note.find("but the edge ratio") != std::string::npos, ratio > 10) << r.polycube_note;
  }
  // A first candidate that ends before the cut is not stopped, and its mesh, meeting every target,
  // is kept; with no cut (0) a slow one runs to its end.
  for (double cut : {5.0, 0.0}) {
    Fake g;
    g.first_millis = 300;
    g.first_sj = 0.7;
    g.overlay_ratio = 12;
    g.seconds_overlay_met = cut;
    EXPECT_EQ(g.choose().method, Method::Polycube);
    EXPECT_FALSE(g.first_cancelled.load());
  }
}

TEST(ChoosePath, FurtherCandidatesThatMeetEveryTargetStopASlowOverlayAtTheCut) {
  // The overlay would take 20 s; the further candidates' mesh (0.6) meets every target: the overlay
  // is called off 0.3 s after the start and the polycube's mesh kept.
  Fake f;
  f.overlay_millis = 20000;
  f.seconds_overlay_met = 0.3;
  const auto t0 = std::chrono::steady_clock::now();
  const MeshSurfaceRun r = f.choose();
  EXPECT_LT(seconds_since(t0), 10.0);
  EXPECT_TRUE(f.overlay_cancelled.load());
  EXPECT_EQ(r.method, Method::Polycube);
  EXPECT_DOUBLE_EQ(r.quality.hex.sj_min, 0.6);
  EXPECT_GE(f.index("overlay: called off after 0.3 s, the polycube mesh meets every target"), 0);
}
