// Interrupt: a flag raised from another thread stops the calls running under it (InterruptScope);
// deadlines count as passed, parallel_for starts no further index, check() throws InterruptedError.
#include "hexdom/common/interrupt.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "hexdom/common/deadline.h"
#include "hexdom/common/parallel_for.h"

using hexdom::Deadline;
using hexdom::Interrupt;
using hexdom::InterruptedError;
using hexdom::InterruptScope;

TEST(Interrupt, ScopesNestAndRestoreThePreviousOne) {
  const Interrupt a, b;
  EXPECT_EQ(hexdom::current_interrupt(), nullptr);
  {
    const InterruptScope sa(&a);
    EXPECT_EQ(hexdom::current_interrupt(), &a);
    {
      const InterruptScope sb(&b);
      EXPECT_EQ(hexdom::current_interrupt(), &b);
    }
    EXPECT_EQ(hexdom::current_interrupt(), &a);
  }
  EXPECT_EQ(hexdom::current_interrupt(), nullptr);
}

TEST(Interrupt, ADeadlinePassesOnceTheThreadsInterruptIsRaised) {
  const Interrupt i;
  const Deadline none, later = Deadline::in(3600);
  const InterruptScope scope(&i);
  EXPECT_FALSE(none.passed());
  EXPECT_NO_THROW(none.check("stage"));
  i.raise();
  EXPECT_TRUE(i.raised());
  EXPECT_TRUE(none.passed());
  EXPECT_TRUE(later.passed());
  EXPECT_EQ(later.left(), 0.0);
  try {
    later.check("stage");
    FAIL() << "check() did not throw";
  } catch (const InterruptedError& e) {
    EXPECT_STREQ(e.what(), "stage: interrupted");
  }
  i.clear();
  EXPECT_FALSE(none.passed());
  EXPECT_NO_THROW(hexdom::check_interrupt("stage"));
}

TEST(Interrupt, OnlyTheThreadsUnderItStop) {
  const Interrupt i;
  i.raise();
  EXPECT_FALSE(hexdom::interrupted());  // no scope on this thread
  EXPECT_FALSE(Deadline().passed());
  bool seen = false;
  std::thread([&] {
    const InterruptScope scope(&i);
    seen = hexdom::interrupted();
  }).join();
  EXPECT_TRUE(seen);
}

TEST(Interrupt, ParallelForStartsNoFurtherIndexAndThrows) {
  for (int threads : {1, 3}) {
    const Interrupt i;
    const InterruptScope scope(&i);
    std::atomic<int> calls{0};
    const int n = 100000;
    EXPECT_THROW(hexdom::parallel_for(n, threads, [&](int k) {
                   ++calls;
                   if (k == 100) i.raise();
                 }),
                 InterruptedError)
        << threads << " threads";
    EXPECT_LT(calls.load(), n / 2) << threads << " threads";
  }
}
