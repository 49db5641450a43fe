// The threads parallel_for runs on: made once, reused by every loop (starting threads for each
// loop cost more than the loop on small ones, e.g. one colour of an optimiser sweep).
#pragma once

#include <functional>

namespace hexdom {

/// Calls `work` on the calling thread and on up to `helpers` threads of a pool shared by the whole
/// program, each call once per thread that joins, and returns when every call has returned. A
/// helper may join late or not at all (the pool's threads also serve other loops, the pool grows
/// to the largest number of helpers asked for), so `work` must take its items from a shared
/// counter until none is left; it must not throw. Calls may nest (a `work` may call run_on_pool)
/// and come from several threads at once.
void run_on_pool(int helpers, const std::function<void()>& work);

}  // namespace hexdom
