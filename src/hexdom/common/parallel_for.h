// A plain parallel loop over indices, for stages whose work items are independent.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

#include "hexdom/common/interrupt.h"
#include "hexdom/common/thread_grant.h"
#include "hexdom/common/thread_pool.h"

namespace hexdom {

/// Calls f(i) for every i in [0, n) on `threads` threads (the caller's and the program's pool's,
/// thread_pool.h; fewer when n is smaller, one when threads < 1). Each thread takes runs of
/// consecutive indices (about a sixteenth of n / threads each), in increasing order: neighbouring
/// items, which often write to neighbouring memory, go to the same thread. f must write only what
/// index i owns; then the result does not depend on the number of threads. When calls throw, the
/// exception of the lowest index is rethrown after every call has returned. The threads run under
/// the caller's interrupt (interrupt.h); once it is raised no further run starts and
/// InterruptedError is thrown. Under a thread grant (thread_grant.h) the grant's count replaces
/// `threads`.
template <class Fn>
void parallel_for(int n, int threads, Fn&& f) {
  threads = std::max(1, std::min(granted_threads(threads), n));
  if (threads == 1) {
    for (int i = 0; i < n; ++i) {
      check_interrupt("parallel loop");
      f(i);
    }
    return;
  }
  const int grain = std::max(1, n / (16 * threads));
  std::atomic<int> next{0};
  std::mutex failed;
  int first_error = n;  // the lowest index whose call threw, and its exception
  std::exception_ptr error;
  const Interrupt* interrupt = current_interrupt();
  auto worker = [&] {
    const InterruptScope scope(interrupt);
    for (int start; (start = next.fetch_add(grain)) < n;)
      for (int i = start, end = std::min(n, start + grain); i < end; ++i) {
        try {
          check_interrupt("parallel loop");
          f(i);
        } catch (...) {
          const std::lock_guard<std::mutex> lock(failed);
          if (i < first_error) {
            first_error = i;
            error = std::current_exception();
          }
          if (interrupted()) next.store(n);
        }
      }
  };
  run_on_pool(threads - 1, worker);
  if (error) std::rethrow_exception(error);
}

/// One thread per hardware thread when `requested` is 0 or less, else `requested`.
inline int thread_count(int requested) {
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  return requested > 0 ? requested : std::max(1, cores);
}

}  // namespace hexdom
