// run_with_time_limit: a body past its time ends in TimeoutError naming its step, within a fraction
// of a second; one in time ends as it would have; the caller's interrupt still interrupts.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "hexdom/common/error.h"
#include "hexdom/common/interrupt.h"
#include "hexdom/common/stopwatch.h"
#include "hexdom/common/time_limit.h"

using namespace hexdom;

namespace {

// Work that looks at the interrupt every millisecond, for at most `limit` seconds.
void busy(double limit, const char* where) {
  const auto t = std::chrono::steady_clock::now();
  while (seconds_since(t) < limit) {
    check_interrupt(where);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

}  // namespace

TEST(TimeLimit, AStepPastTheLimitEndsInTimeoutErrorNamingIt) {
  const auto t = std::chrono::steady_clock::now();
  try {
    run_with_time_limit(0.2, [] { busy(30, "octree refinement"); });
    FAIL() << "no TimeoutError";
  } catch (const TimeLimitError& e) {
    EXPECT_EQ(e.where(), "octree refinement (time limit of the run)");
    EXPECT_EQ(e.budget(), 0.2);
    EXPECT_NE(std::string(e.what()).find("time budget of 0.2 s"), std::string::npos) << e.what();
  }
  const double took = seconds_since(t);
  EXPECT_GE(took, 0.2);
  EXPECT_LT(took, 1.0);
}

TEST(TimeLimit, ABodyInTimeEndsAsItWould) {
  int calls = 0;
  run_with_time_limit(5, [&] { busy(0.01, "step"); ++calls; });
  EXPECT_EQ(calls, 1);
  EXPECT_THROW(run_with_time_limit(5, [] { throw GeometryError("open surface"); }), GeometryError);
  // No limit: the body runs on the caller's interrupt, with no watcher.
  const Interrupt* seen = reinterpret_cast<const Interrupt*>(1);
  run_with_time_limit(0, [&] { seen = current_interrupt(); });
  EXPECT_EQ(seen, nullptr);
}

TEST(TimeLimit, TheCallersInterruptStillInterrupts) {
  const Interrupt outer;
  const InterruptScope scope(&outer);
  std::thread raiser([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    outer.raise();
  });
  const auto t = std::chrono::steady_clock::now();
  EXPECT_THROW(run_with_time_limit(30, [] { busy(30, "label repair"); }), InterruptedError);
  EXPECT_LT(seconds_since(t), 1.0);
  raiser.join();
}

TEST(TimeLimit, ABodyThatStopsEarlyOnTheInterruptStillTimesOut) {
  // A step that takes the interrupt as "stop and return what you have" must not pass for done.
  EXPECT_THROW(run_with_time_limit(0.1, [] {
                 while (!interrupted()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
               }),
               TimeLimitError);
}
