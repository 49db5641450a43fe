#include "hexdom/common/error.h"

namespace hexdom {

static std::string format_input_error(const std::string& path, long line, const std::string& text) {
  std::string s = path;
  if (line > 0) s += ":" + std::to_string(line);
  if (!s.empty()) s += ": ";
  return s + text;
}

InputError::InputError(const std::string& path, long line, const std::string& text)
    : Error(format_input_error(path, line, text)), path_(path), line_(line) {}

}  // namespace hexdom
