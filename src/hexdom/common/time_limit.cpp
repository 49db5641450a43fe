#include "hexdom/common/time_limit.h"

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "hexdom/common/error.h"
#include "hexdom/common/interrupt.h"

namespace hexdom {

void run_with_time_limit(double seconds, const std::function<void()>& body) {
  if (!(seconds > 0) || !std::isfinite(seconds)) {
    body();
    return;
  }
  const Interrupt* outer = current_interrupt();
  const Interrupt inner;
  std::mutex m;
  std::condition_variable cv;
  bool done = false, timed_out = false;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  std::thread watcher([&] {
    std::unique_lock<std::mutex> lock(m);
    while (!done) {
      if (outer && outer->raised()) {
        inner.raise();
        return;
      }
      if (std::chrono::steady_clock::now() >= end) {
        timed_out = true;
        inner.raise();
        return;
      }
      cv.wait_for(lock, std::chrono::milliseconds(20));
    }
  });
  auto stop_watcher = [&] {
    {
      std::lock_guard<std::mutex> lock(m);
      done = true;
    }
    cv.notify_all();
    watcher.join();
  };
  try {
    const InterruptScope scope(&inner);
    body();
  } catch (const InterruptedError& e) {
    stop_watcher();
    if (timed_out) throw TimeLimitError(e.where(), seconds);
    throw;
  } catch (...) {
    stop_watcher();
    if (timed_out) throw TimeLimitError("the run", seconds);  // a step that turned the interrupt into its own error
    throw;
  }
  stop_watcher();
  // A body that let the interrupt pass as a stop-early signal and returned must not count as done.
  if (timed_out) throw TimeLimitError("the run", seconds);
}

}  // namespace hexdom
