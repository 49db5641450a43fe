#include <cstdint>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>

#include "hexdom/io/vtk.h"
#include "io_test_util.h"

using namespace hexdom;

namespace {

std::string decode_base64(const std::string& s) {
  auto val = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    return c == '+' ? 62 : c == '/' ? 63 : -1;
  };
  std::string out;
  uint32_t buf = 0;  // only its low bits matter: unsigned, so the shift may drop the high ones
  int bits = 0;
  for (char c : s) {
    int v = val(c);
    if (v < 0) continue;
    buf = (buf << 6) | static_cast<uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((buf >> bits) & 0xff);
    }
  }
  return out;
}

// Values of the DataArray called `name` (UInt64 byte-count header, then little-endian data).
template <class T>
std::vector<T> array(const std::string& xml, const std::string& name) {
  std::smatch m;
  if (!std::regex_search(xml, m, std::regex("Name=\"" + name + "\"[^>]*>\\s*([A-Za-z0-9+/=]+)\\s*<"))) return {};
  const std::string bytes = decode_base64(m[1].str());
  uint64_t n = 0;
  std::memcpy(&n, bytes.data(), 8);
  std::vector<T> v(n / sizeof(T));
  std::memcpy(v.data(), bytes.data() + 8, n);
  return v;
}

}  // namespace

TEST(WriteVtu, ArraysDecodeToTheMesh) {
  const mesh::Mesh m = test::mixed_mesh();
  const std::string path = test::temp_path("mesh.vtu");
  io::write_vtu(path, m);
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string xml = ss.str();
  EXPECT_NE(xml.find("NumberOfPoints=\"16\" NumberOfCells=\"6\""), std::string::npos);
  auto pts = array<double>(xml, "Points");
  ASSERT_EQ(pts.size(), 48u);
  for (int i = 0; i < 16; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(pts[3 * i + k], m.V(i, k));
  auto conn = array<int64_t>(xml, "connectivity");
  auto offsets = array<int64_t>(xml, "offsets");
  auto types = array<uint8_t>(xml, "types");
  auto region = array<int32_t>(xml, "region");
  ASSERT_EQ(offsets.size(), 6u);
  ASSERT_EQ(types.size(), 6u);
  ASSERT_EQ(region.size(), 6u);
  int64_t start = 0;
  for (int c = 0; c < 6; ++c) {
    EXPECT_EQ(types[c], m.types(c));
    EXPECT_EQ(region[c], m.region(c));
    ASSERT_EQ(offsets[c] - start, mesh::node_count(m.type(c)));
    for (int j = 0; j < offsets[c] - start; ++j) EXPECT_EQ(conn[start + j], m.cells(c, j));
    start = offsets[c];
  }
  EXPECT_EQ(start, static_cast<int64_t>(conn.size()));
}
