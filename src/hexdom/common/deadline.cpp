#include "hexdom/common/deadline.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hexdom/common/error.h"
#include "hexdom/common/interrupt.h"

namespace hexdom {

Deadline Deadline::in(double seconds) {
  Deadline d;
  if (!(seconds > 0) || std::isinf(seconds)) return d;
  d.set_ = true;
  d.budget_ = seconds;
  // duration<double> to the clock's ticks; budgets beyond a century are clamped to a century (the
  // time_point would overflow), which is no limit in practice.
  const double capped = std::min(seconds, 100.0 * 365 * 24 * 3600);
  d.end_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(capped));
  return d;
}

Deadline Deadline::cancellable(const Deadline& base) {
  Deadline d = base;
  d.cancel_ = std::make_shared<std::atomic<bool>>(false);
  return d;
}

Deadline Deadline::cancellable() { return cancellable(Deadline()); }

bool Deadline::passed() const { return interrupted() || cancelled() || (set_ && Clock::now() >= end_); }

double Deadline::left() const {
  if (cancelled() || interrupted()) return 0.0;
  if (!set_) return std::numeric_limits<double>::infinity();
  const double s = std::chrono::duration<double>(end_ - Clock::now()).count();
  return s > 0 ? s : 0.0;
}

void Deadline::check(const std::string& where) const {
  check_interrupt(where.c_str());
  if (cancelled()) throw TimeoutError(where, budget_, true);
  if (passed()) throw TimeoutError(where, budget_);
}

}  // namespace hexdom
