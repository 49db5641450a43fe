// io::face_sets: each boundary face's CAD face and each CAD face's nodes, from the nearest triangle of
// the tessellation alone and with the CAD faces each node was snapped onto (node_faces). Oracle: a
// unit cube as one hex, its sides numbered as FreeCAD numbers a box's faces (x = 0, x = 1, y = 0,
// y = 1, z = 0, z = 1 -> 1..6), and each corner on the three sides through it.
#include <gtest/gtest.h>

#include <algorithm>

#include "hexdom/io/face_sets.h"
#include "hexdom/mesh/second_order.h"

using namespace hexdom;

namespace {

// Corner i + 2j + 4k at (i, j, k), as one hex in VTK's order.
mesh::Mesh cube() {
  Eigen::MatrixXd V(8, 3);
  for (int i = 0; i < 8; ++i) V.row(i) << (i & 1), ((i >> 1) & 1), ((i >> 2) & 1);
  const int h[8] = {0, 1, 3, 2, 4, 5, 7, 6};
  mesh::MeshBuilder b;
  b.add(mesh::CellType::Hex, h, 1);
  return b.finish(V);
}

// The sides through corner i (increasing).
std::vector<int> sides_of(int i) {
  std::vector<int> s;
  for (int k = 0; k < 3; ++k) s.push_back(2 * k + 1 + ((i >> k) & 1));
  std::sort(s.begin(), s.end());
  return s;
}

// The cube's sides as two triangles each, patch = side number.
mesh::SurfaceMesh tessellation() {
  mesh::SurfaceMesh s;
  s.V.resize(8, 3);
  for (int i = 0; i < 8; ++i) s.V.row(i) << (i & 1), ((i >> 1) & 1), ((i >> 2) & 1);
  s.F.resize(12, 3);
  s.patch.resize(12);
  int t = 0;
  for (int k = 0; k < 3; ++k) {
    const int a = 1 << ((k + 1) % 3), b = 1 << ((k + 2) % 3);
    for (int side = 0; side < 2; ++side) {
      const int o = side << k;
      s.F.row(t) << o, o + a, o + a + b;  // orientation does not matter here
      s.F.row(t + 1) << o, o + a + b, o + b;
      s.patch(t) = s.patch(t + 1) = 2 * k + 1 + side;
      t += 2;
    }
  }
  return s;
}

std::vector<std::vector<int>> all_sides() {
  std::vector<std::vector<int>> out;
  for (int i = 0; i < 8; ++i) out.push_back(sides_of(i));
  return out;
}

// The side a boundary face lies on, by its corners.
int side(const mesh::Mesh& m, const mesh::BoundaryFace& f) {
  for (int k = 0; k < 3; ++k)
    for (int v = 0; v < 2; ++v) {
      bool all = true;
      for (int i = 0; i < f.n; ++i) all = all && m.V(f.v[i], k) == v;
      if (all) return 2 * k + 1 + v;
    }
  return 0;
}

std::vector<int> corners_on(int tag) {
  std::vector<int> out;
  for (int i = 0; i < 8; ++i) {
    const std::vector<int> s = sides_of(i);
    if (std::count(s.begin(), s.end(), tag)) out.push_back(i);
  }
  return out;
}

}  // namespace

TEST(FaceSets, NearestTriangleOrSnappedFacesGiveEachSideItsFourCorners) {
  const mesh::Mesh m = cube();
  for (bool with_nodes : {false, true}) {
    const io::FaceSets sets = io::face_sets(m, tessellation(), with_nodes ? all_sides() : std::vector<std::vector<int>>{});
    ASSERT_EQ(sets.faces.size(), 6u);
    for (size_t i = 0; i < 6; ++i) EXPECT_EQ(sets.tag[i], side(m, sets.faces[i])) << i;
    EXPECT_EQ(std::count(sets.across.begin(), sets.across.end(), 1), 0);
    ASSERT_EQ(sets.nodes.size(), 6u);
    for (const auto& [tag, nodes] : sets.nodes) EXPECT_EQ(nodes, corners_on(tag)) << tag;
  }
}

// A node known to lie on other CAD faces only leaves a face's node set, with the mid-edge nodes of
// its edges (a boundary quad straddling a sharp curve keeps the nodes on its tag's face alone); the
// face still takes the nearest triangle's tag. Corners that all share one other face take it.
TEST(FaceSets, NodesSnappedElsewhereLeaveTheSet) {
  for (int order : {1, 2}) {
    mesh::Mesh m = cube();
    if (order == 2) m = mesh::add_mid_edge_nodes(m);
    std::vector<std::vector<int>> faces = all_sides();
    faces[0] = {1, 3};  // corner 0 said to be on x = 0 and y = 0 only, not on z = 0 (side 5)
    for (int i : corners_on(6)) faces[i].push_back(9);  // side 6's corners also on a face 9
    faces[7] = {2};     // corner 7 (1, 1, 1) said to be on side 2 only
    const io::FaceSets sets = io::face_sets(m, tessellation(), faces);
    for (size_t i = 0; i < sets.faces.size(); ++i) EXPECT_EQ(sets.tag[i], side(m, sets.faces[i])) << i;
    const std::vector<int>& bottom = sets.nodes.at(5);
    EXPECT_FALSE(std::binary_search(bottom.begin(), bottom.end(), 0));
    // Side 5's other three corners, and of its four mid-edge nodes the two away from corner 0.
    EXPECT_EQ(bottom.size(), order == 1 ? 3u : 5u);
    EXPECT_EQ(sets.nodes.at(1).size(), order == 1 ? 4u : 8u);
    // Side 4 (y = 1) held corner 7, on side 2 only now: it and its two mid-edge nodes leave.
    const std::vector<int>& back = sets.nodes.at(4);
    EXPECT_FALSE(std::binary_search(back.begin(), back.end(), 7));
    EXPECT_EQ(back.size(), order == 1 ? 3u : 5u);
    EXPECT_EQ(sets.nodes.at(3).size(), order == 1 ? 4u : 8u);
    EXPECT_EQ(io::set_nodes(m, sets, 5), bottom);
    // Sides 4, 5 and 6 have corners sharing no CAD face now: they cross a CAD edge.
    for (size_t i = 0; i < sets.faces.size(); ++i) {
      const int t = side(m, sets.faces[i]);
      EXPECT_EQ(sets.across[i], t >= 4) << t;
    }
  }
  // Corners that all share face 9 only: the face takes 9 whatever the nearest triangle.
  const mesh::Mesh m = cube();
  std::vector<std::vector<int>> faces = all_sides();
  for (int i : corners_on(6)) faces[i] = {9};
  const io::FaceSets sets = io::face_sets(m, tessellation(), faces);
  int nine = 0;
  for (size_t i = 0; i < sets.faces.size(); ++i) nine += sets.tag[i] == 9 && side(m, sets.faces[i]) == 6;
  EXPECT_EQ(nine, 1);
}

// Sets made by hand (no node lists): set_nodes gives every node of the tag's faces.
TEST(FaceSets, SetNodesOfHandMadeSets) {
  const mesh::Mesh m = mesh::add_mid_edge_nodes(cube());
  io::FaceSets sets;
  sets.faces = mesh::boundary_faces(m);
  for (const mesh::BoundaryFace& f : sets.faces) sets.tag.push_back(side(m, f));
  for (int tag = 1; tag <= 6; ++tag) EXPECT_EQ(io::set_nodes(m, sets, tag).size(), 8u) << tag;
}
