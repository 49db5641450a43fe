// The original segmentation program's manual override file.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace hexdom::segmentation {

/// Reads "triangle label" lines, both 0-based (label 0..5 = +X, -X, +Y, -Y, +Z, -Z, the original's
/// generator order), and returns (triangle, label + 1) pairs for CvtOptions::manual. Blank lines and
/// lines starting with '#' or '$' are skipped. Throws InputError "path:line: ..." for anything else,
/// a negative triangle or a label outside 0..5.
std::vector<std::pair<int, int>> read_manual_labels(const std::string& path);

}  // namespace hexdom::segmentation
