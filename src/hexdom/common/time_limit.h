// A limit on the wall time of a whole call (the program's --time-limit), enforced through the
// interrupt that every long loop already checks (interrupt.h).
#pragma once

#include <functional>

namespace hexdom {

/// Runs `body` with at most `seconds` of wall time; no limit (body called as is) when seconds <= 0,
/// NaN or infinite. The body runs under an Interrupt of its own, raised by a watcher thread once
/// the time is up or once the caller's interrupt (if any) is raised, looked at every 20 ms. A body
/// stopped by the clock ends in TimeLimitError (a TimeoutError) naming the step that was running
/// ("<where> (time limit of the run): stopped after the time budget of 60 s"); one stopped by the caller's
/// interrupt in InterruptedError as without a limit. A body that ends in time ends as it would
/// have: its result, or its exception, passes unchanged. Bodies that finish just as the time runs
/// out may stop in a step that treats the interrupt as a stop-early signal and then in the next
/// check; either way the call ends with TimeoutError within a fraction of a second of the limit.
void run_with_time_limit(double seconds, const std::function<void()>& body);

}  // namespace hexdom
