// Stopping a running call from outside it: the workbench's Cancel button, the program's Ctrl-C.
//
// Contract: an Interrupt is a flag shared by its copies; raise() sets it from any thread (also from
// a signal handler: it only stores to a lock-free atomic). A call runs under an interrupt when the
// calling thread has an InterruptScope for it; the core's threads (parallel_for, the auto method's
// second path) run under their caller's. Long loops call check_interrupt() at least every tenth of
// a second or so of work, and every Deadline counts as passed once the calling thread's interrupt is
// raised, so the stages that stop early on their time budget stop on it too. An interrupted call
// throws InterruptedError and returns nothing: the caller's data are as they were (the core takes
// its inputs by const reference or by value), no file is written.
#pragma once

#include <atomic>
#include <memory>
#include <stdexcept>
#include <string>

namespace hexdom {

/// A call that was stopped from outside (Interrupt::raise): "<where>: interrupted". Not an Error:
/// the stages that catch Error to try another way (the auto method's fallbacks, the candidates)
/// let it pass, so an interrupted call ends at once.
class InterruptedError : public std::runtime_error {
 public:
  explicit InterruptedError(const std::string& where) : std::runtime_error(where + ": interrupted"), where_(where) {}
  /// The step that stopped.
  const std::string& where() const { return where_; }

 private:
  std::string where_;
};

class Interrupt {
 public:
  Interrupt() : flag_(std::make_shared<std::atomic<bool>>(false)) {}
  /// Stops the calls running under this flag (thread- and signal-safe).
  void raise() const { flag_->store(true); }
  bool raised() const { return flag_->load(); }
  /// Lowers the flag for the next call.
  void clear() const { flag_->store(false); }

 private:
  std::shared_ptr<std::atomic<bool>> flag_;
};

/// The calling thread runs under `interrupt` while the scope lives (the previous one back after it;
/// scopes nest, the innermost counts). Pass nullptr for none.
class InterruptScope {
 public:
  explicit InterruptScope(const Interrupt* interrupt);
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  const Interrupt* previous_;
};

/// The calling thread's interrupt, or nullptr outside any scope.
const Interrupt* current_interrupt();

/// Whether the calling thread's interrupt is raised.
inline bool interrupted() {
  const Interrupt* i = current_interrupt();
  return i && i->raised();
}

/// Throws InterruptedError(where) when the calling thread's interrupt is raised.
inline void check_interrupt(const char* where) {
  if (interrupted()) throw InterruptedError(where);
}

}  // namespace hexdom
