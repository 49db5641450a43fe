// Gmsh .msh files (io::read_msh): hand-written MSH 4.1 and 2.2 files, ASCII and binary (the bytes
// built here), second-order cells, regions from physical groups, and malformed files giving the
// line and the message.
#include <cstdint>
#include <cstring>
#include <initializer_list>

#include "hexdom/io/mesh_io.h"
#include "hexdom/io/msh.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/quality/metrics.h"
#include "hexdom/mesh/second_order.h"
#include "io_test_util.h"

using namespace hexdom;
using mesh::CellType;
using test::ThrowsInputError;

namespace {

std::string write(const std::string& name, const std::string& text) {
  const std::string path = test::temp_path(name);
  test::write_text(path, text);
  return path;
}

// 1-based line of the first occurrence of `what` in `text` (0 when absent).
long line_of(const std::string& text, const std::string& what) {
  const size_t at = text.find(what);
  return at == std::string::npos ? 0 : 1 + static_cast<long>(std::count(text.begin(), text.begin() + at, '\n'));
}

// A unit hex (tags 10..80, volume 1, physical 5) and a prism on its x = 1 face (tags 20, 90, 30, 60,
// 100, 70 in Gmsh's order, volume 2, no physical group) with sparse node tags out of order, a
// point, a boundary triangle and other sections to skip.
const char* const kHexPrism41 = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
3 5 "hex part"
2 9 "skin"
$EndPhysicalNames
$Entities
1 0 1 2
1 0 0 0 0
3 0 0 0 1 1 0 1 9 0
1 0 0 0 1 1 1 1 5 0
2 1 0 0 2 1 1 0 0
$EndEntities
$Nodes
3 10 10 100
0 1 0 1
10
0 0 0
3 1 0 7
80
20
40
30
50
60
70
0 1 1
1 0 0
0 1 0
1 1 0
0 0 1
1 0 1
1 1 1
3 2 1 2
100
90
2 0 1 0.5 0.5 0.5
2 0 0 0.5 0.5 0.5
$EndNodes
$Elements
4 4 1 12
0 1 15 1
12 10
2 3 2 1
11 20 30 60
3 1 5 1
1 10 20 30 40 50 60 70 80
3 2 6 1
7 20 90 30 60 100 70
$EndElements
$NodeData
1
"a view"
0
3
0
1
1
10 3.5
$EndNodeData
)";

// The same mesh in MSH 2.2: the hex is written twice (two physical groups, as Gmsh does), the
// prism has physical tag 0 (its entity's tag, 2, is the region).
const char* const kHexPrism22 = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
10
10 0 0 0
80 0 1 1
20 1 0 0
40 0 1 0
30 1 1 0
50 0 0 1
60 1 0 1
70 1 1 1
100 2 0 1
90 2 0 0
$EndNodes
$Elements
5
12 15 2 0 1 10
11 2 2 9 3 20 30 60
1 5 2 5 1 10 20 30 40 50 60 70 80
2 5 2 6 1 10 20 30 40 50 60 70 80
7 6 2 0 2 20 90 30 60 100 70
$EndElements
)";

// Checks the mesh of kHexPrism41 / kHexPrism22: node order of the file, the hex as is, the prism
// turned into VTK's wedge, regions, no inverted cell and the right volume.
void expect_hex_prism(const mesh::Mesh& m) {
  ASSERT_EQ(m.num_nodes(), 10);
  ASSERT_EQ(m.num_cells(), 2);
  EXPECT_FALSE(m.second_order());
  EXPECT_EQ(m.type(0), CellType::Hex);
  EXPECT_EQ(m.type(1), CellType::Wedge);
  EXPECT_EQ(m.region(0), 5);
  EXPECT_EQ(m.region(1), 2);
  // Index of each tag in the file's node order.
  const int at[] = {0, 2, 4, 3, 5, 6, 7, 1, 9, 8};  // tag 10 k -> at[k - 1] (both files' order)
  for (int i = 0; i < 8; ++i) EXPECT_EQ(m.cells(0, i), at[i]) << i;
  const int wedge[6] = {20, 30, 90, 60, 70, 100};  // Gmsh 20 90 30 60 100 70 with 1<->2, 4<->5
  for (int i = 0; i < 6; ++i) EXPECT_EQ(m.cells(1, i), at[wedge[i] / 10 - 1]) << i;
  EXPECT_EQ(m.V.row(at[8]), Eigen::RowVector3d(2, 0, 0));
  EXPECT_EQ(m.V.row(at[9]), Eigen::RowVector3d(2, 0, 1));
  EXPECT_EQ(test::worst_of(m).inverted, 0);
  double volume = 0;
  for (int c = 0; c < m.num_cells(); ++c) volume += quality::volume(m.type(c), quality::cell_points(m, c));
  EXPECT_NEAR(volume, 1.5, 1e-14);
}

// Little-endian (or big-endian) bytes of a value.
template <class T>
void put(std::string& s, T v, bool big = false) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  for (size_t i = 0; i < sizeof(T); ++i) s += static_cast<char>(b[big ? sizeof(T) - 1 - i : i]);
}

const double kPoints[10][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1},
                               {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, {2, 0, 0}, {2, 0, 1}};

// kHexPrism41 as a binary MSH 4.1 file (nodes in tag order, tags 10..100); `cut` drops that many
// bytes from the end of the node data.
std::string hex_prism_41_binary(size_t cut = 0) {
  std::string s = "$MeshFormat\n4.1 1 8\n";
  put<int32_t>(s, 1);
  s += "\n$EndMeshFormat\n$Entities\n";
  for (uint64_t c : {0, 0, 0, 2}) put<uint64_t>(s, c);
  for (int32_t v : {1, 2}) {
    put<int32_t>(s, v);
    for (int k = 0; k < 6; ++k) put<double>(s, 0.0);
    put<uint64_t>(s, v == 1 ? 1 : 0);
    if (v == 1) put<int32_t>(s, 5);
    put<uint64_t>(s, 0);
  }
  s += "\n$EndEntities\n$Nodes\n";
  for (uint64_t c : {1, 10, 10, 100}) put<uint64_t>(s, c);
  for (int32_t v : {3, 1, 0}) put<int32_t>(s, v);
  put<uint64_t>(s, 10);
  for (uint64_t t = 10; t <= 100; t += 10) put<uint64_t>(s, t);
  for (const auto& p : kPoints)
    for (double x : p) put<double>(s, x);
  s.resize(s.size() - cut);
  s += "\n$EndNodes\n$Elements\n";
  for (uint64_t c : {2, 2, 1, 7}) put<uint64_t>(s, c);
  for (int32_t v : {3, 1, 5}) put<int32_t>(s, v);
  put<uint64_t>(s, 1);
  for (uint64_t v : {1, 10, 20, 30, 40, 50, 60, 70, 80}) put<uint64_t>(s, v);
  for (int32_t v : {3, 2, 6}) put<int32_t>(s, v);
  put<uint64_t>(s, 1);
  for (uint64_t v : {7, 20, 90, 30, 60, 100, 70}) put<uint64_t>(s, v);
  return s + "\n$EndElements\n";
}

// The same as a binary MSH 2.2 file, big-endian when `big`.
std::string hex_prism_22_binary(bool big, int32_t check = 1) {
  std::string s = "$MeshFormat\n2.2 1 8\n";
  put<int32_t>(s, check, big);
  s += "\n$EndMeshFormat\n$Nodes\n10\n";
  for (int i = 0; i < 10; ++i) {
    put<int32_t>(s, 10 * (i + 1), big);
    for (double x : kPoints[i]) put<double>(s, x, big);
  }
  s += "\n$EndNodes\n$Elements\n2\n";
  for (int32_t v : {5, 1, 2, 1, 5, 1, 10, 20, 30, 40, 50, 60, 70, 80}) put<int32_t>(s, v, big);
  for (int32_t v : {6, 1, 2, 7, 0, 2, 20, 90, 30, 60, 100, 70}) put<int32_t>(s, v, big);
  return s + "\n$EndElements\n";
}

// One second-order cell in MSH 4.1: `corners`, then a node in the middle of each edge of Gmsh's
// list (the reference element's order, restated here from the Gmsh manual).
std::string one_second_order(int type, const std::vector<Eigen::RowVector3d>& corners,
                             const std::vector<std::pair<int, int>>& edges) {
  std::vector<Eigen::RowVector3d> p = corners;
  for (auto [a, b] : edges) p.push_back((corners[a] + corners[b]) / 2);
  const size_t n = p.size();
  std::string s = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 " + std::to_string(n) + " 1 " + std::to_string(n) +
                  "\n3 1 0 " + std::to_string(n) + "\n";
  for (size_t i = 1; i <= n; ++i) s += std::to_string(i) + "\n";
  for (const auto& q : p) s += std::to_string(q(0)) + " " + std::to_string(q(1)) + " " + std::to_string(q(2)) + "\n";
  s += "$EndNodes\n$Elements\n1 1 1 1\n3 1 " + std::to_string(type) + " 1\n1";
  for (size_t i = 1; i <= n; ++i) s += " " + std::to_string(i);
  return s + "\n$EndElements\n";
}

// Every mid-edge node of a second-order mesh lies in the middle of its VTK edge.
::testing::AssertionResult MidNodesOnTheirEdges(const mesh::Mesh& m) {
  if (!m.second_order()) return ::testing::AssertionFailure() << "not second order";
  for (int c = 0; c < m.num_cells(); ++c) {
    const auto [edges, ne] = mesh::cell_edges(m.type(c));
    for (int e = 0; e < ne; ++e) {
      const Eigen::RowVector3d mid = (m.V.row(m.cells(c, edges[e][0])) + m.V.row(m.cells(c, edges[e][1]))) / 2;
      if ((m.V.row(m.mid(c, e)) - mid).norm() > 1e-12)
        return ::testing::AssertionFailure() << "cell " << c << " edge " << e << ": mid node " << m.mid(c, e);
    }
  }
  return ::testing::AssertionSuccess();
}

// 1-based line of a byte offset (the newline bytes of binary data count too, as in an editor).
long line_at(const std::string& text, size_t offset) {
  return 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(offset), '\n'));
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? s : s.replace(at, from.size(), to);
}

}  // namespace

TEST(ReadMsh, Ascii41HexAndPrismWithSparseTagsAndRegions) {
  expect_hex_prism(io::read_msh(write("hex_prism_41.msh", kHexPrism41)));
}

TEST(ReadMsh, Ascii22HexAndPrismReadOnceWithThePhysicalOrEntityTag) {
  expect_hex_prism(io::read_msh(write("hex_prism_22.msh", kHexPrism22)));
}

TEST(ReadMsh, Binary41ReadsAsTheAsciiFile) {
  const mesh::Mesh m = io::read_msh(write("hex_prism_41_bin.msh", hex_prism_41_binary()));
  ASSERT_EQ(m.num_nodes(), 10);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(m.V.row(i), Eigen::RowVector3d(kPoints[i][0], kPoints[i][1], kPoints[i][2]));
  ASSERT_EQ(m.num_cells(), 2);
  EXPECT_EQ(m.cells.row(0), (mesh::CellMatrix::RowXpr::PlainObject() << 0, 1, 2, 3, 4, 5, 6, 7).finished());
  EXPECT_EQ(m.cells.row(1).head(6), (Eigen::Matrix<int, 1, 6>() << 1, 2, 8, 5, 6, 9).finished());
  EXPECT_EQ(m.region(0), 5);
  EXPECT_EQ(m.region(1), 2);
  EXPECT_EQ(test::worst_of(m).inverted, 0);
}

TEST(ReadMsh, Binary22LittleAndBigEndian) {
  for (bool big : {false, true}) {
    const mesh::Mesh m = io::read_msh(write(big ? "hex_prism_22_be.msh" : "hex_prism_22_le.msh", hex_prism_22_binary(big)));
    ASSERT_EQ(m.num_cells(), 2) << big;
    EXPECT_EQ(m.V.row(9), Eigen::RowVector3d(2, 0, 1)) << big;
    EXPECT_EQ(m.cells.row(1).head(6), (Eigen::Matrix<int, 1, 6>() << 1, 2, 8, 5, 6, 9).finished()) << big;
    EXPECT_EQ(m.region(0), 5) << big;
    EXPECT_EQ(m.region(1), 2) << big;  // physical 0: the entity's tag
  }
}

TEST(ReadMsh, SecondOrderTetHexPrismGetVtkMidNodes) {
  using V3 = Eigen::RowVector3d;
  const std::vector<V3> tet = {V3(0, 0, 0), V3(1, 0, 0), V3(0, 1, 0), V3(0, 0, 1)};
  const std::vector<V3> hex = {V3(0, 0, 0), V3(1, 0, 0), V3(1, 1, 0), V3(0, 1, 0),
                               V3(0, 0, 1), V3(1, 0, 1), V3(1, 1, 1), V3(0, 1, 1)};
  const std::vector<V3> prism = {V3(0, 0, 0), V3(1, 0, 0), V3(0, 1, 0), V3(0, 0, 1), V3(1, 0, 1), V3(0, 1, 1)};
  struct Case { int type; std::vector<V3> corners; std::vector<std::pair<int, int>> edges; CellType t; double volume; };
  const Case cases[] = {
      {11, tet, {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}}, CellType::Tet, 1.0 / 6},
      {17, hex, {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3}, {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}}, CellType::Hex, 1},
      {18, prism, {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 4}, {2, 5}, {3, 4}, {3, 5}, {4, 5}}, CellType::Wedge, 0.5}};
  for (const Case& k : cases) {
    const mesh::Mesh m = io::read_msh(write("second_" + std::to_string(k.type) + ".msh", one_second_order(k.type, k.corners, k.edges)));
    ASSERT_EQ(m.num_cells(), 1) << k.type;
    EXPECT_EQ(m.type(0), k.t) << k.type;
    EXPECT_TRUE(MidNodesOnTheirEdges(m)) << k.type;
    EXPECT_EQ(test::worst_of(m).inverted, 0) << k.type;
    EXPECT_NEAR(quality::volume(m.type(0), quality::cell_points(m, 0)), k.volume, 1e-12) << k.type;
  }
}

TEST(ReadMsh, Tet10MidNodesFollowTheirEdges) {
  // Gmsh's tet10 gives the mid nodes of edges 3-0, 3-2, 3-1 where VTK wants 0-3, 1-3, 2-3.
  const std::string path = write("tet10.msh", one_second_order(11, {Eigen::RowVector3d(0, 0, 0), Eigen::RowVector3d(1, 0, 0),
                                                                     Eigen::RowVector3d(0, 1, 0), Eigen::RowVector3d(0, 0, 1)},
                                                               {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}}));
  const mesh::Mesh m = io::read_msh(path);
  ASSERT_TRUE(m.second_order());
  EXPECT_EQ(m.mid.row(0).head(6), (Eigen::Matrix<int, 1, 6>() << 4, 5, 6, 7, 9, 8).finished());
}

TEST(ReadMsh, SurfaceOnlyFileGivesItsTrianglesAndQuads) {
  const std::string path = write("surface.msh",
                                 "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n"
                                 "0 0 0\n1 0 0\n1 1 0\n0 1 0\n$EndNodes\n$Elements\n3 3 1 3\n1 1 1 1\n3 1 2\n"
                                 "2 1 2 1\n1 1 2 3\n2 1 3 1\n2 1 2 3 4\n$EndElements\n");
  const mesh::Mesh m = io::read_msh(path);
  ASSERT_EQ(m.num_cells(), 2);
  EXPECT_EQ(m.type(0), CellType::Triangle);
  EXPECT_EQ(m.type(1), CellType::Quad);
  EXPECT_EQ(m.region(0), 1);  // no $Entities: the entity's tag
  EXPECT_EQ(io::read_mesh(path).num_cells(), 2);
  EXPECT_EQ(io::read_surface(path).F.rows(), 3);
}

TEST(ReadMsh, ReadMeshDispatchesAndWritesBack) {
  EXPECT_EQ(io::format_of("a/b.MSH"), io::Format::Msh);
  const std::string path = write("dispatch.msh", kHexPrism41);
  const mesh::Mesh m = io::read_mesh(path);
  EXPECT_EQ(m.num_cells(), 2);
  // write_msh then read_msh: the same cells, nodes and regions.
  const std::string out = test::temp_path("out.msh");
  io::write_mesh(out, m);
  EXPECT_TRUE(test::SameMesh(io::read_mesh(out), m));
  EXPECT_TRUE(ThrowsInputError([&] { io::format_of("m.xyz"); }, "m.xyz", 0, ".msh"));
}

TEST(ReadMsh, SecondOrderAndFaceSetsWriteBack) {
  mesh::Mesh m = mesh::add_mid_edge_nodes(test::volume_part(test::mixed_mesh()));
  m.V(m.mid(0, 3), 0) += 0.05;
  io::FaceSets sets;
  sets.faces = mesh::boundary_faces(m);
  for (size_t i = 0; i < sets.faces.size(); ++i) sets.tag.push_back(1 + static_cast<int>(i % 3));
  const std::string out = test::temp_path("quadratic_sets.msh");
  io::write_msh(out, m, &sets);
  const mesh::Mesh r = io::read_msh(out);  // the boundary elements are skipped: the volume comes back
  EXPECT_TRUE(test::SameMesh(r, m));
  EXPECT_EQ(r.mid, m.mid);
}

// ---- malformed files ----

TEST(ReadMsh, NotAMshFile) {
  const std::string path = write("bad_header.msh", "hello\nworld\n");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(path); }, path, 1, "not a Gmsh mesh file"));
}

TEST(ReadMsh, UnsupportedVersionNamesLineTwo) {
  const std::string path = write("version.msh", replaced(kHexPrism41, "4.1 0 8", "4.0 0 8"));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(path); }, path, 2, "MSH version '4.0' is not supported"));
}

TEST(ReadMsh, BadFileTypeAndDataSize) {
  const std::string a = write("file_type.msh", replaced(kHexPrism41, "4.1 0 8", "4.1 2 8"));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(a); }, a, 2, "file type 2"));
  const std::string b = write("data_size.msh", replaced(kHexPrism22, "2.2 0 8", "2.2 0 4"));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(b); }, b, 2, "data size 4 is not supported"));
}

TEST(ReadMsh, ElementWithAnUnknownNodeTag) {
  const std::string text = replaced(kHexPrism41, "1 10 20 30 40 50 60 70 80", "1 10 20 30 40 50 60 70 99");
  const std::string path = write("unknown_node.msh", text);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(path); }, path, line_of(text, "1 10 20 30"),
                               "element 1 refers to node tag 99, which $Nodes does not give"));
  const std::string t22 = replaced(kHexPrism22, "7 6 2 0 2 20 90", "7 6 2 0 2 20 91");
  const std::string p22 = write("unknown_node_22.msh", t22);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(p22); }, p22, line_of(t22, "7 6 2"), "element 7 refers to node tag 91"));
}

TEST(ReadMsh, DuplicateNodeTag) {
  const std::string text = replaced(kHexPrism41, "100\n90\n", "100\n50\n");
  const std::string path = write("duplicate_node.msh", text);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(path); }, path, line_of(text, "100\n50") + 1,
                               "node tag 50 is given twice (first on line " + std::to_string(line_of(text, "50\n60")) + ")"));
}

TEST(ReadMsh, TruncatedNodes) {
  const std::string full = kHexPrism41;
  const std::string text = full.substr(0, full.find("2 0 0 0.5"));
  const std::string path = write("truncated_nodes.msh", text);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(path); }, path, line_of(text, "2 0 1 0.5"),
                               "file ends where node coordinate was expected (truncated?)"));
  // A block holding fewer nodes than it says runs into $EndNodes.
  const std::string short22 = replaced(kHexPrism22, "$Nodes\n10\n", "$Nodes\n11\n");
  const std::string p22 = write("short_nodes_22.msh", short22);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(p22); }, p22, line_of(short22, "$EndNodes"),
                               "found '$EndNodes' where node tag was expected"));
}

TEST(ReadMsh, TruncatedBinaryData) {
  // 4.1: a node block whose records run past the end: its count is more than the bytes left.
  const std::string full41 = hex_prism_41_binary();
  const std::string cut41 = full41.substr(0, full41.find("\n$EndNodes") - 20);
  const size_t block = cut41.find("$Nodes\n") + 7 + 4 * 8;  // after the section header's 4 size_t
  const std::string p41 = write("truncated_binary_41.msh", cut41);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(p41); }, p41, line_at(cut41, block + 12),
                               "block node count 10 is larger than the file can hold (truncated?"));
  // 2.2: the last element's nodes end early.
  const std::string full22 = hex_prism_22_binary(false);
  const std::string cut22 = full22.substr(0, full22.find("\n$EndElements") - 6);
  const std::string p22 = write("truncated_binary_22.msh", cut22);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(p22); }, p22, line_at(cut22, cut22.size() - 2),
                               "file ends inside element node: 4 bytes needed, 2 left (truncated?)"));
}

TEST(ReadMsh, CountLargerThanTheFile) {
  const std::string text = replaced(kHexPrism41, "3 10 10 100", "3 900000000000 10 100");
  const std::string path = write("huge_count.msh", text);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(path); }, path, line_of(text, "3 900000000000"),
                               "node count 900000000000 is larger than the file can hold"));
  std::string bin = hex_prism_22_binary(false);
  bin = replaced(bin, "$Elements\n2\n", "$Elements\n2000000000\n");
  const std::string p2 = write("huge_count_bin.msh", bin);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(p2); }, p2, line_of(bin, "2000000000"), "larger than the file can hold"));
}

TEST(ReadMsh, UnsupportedVolumeType) {
  const std::string text = replaced(kHexPrism41, "3 2 6 1\n7 20 90 30 60 100 70", "3 2 7 1\n7 20 90 30 60 100");
  const std::string path = write("pyramid.msh", text);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(path); }, path, line_of(text, "7 20 90"),
                               "element 7: Gmsh element type 7 (5-node pyramid) is not supported"));
  const std::string unknown = replaced(kHexPrism22, "7 6 2 0 2", "7 77 2 0 2");
  const std::string p2 = write("unknown_type.msh", unknown);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(p2); }, p2, line_of(unknown, "7 77"), "unknown Gmsh element type 77"));
}

TEST(ReadMsh, SecondOrderSurfaceIsRefused) {
  const std::string path = write("tri6.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
                                             "$EndNodes\n$Elements\n1\n5 9 0 1 2 3 1 2 3\n$EndElements\n");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(path); }, path, 12, "element 5: Gmsh element type 9 (6-node triangle) is not "
                                                                      "supported in a surface mesh"));
}

TEST(ReadMsh, MixedOrder) {
  std::string text = one_second_order(11, {Eigen::RowVector3d(0, 0, 0), Eigen::RowVector3d(1, 0, 0), Eigen::RowVector3d(0, 1, 0),
                                           Eigen::RowVector3d(0, 0, 1)},
                                      {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}});
  text = replaced(text, "1 1 1 1\n3 1 11 1\n1 1 2 3 4 5 6 7 8 9 10\n",
                  "2 2 1 2\n3 1 11 1\n1 1 2 3 4 5 6 7 8 9 10\n3 1 4 1\n2 1 2 3 5\n");
  const std::string path = write("mixed_order.msh", text);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(path); }, path, line_of(text, "2 1 2 3 5"),
                               "element 2: is first order, but element 1"));
}

TEST(ReadMsh, MissingEndMarkers) {
  const std::string a = replaced(kHexPrism41, "$EndNodes\n", "");
  const std::string pa = write("no_end_nodes.msh", a);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(pa); }, pa, line_of(a, "$Elements"), "expected $EndNodes, found '$Elements'"));
  const std::string b = replaced(kHexPrism41, "$EndNodeData\n", "");
  const std::string pb = write("no_end_node_data.msh", b);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(pb); }, pb, line_of(b, "$NodeData"), "section $NodeData has no $EndNodeData"));
  const std::string c = replaced(kHexPrism22, "$EndElements\n", "");
  const std::string pc = write("no_end_elements.msh", c);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(pc); }, pc, line_of(c, "7 6 2 0"), "file ends before $EndElements (truncated?)"));
}

TEST(ReadMsh, BinaryCheckIntMustBeOne) {
  const std::string path = write("check_int.msh", hex_prism_22_binary(false, 7));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(path); }, path, 3, "check int after the format line is 7, not 1"));
}

TEST(ReadMsh, ElementsBeforeNodesAndMissingSections) {
  const std::string a = write("no_elements.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n0\n$EndNodes\n");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(a); }, a, 0, "no $Elements section"));
  const std::string b = write("elements_first.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Elements\n0\n$EndElements\n");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(b); }, b, 4, "$Elements comes before $Nodes"));
  const std::string c = write("only_points.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n"
                                                 "$Elements\n1\n1 15 0 1\n$EndElements\n");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_msh(c); }, c, 8, "no volume or surface elements"));
}
