// A plain parallel loop over indices, for stages whose work items are independent.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

#include "hexdom/common/interrupt.h"

namespace hexdom {

/// Calls f(i) for every i in [0, n) on `threads` threads (the caller's included; fewer when n is
/// smaller, one when threads < 1), handing out indices in increasing order. f must write only what
/// index i owns; then the result does not depend on the number of threads. When calls throw, the
/// exception of the lowest index is rethrown after every call has returned. The threads run under
/// the caller's interrupt (interrupt.h); once it is raised no further index starts and
/// InterruptedError is thrown.
template <class Fn>
void parallel_for(int n, int threads, Fn&& f) {
  threads = std::max(1, std::min(threads, n));
  if (threads == 1) {
    for (int i = 0; i < n; ++i) {
      check_interrupt("parallel loop");
      f(i);
    }
    return;
  }
  std::atomic<int> next{0};
  std::vector<std::exception_ptr> errors(n);
  const Interrupt* interrupt = current_interrupt();
  auto worker = [&] {
    const InterruptScope scope(interrupt);
    for (int i; (i = next.fetch_add(1)) < n;) {
      try {
        check_interrupt("parallel loop");
        f(i);
      } catch (...) {
        errors[i] = std::current_exception();
        if (interrupted()) next.store(n);
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

/// One thread per hardware thread when `requested` is 0 or less, else `requested`.
inline int thread_count(int requested) {
  return requested > 0 ? requested : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

}  // namespace hexdom
