// Threads lent to a call that runs beside another one (the auto method's two paths): when one
// path ends, its threads go to the other while that one still runs.
//
// Contract: a ThreadGrant is a count shared by its copies; set() changes it from any thread. A
// thread runs under a grant while it has a ThreadGrantScope for it; then every parallel loop it
// starts (parallel_for, the optimiser's sweeps) takes the grant's count at that moment instead of
// the count it was given (granted_threads). Results do not depend on it: every parallel loop of the
// core gives the same result on any number of threads.
#pragma once

#include <atomic>
#include <memory>

namespace hexdom {

class ThreadGrant {
 public:
  explicit ThreadGrant(int threads) : n_(std::make_shared<std::atomic<int>>(threads < 1 ? 1 : threads)) {}
  void set(int threads) const { n_->store(threads < 1 ? 1 : threads); }
  int get() const { return n_->load(); }

 private:
  std::shared_ptr<std::atomic<int>> n_;
};

/// The calling thread runs under `grant` while the scope lives (the previous one back after it;
/// scopes nest, the innermost counts). Pass nullptr for none.
class ThreadGrantScope {
 public:
  explicit ThreadGrantScope(const ThreadGrant* grant);
  ~ThreadGrantScope();
  ThreadGrantScope(const ThreadGrantScope&) = delete;
  ThreadGrantScope& operator=(const ThreadGrantScope&) = delete;

 private:
  const ThreadGrant* previous_;
};

/// The calling thread's grant, or nullptr outside any scope.
const ThreadGrant* current_thread_grant();

/// The grant's count now when the calling thread runs under one, else `requested`.
inline int granted_threads(int requested) {
  const ThreadGrant* g = current_thread_grant();
  return g ? g->get() : requested;
}

}  // namespace hexdom
