// ThreadGrant: a count lent to the calls a thread makes (the auto method's paths); parallel_for
// and the optimiser's sweeps take the grant's count at each loop instead of the one they were given.
#include "hexdom/common/thread_grant.h"

#include <gtest/gtest.h>

#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>

#include "hexdom/common/parallel_for.h"

using hexdom::ThreadGrant;
using hexdom::ThreadGrantScope;

namespace {

// The threads that made the calls of one parallel_for over n items, each busy for about 20 us.
std::set<std::thread::id> threads_of_loop(int n, int threads) {
  std::mutex mu;
  std::set<std::thread::id> ids;
  hexdom::parallel_for(n, threads, [&](int) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(20);
    while (std::chrono::steady_clock::now() < until) {
    }
    const std::lock_guard<std::mutex> lock(mu);
    ids.insert(std::this_thread::get_id());
  });
  return ids;
}

}  // namespace

TEST(ThreadGrant, ScopesNestAndRestoreThePreviousOne) {
  const ThreadGrant a(1), b(2);
  EXPECT_EQ(hexdom::current_thread_grant(), nullptr);
  EXPECT_EQ(hexdom::granted_threads(5), 5);
  {
    const ThreadGrantScope sa(&a);
    EXPECT_EQ(hexdom::granted_threads(5), 1);
    {
      const ThreadGrantScope sb(&b);
      EXPECT_EQ(hexdom::current_thread_grant(), &b);
      EXPECT_EQ(hexdom::granted_threads(5), 2);
    }
    EXPECT_EQ(hexdom::current_thread_grant(), &a);
  }
  EXPECT_EQ(hexdom::current_thread_grant(), nullptr);
}

TEST(ThreadGrant, ALoopTakesTheGrantsCountAtItsStart) {
  const ThreadGrant grant(1);
  const ThreadGrantScope scope(&grant);
  // Asked for 4 threads, granted 1: every call on this thread.
  const auto one = threads_of_loop(2000, 4);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(*one.begin(), std::this_thread::get_id());
  // Raised (as when the path beside it ends): the next loop, asked for 1, runs on more.
  grant.set(3);
  EXPECT_GT(threads_of_loop(2000, 1).size(), 1u);
  // Copies share the count.
  const ThreadGrant copy = grant;
  copy.set(1);
  EXPECT_EQ(grant.get(), 1);
  EXPECT_EQ(threads_of_loop(2000, 4).size(), 1u);
}

TEST(ThreadGrant, ParallelForCallsEachIndexOnceAndRethrowsTheLowestIndexsError) {
  for (int threads : {1, 2, 3}) {
    std::vector<int> calls(1000, 0);
    try {
      hexdom::parallel_for(1000, threads, [&](int i) {
        ++calls[i];
        if (i == 700 || i == 300) throw std::runtime_error(std::to_string(i));
      });
      ADD_FAILURE() << "no exception with " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "300") << threads << " threads";
    }
    // Every index up to the first that threw was called, none twice (on one thread the loop stops
    // there; on more, every call is made).
    for (int i = 0; i < 1000; ++i) {
      ASSERT_LE(calls[i], 1) << "index " << i << ", " << threads << " threads";
      if (i <= 300 || threads > 1) ASSERT_EQ(calls[i], 1) << "index " << i << ", " << threads << " threads";
    }
  }
}
