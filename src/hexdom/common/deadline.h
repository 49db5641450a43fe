// A time budget as a value: the moment after which a long computation should give up or stop early.
//
// Contract: a default-constructed Deadline is none (no limit): passed() is false, left() infinite and
// check() never throws. Deadline::in(s) is s seconds from the call on the steady clock; s <= 0, NaN or
// infinite give none, so that "0: no limit" options pass their value straight in. A Deadline is
// copied freely into the options of the stages it bounds (all copies share the same moment); it
// measures, it never interrupts: each stage decides where it looks (loop heads, between stages) and
// what it does when the time is up: throw TimeoutError through check() where it has no result yet,
// or stop early and return the best it has (saying so in its log) where it has one.
//
// A cancellable Deadline (Deadline::cancellable) also passes once cancel() is called on any of its
// copies, from any thread: the auto method runs the overlay path beside the polycube's first
// candidate and calls it off when that candidate is kept.
//
// Every Deadline, none included, also passes once the calling thread's interrupt (interrupt.h) is
// raised, and check() then throws InterruptedError: the stages that stop early on their budget stop
// on the user's Cancel too, and the call's caller sees that it was interrupted.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <string>

namespace hexdom {

class Deadline {
 public:
  using Clock = std::chrono::steady_clock;

  Deadline() = default;  ///< none: never passes

  /// `seconds` from now; none when seconds <= 0, NaN or infinite.
  static Deadline in(double seconds);
  /// `base` (its moment, if any) that cancel() also ends; its copies share the cancellation.
  static Deadline cancellable(const Deadline& base);
  static Deadline cancellable();  ///< no moment: only cancel() ends it

  /// Whether there is a limit at all (a moment, or a cancellation); the calling thread's interrupt
  /// counts in passed() and check() whatever this says.
  bool is_set() const { return set_ || cancel_; }
  explicit operator bool() const { return is_set(); }
  /// Whether the moment has come, the deadline was cancelled or the calling thread's interrupt is
  /// raised.
  bool passed() const;
  /// Ends a cancellable deadline and every copy of it at once (thread-safe); nothing otherwise.
  void cancel() const {
    if (cancel_) cancel_->store(true);
  }
  bool cancelled() const { return cancel_ && cancel_->load(); }
  /// Seconds until the moment: 0 once passed, infinity for none.
  double left() const;
  /// The budget it was made with (Deadline::in's seconds; 0 for none), for messages.
  double budget() const { return budget_; }
  /// Throws InterruptedError(where) when the calling thread's interrupt is raised, else
  /// TimeoutError(where, budget()) when passed(): "<where>: stopped after the time budget of 5 s"
  /// ("<where>: cancelled" once cancelled).
  void check(const std::string& where) const;

 private:
  bool set_ = false;
  std::shared_ptr<std::atomic<bool>> cancel_;
  double budget_ = 0;
  Clock::time_point end_{};
};

}  // namespace hexdom
