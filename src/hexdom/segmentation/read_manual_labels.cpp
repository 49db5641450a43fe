#include "hexdom/segmentation/read_manual_labels.h"

#include "hexdom/common/error.h"
#include "hexdom/io/text.h"

namespace hexdom::segmentation {

std::vector<std::pair<int, int>> read_manual_labels(const std::string& path) {
  const std::string text = io::load_file(path);
  io::LineCursor cur(path, text);
  std::vector<std::pair<int, int>> out;
  std::string_view line;
  while (cur.next(line)) {
    line = io::trim(line);
    if (line.empty() || line[0] == '#' || line[0] == '$') continue;
    auto fields = io::split_ws(line);
    long t = 0, l = 0;
    if (fields.size() != 2 || !io::parse_int(fields[0], t) || !io::parse_int(fields[1], l))
      cur.fail("expected 'triangle label' (two integers, 0-based), found '" + std::string(line) + "'");
    if (t < 0) cur.fail("triangle index " + std::to_string(t) + " is negative (indices are 0-based)");
    if (l < 0 || l > 5) cur.fail("label " + std::to_string(l) + " is not 0..5 (+X, -X, +Y, -Y, +Z, -Z)");
    out.emplace_back(static_cast<int>(t), static_cast<int>(l) + 1);
  }
  return out;
}

}  // namespace hexdom::segmentation
