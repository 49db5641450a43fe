// Deadline: none by default and for budgets that are no limit; a set one passes after its seconds,
// and check() then throws TimeoutError naming the place and the budget.
#include "hexdom/common/deadline.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

#include "hexdom/common/error.h"

using hexdom::Deadline;

namespace {
// A deadline that has certainly passed: a microsecond's budget, then a millisecond's sleep.
Deadline passed_deadline() {
  const Deadline d = Deadline::in(1e-6);
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  return d;
}
}  // namespace

TEST(Deadline, NoneByDefault) {
  const Deadline d;
  EXPECT_FALSE(d.is_set());
  EXPECT_FALSE(static_cast<bool>(d));
  EXPECT_FALSE(d.passed());
  EXPECT_TRUE(std::isinf(d.left()));
  EXPECT_EQ(d.budget(), 0.0);
  EXPECT_NO_THROW(d.check("anywhere"));
}

TEST(Deadline, BudgetsThatAreNoLimitGiveNone) {
  for (double s : {0.0, -1.0, -1e-9, std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                   std::numeric_limits<double>::quiet_NaN()}) {
    const Deadline d = Deadline::in(s);
    EXPECT_FALSE(d.is_set()) << s;
    EXPECT_FALSE(d.passed()) << s;
    EXPECT_TRUE(std::isinf(d.left())) << s;
    EXPECT_NO_THROW(d.check("x")) << s;
  }
}

TEST(Deadline, ALongBudgetHasNotPassed) {
  const Deadline d = Deadline::in(1000);
  EXPECT_TRUE(d.is_set());
  EXPECT_FALSE(d.passed());
  EXPECT_GT(d.left(), 990.0);
  EXPECT_LE(d.left(), 1000.0);
  EXPECT_EQ(d.budget(), 1000.0);
  EXPECT_NO_THROW(d.check("x"));
  // A budget beyond any clock range is still a (far) deadline, not an overflow into the past.
  const Deadline far = Deadline::in(1e300);
  EXPECT_TRUE(far.is_set());
  EXPECT_FALSE(far.passed());
}

TEST(Deadline, PassesAfterItsSecondsAndCopiesShareTheMoment) {
  const Deadline d = Deadline::in(0.05);
  const Deadline copy = d;
  EXPECT_FALSE(d.passed());
  std::this_thread::sleep_for(std::chrono::milliseconds(80));
  EXPECT_TRUE(d.passed());
  EXPECT_TRUE(copy.passed());
  EXPECT_EQ(d.left(), 0.0);
}

TEST(Deadline, CheckThrowsTimeoutErrorNamingThePlaceAndTheBudget) {
  const Deadline d = passed_deadline();
  try {
    d.check("autopolycube");
    FAIL() << "no TimeoutError";
  } catch (const hexdom::TimeoutError& e) {
    EXPECT_STREQ(e.what(), "autopolycube: stopped after the time budget of 1e-06 s");
    EXPECT_EQ(e.where(), "autopolycube");
    EXPECT_EQ(e.budget(), 1e-6);
  }
  EXPECT_THROW(d.check("x"), hexdom::Error);  // an Error like the others
  EXPECT_STREQ(hexdom::TimeoutError("improve", 5).what(), "improve: stopped after the time budget of 5 s");
}

TEST(Deadline, ACancellableOnePassesOnceAnyCopyIsCancelledFromAnotherThread) {
  const Deadline d = Deadline::cancellable();
  const Deadline copy = d, later = copy;
  EXPECT_TRUE(d.is_set());
  EXPECT_FALSE(d.passed());
  EXPECT_TRUE(std::isinf(d.left()));
  EXPECT_NO_THROW(d.check("overlay"));
  std::thread([copy] { copy.cancel(); }).join();
  for (const Deadline& x : {d, copy, later}) {
    EXPECT_TRUE(x.cancelled());
    EXPECT_TRUE(x.passed());
    EXPECT_EQ(x.left(), 0.0);
  }
  try {
    later.check("overlay");
    FAIL() << "no TimeoutError";
  } catch (const hexdom::TimeoutError& e) {
    EXPECT_STREQ(e.what(), "overlay: cancelled");
    EXPECT_TRUE(e.cancelled());
  }
  // Cancelling a plain deadline does nothing; a cancellable one keeps its base's moment.
  const Deadline plain = Deadline::in(1000);
  plain.cancel();
  EXPECT_FALSE(plain.passed());
  EXPECT_TRUE(Deadline::cancellable(passed_deadline()).passed());
  EXPECT_FALSE(Deadline::cancellable(plain).passed());
}
