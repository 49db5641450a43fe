// Error types thrown by every stage. Stages never print or exit: they throw one of these, and the
// program, the Python module and the workbench turn it into an exit code, an exception or a message.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

namespace hexdom {

/// Base of every error HexDom reports on purpose.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

/// Unreadable or malformed input. Prints as "path:line: text" (or "path: text" without a line).
class InputError : public Error {
 public:
  InputError(const std::string& path, long line, const std::string& text);
  explicit InputError(const std::string& text) : Error(text), line_(0) {}
  const std::string& path() const { return path_; }
  long line() const { return line_; }

 private:
  std::string path_;
  long line_;
};

/// Input that parses but cannot be meshed (open surface, invalid polycube, ...); names the ids.
class GeometryError : public Error {
 public:
  explicit GeometryError(const std::string& what) : Error(what) {}
};

/// A stage that cannot keep its contract (a solve that fails, an inverted cell that remains).
class MeshingError : public Error {
 public:
  explicit MeshingError(const std::string& what) : Error(what) {}
};

/// A computation that ran out of its time budget (Deadline::check) before it had a result: the
/// stage that stopped and the budget. Prints as "<where>: stopped after the time budget of 5 s".
/// Callers that have another way to a result (the auto method's overlay path) treat it as a failure
/// of that path; the others pass it on (the program exits 5).
class TimeoutError : public Error {
 public:
  /// `cancelled`: the run was called off (Deadline::cancel), not out of time: "<where>: cancelled".
  TimeoutError(const std::string& where, double budget, bool cancelled = false);
  const std::string& where() const { return where_; }
  double budget() const { return budget_; }  ///< seconds
  bool cancelled() const { return cancelled_; }

 private:
  std::string where_;
  double budget_;
  bool cancelled_;
};

/// The whole call ran past its time limit (run_with_time_limit, the program's --time-limit): a
/// TimeoutError whose `where` is the step that was running, followed by "(time limit of the run)".
class TimeLimitError : public TimeoutError {
 public:
  TimeLimitError(const std::string& step, double budget) : TimeoutError(step + " (time limit of the run)", budget) {}
};

/// Optional progress and warning sink carried in options structs. Level: 0 info, 1 warning.
using LogCallback = std::function<void(int level, const std::string& message)>;

}  // namespace hexdom
