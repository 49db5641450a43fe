// Shared helpers for the GoogleTest suites: where the paper data is, the paper models, tiny cells.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "hexdom/mesh/mesh.h"
#include "hexdom/quality/metrics.h"

namespace hexdom::test {

/// Root of the shared data (HEXDOM_DATA, else ../shared/data beside the repository).
inline std::string data_root() {
  const char* env = std::getenv("HEXDOM_DATA");
  return env && *env ? env : HEXDOM_DEFAULT_DATA;
}

/// Path of a file under data_root(), e.g. data_path("hexdom/rockerarm/rockerarm.k").
inline std::string data_path(const std::string& rel) { return data_root() + "/" + rel; }

/// Skips the current test, naming the missing path, when a data file is absent.
#define HEXDOM_REQUIRE_DATA(path)                                                     \
  do {                                                                                \
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data missing: " << (path); \
  } while (0)

/// A fresh scratch path for one test.
inline std::string temp_path(const std::string& name) {
  std::filesystem::create_directories(HEXDOM_TEST_TMP);
  return std::string(HEXDOM_TEST_TMP) + "/" + name;
}

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// The paper models that come with a hand-built *_withtet.k structure.
inline const std::vector<std::string>& paper_models() {
  static const std::vector<std::string> m = {"rockerarm", "mount1", "hepta", "fertility", "ant", "mountwithhole"};
  return m;
}

/// Unit cube as a hex, unit wedge (equilateral triangles, Verdict's ideal), and the corner unit tet,
/// in VTK order.
// Worst scaled Jacobian of each cell type and of all cells (quality::signed_sj: -1 for a
// degenerate cell), and the number of inverted cells, by the quality module.
struct Worst {
  double hex = 2, prism = 2, tet = 2, all = 2;
  int inverted = 0;
};
inline Worst worst_of(const mesh::Mesh& m) {
  Worst w;
  for (int c = 0; c < m.num_cells(); ++c) {
    const double raw = quality::scaled_jacobian(m.type(c), quality::cell_points(m, c));
    w.inverted += quality::is_inverted(raw);
    const double sj = quality::signed_sj(raw);
    double& t = m.type(c) == mesh::CellType::Hex ? w.hex : m.type(c) == mesh::CellType::Wedge ? w.prism : w.tet;
    t = std::min(t, sj);
    w.all = std::min(w.all, sj);
  }
  return w;
}

inline quality::CellPoints unit_hex() {
  quality::CellPoints P;
  P << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  return P;
}
inline quality::CellPoints unit_wedge() {
  // VTK wedge: first triangle's normal points away from the second.
  quality::CellPoints P = quality::CellPoints::Zero();
  const double h = std::sqrt(3.0) / 2.0;
  P.topRows(6) << 0, 0, 0, 0.5, h, 0, 1, 0, 0, 0, 0, 1, 0.5, h, 1, 1, 0, 1;
  return P;
}
inline quality::CellPoints unit_tet() {
  quality::CellPoints P = quality::CellPoints::Zero();
  P.topRows(4) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  return P;
}

}  // namespace hexdom::test
