// Helpers of the io suites: a small mixed mesh, mesh comparison, and the InputError check.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>

#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"
#include "test_common.h"

namespace hexdom::test {

/// `f` must throw InputError whose message starts "<path>:<line>: " ("<path>: " for line 0) and
/// contains `text`, with path() and line() set accordingly.
inline ::testing::AssertionResult ThrowsInputError(const std::function<void()>& f, const std::string& path,
                                                   long line, const std::string& text) {
  try {
    f();
  } catch (const InputError& e) {
    const std::string what = e.what();
    const std::string where = line > 0 ? path + ":" + std::to_string(line) + ": " : path + ": ";
    if (what.rfind(where, 0) != 0)
      return ::testing::AssertionFailure() << "message '" << what << "' does not start with '" << where << "'";
    if (what.find(text) == std::string::npos)
      return ::testing::AssertionFailure() << "message '" << what << "' lacks '" << text << "'";
    if (e.path() != path || e.line() != line)
      return ::testing::AssertionFailure() << "path()/line() are " << e.path() << ":" << e.line();
    return ::testing::AssertionSuccess();
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "threw something else than InputError: " << e.what();
  }
  return ::testing::AssertionFailure() << "no exception";
}

/// Two hexes, a wedge and a tet sharing nodes, plus a triangle and a quad; regions 1..4.
/// Coordinates need all 17 significant digits.
inline mesh::Mesh mixed_mesh() {
  using mesh::CellType;
  Eigen::MatrixXd V(16, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1,  // unit cube 0..7
      2, 0, 0, 2, 1, 0, 2, 0, 1, 2, 1, 1,                                       // 8..11
      1.0 / 3.0, 2.0 / 3.0, 2.0 + 1e-13, 0.1, 0.7, 1.9, 3.25, 0.5, 0.5, 1e-300, -7.0e12, 5.5;
  mesh::MeshBuilder b;
  const int hex1[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  const int hex2[8] = {1, 8, 9, 2, 5, 10, 11, 6};
  const int wedge[6] = {4, 6, 5, 12, 13, 14};
  const int tet[4] = {4, 5, 7, 12};
  const int tri[3] = {0, 1, 15};
  const int quad[4] = {0, 3, 2, 1};
  b.add(CellType::Hex, hex1, 1);
  b.add(CellType::Hex, hex2, 1);
  b.add(CellType::Wedge, wedge, 2);
  b.add(CellType::Tet, tet, 3);
  b.add(CellType::Triangle, tri, 4);
  b.add(CellType::Quad, quad, 4);
  return b.finish(V);
}

/// Only the volume cells of mixed_mesh().
inline mesh::Mesh volume_part(const mesh::Mesh& m) {
  mesh::MeshBuilder b;
  for (int c = 0; c < m.num_cells(); ++c)
    if (mesh::is_volume(m.type(c))) b.add(m.type(c), m.cells.row(c).data(), m.region(c));
  return b.finish(m.V);
}

inline ::testing::AssertionResult SameMesh(const mesh::Mesh& a, const mesh::Mesh& b, double tol = 0.0) {
  if (a.V.rows() != b.V.rows() || a.num_cells() != b.num_cells())
    return ::testing::AssertionFailure() << a.V.rows() << " vs " << b.V.rows() << " nodes, " << a.num_cells()
                                         << " vs " << b.num_cells() << " cells";
  const double d = a.V.rows() ? (a.V - b.V).cwiseAbs().maxCoeff() : 0.0;
  if (!(d <= tol)) return ::testing::AssertionFailure() << "coordinates differ by " << d;
  for (int c = 0; c < a.num_cells(); ++c) {
    if (a.types(c) != b.types(c)) return ::testing::AssertionFailure() << "cell " << c << " type differs";
    if (a.region(c) != b.region(c)) return ::testing::AssertionFailure() << "cell " << c << " region differs";
    if (a.cells.row(c) != b.cells.row(c)) return ::testing::AssertionFailure() << "cell " << c << " nodes differ";
  }
  return ::testing::AssertionSuccess();
}

/// Files in the scratch directory whose name starts with `stem` (to find stray temporaries).
inline int files_starting_with(const std::string& stem) {
  namespace fs = std::filesystem;
  int n = 0;
  const fs::path p(stem);
  for (const auto& e : fs::directory_iterator(p.parent_path()))
    if (e.path().filename().string().rfind(p.filename().string(), 0) == 0) ++n;
  return n;
}

}  // namespace hexdom::test
