// printf-style formatting of a few numbers into a std::string, for log lines and messages.
#pragma once

#include <cstdio>
#include <string>

namespace hexdom {

/// `f` (a printf format taking up to four doubles, e.g. "%.0f blocks, worst %.3f") applied to a..d.
inline std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d);
  return buf;
}

}  // namespace hexdom
