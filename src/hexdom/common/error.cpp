#include "hexdom/common/error.h"

#include <cstdio>

namespace hexdom {

static std::string format_input_error(const std::string& path, long line, const std::string& text) {
  std::string s = path;
  if (line > 0) s += ":" + std::to_string(line);
  if (!s.empty()) s += ": ";
  return s + text;
}

InputError::InputError(const std::string& path, long line, const std::string& text)
    : Error(format_input_error(path, line, text)), path_(path), line_(line) {}

static std::string format_timeout(const std::string& where, double budget) {
  char seconds[64];
  std::snprintf(seconds, sizeof seconds, "%g", budget);
  return (where.empty() ? std::string() : where + ": ") + "stopped after the time budget of " + seconds + " s";
}

TimeoutError::TimeoutError(const std::string& where, double budget, bool cancelled)
    : Error(cancelled ? where + ": cancelled" : format_timeout(where, budget)), where_(where), budget_(budget), cancelled_(cancelled) {}

}  // namespace hexdom
