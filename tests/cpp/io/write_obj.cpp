#include "hexdom/io/surface_formats.h"
#include "io_test_util.h"

using namespace hexdom;

TEST(WriteObj, RoundTripKeepsCoordinatesAndPatches) {
  mesh::SurfaceMesh s;
  s.V.resize(5, 3);
  s.V << 1.0 / 3.0, 0, 0, 1, 1e-300, 0, 0, 1, 0, 0, 0, 1, -2.5e17, 1, 1;
  s.F.resize(4, 3);
  s.F << 0, 1, 2, 0, 2, 3, 1, 2, 3, 2, 3, 4;
  s.patch.resize(4);
  s.patch << 5, -1, 5, 0;
  const std::string path = test::temp_path("round_trip.obj");
  io::write_obj(path, s);
  auto r = io::read_obj(path);
  EXPECT_EQ(r.V, s.V);
  ASSERT_EQ(r.F.rows(), 4);
  // Faces come back grouped by patch (-1, 0, 5, 5); each keeps its vertices and patch.
  std::vector<std::tuple<int, int, int, int>> a, b;
  for (int t = 0; t < 4; ++t) {
    a.emplace_back(s.patch(t), s.F(t, 0), s.F(t, 1), s.F(t, 2));
    b.emplace_back(r.patch(t), r.F(t, 0), r.F(t, 1), r.F(t, 2));
  }
  std::sort(a.begin(), a.end());
  EXPECT_EQ(a, b);
}
