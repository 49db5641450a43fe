#include <algorithm>
#include <set>

#include "hexdom/common/error.h"
#include "hexdom/generation/generate.h"
#include "hexdom/io/mesh_io.h"
#include "hexdom/quality/metrics.h"
#include "hexdom/quality/report.h"
#include "test_common.h"

using namespace hexdom;
using mesh::CellType;

namespace {
std::string example(const std::string& name) { return std::string(HEXDOM_SOURCE_DIR) + "/examples/data/" + name; }

struct Example {
  mesh::SurfaceMesh surface = io::read_surface(example("lbracket_patches.k"));
  mesh::Mesh structure = io::read_mesh(example("lbracket_structure.k"));
};
}  // namespace

class GenerateLevels : public ::testing::TestWithParam<int> {};

TEST_P(GenerateLevels, EightToTheLevelCellsPerBlock) {
  Example ex;
  generation::GenerateOptions opt;
  opt.level = GetParam();
  auto m = generation::generate(ex.surface, ex.structure, opt);
  const int per = 1 << (3 * opt.level);
  EXPECT_EQ(m.count(CellType::Hex), 3 * per);
  EXPECT_EQ(m.count(CellType::Wedge), per);
  auto q = quality::quality_report(m);
  EXPECT_EQ(q.hex.inverted + q.prism.inverted, 0);
}
INSTANTIATE_TEST_SUITE_P(Generate, GenerateLevels, ::testing::Values(0, 1, 2, 3));

TEST(Generate, SharedFacesShareNodes) {
  Example ex;
  generation::GenerateOptions opt;
  opt.level = 2;
  auto m = generation::generate(ex.surface, ex.structure, opt);
  // Count quad faces of hexes by sorted nodes: interior faces appear exactly twice, never more.
  std::map<std::array<int, 4>, int> faces;
  static const int hf[6][4] = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};
  for (int c = 0; c < m.num_cells(); ++c) {
    if (m.type(c) != CellType::Hex) continue;
    for (const auto& f : hf) {
      std::array<int, 4> k = {m.cells(c, f[0]), m.cells(c, f[1]), m.cells(c, f[2]), m.cells(c, f[3])};
      std::sort(k.begin(), k.end());
      faces[k]++;
    }
  }
  int twice = 0;
  for (const auto& [k, n] : faces) {
    EXPECT_LE(n, 2);
    twice += n == 2;
  }
  // 3 hex blocks of 4x4x4: 3 * 144 internal faces plus 2 block interfaces of 16 faces.
  EXPECT_EQ(twice, 3 * 144 + 2 * 16);
}

TEST(Generate, LevelOutOfRangeIsAGeometryError) {
  Example ex;
  generation::GenerateOptions opt;
  opt.level = 7;
  EXPECT_THROW(generation::generate(ex.surface, ex.structure, opt), GeometryError);
}

TEST(Generate, RockerarmMatchesPaperCounts) {
  const std::string p = test::data_path("hexdom/rockerarm/rockerarm_indexPatch_hexdom.k");
  const std::string s = test::data_path("hexdom/rockerarm/rockerarm_polycube_withtet.k");
  HEXDOM_REQUIRE_DATA(p);
  HEXDOM_REQUIRE_DATA(s);
  auto m = generation::generate(io::read_surface(p), io::read_mesh(s));
  EXPECT_EQ(m.count(CellType::Hex), 3840);
  EXPECT_EQ(m.count(CellType::Wedge), 704);
  EXPECT_EQ(m.count(CellType::Tet), 128);
}

namespace {
}  // namespace

// The untangling moves a node only when the worst scaled Jacobian sample around it rises, so the
// mesh's worst cell can only get better; on the paper's fertility model it untangles every inverted
// cell of the raw placement, sliding boundary nodes within the surface (their distance to it is
// checked in tests/python/test_generate.py). The plain relaxation keeps the worst cell too.
TEST(Generate, RelaxationNeverLowersTheWorstCellAndUntangles) {
  const std::string p = test::data_path("hexdom/fertility/fertility_indexPatch_hexdom.k");
  const std::string s = test::data_path("hexdom/fertility/fertility_polycube_hexdom_withtet.k");
  HEXDOM_REQUIRE_DATA(p);
  HEXDOM_REQUIRE_DATA(s);
  const auto surface = io::read_surface(p);
  const auto structure = io::read_mesh(s);
  generation::GenerateOptions raw;
  raw.relax_sweeps = 0;
  const auto m0 = generation::generate(surface, structure, raw);
  generation::GenerateOptions untangle;
  untangle.untangle = true;
  const auto m1 = generation::generate(surface, structure, untangle);
  const auto m2 = generation::generate(surface, structure);
  const test::Worst w0 = test::worst_of(m0), w1 = test::worst_of(m1), w2 = test::worst_of(m2);
  EXPECT_GT(w0.inverted, 0) << "the raw placement of fertility should have inverted cells to untangle";
  EXPECT_EQ(w1.inverted, 0);
  EXPECT_GE(w1.all, w0.all);
  EXPECT_GE(w2.all, w0.all);
  EXPECT_LE(w2.inverted, w0.inverted);
  // Same cells, same nodes: only positions change.
  ASSERT_EQ(m0.num_nodes(), m1.num_nodes());
  EXPECT_TRUE(m0.cells == m1.cells);
  int moved = 0;
  for (int v = 0; v < m0.num_nodes(); ++v) moved += (m0.V.row(v) - m1.V.row(v)).norm() > 0;
  EXPECT_GT(moved, 0);
}

// The structure's faces are matched to the patches by polycube::match_faces_to_patches: with
// patch 2 merged into patch 1, a block face matches no patch's corners, and the merged patch no
// block face; generate names the first problem and counts the others.
TEST(Generate, PatchesThatDoNotFitTheStructureNameTheFirstProblemAndCountTheRest) {
  Example ex;
  for (Eigen::Index t = 0; t < ex.surface.patch.size(); ++t)
    if (ex.surface.patch(t) == 2) ex.surface.patch(t) = 1;
  try {
    generation::generate(ex.surface, ex.structure, generation::GenerateOptions{});
    FAIL() << "patches that do not fit the structure were accepted";
  } catch (const GeometryError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("matches no patch"), std::string::npos) << what;
    EXPECT_NE(what.find("more problem"), std::string::npos) << what;
  }
}
