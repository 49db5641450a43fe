#include "hexdom/io/cell_assembly.h"

#include <algorithm>
#include <stdexcept>

#include "hexdom/common/error.h"
#include "hexdom/io/text.h"
#include "hexdom/mesh/second_order.h"

namespace hexdom::io {

using mesh::CellType;

int region_array_rank(const std::string& name) {
  static const char* const names[] = {"region", "blockid", "regionid", "gmsh:physical", "medit:ref",
                                      "cellentityids", "part"};
  const std::string n = lower(name);
  for (int i = 0; i < 7; ++i)
    if (n == names[i]) return i;
  return 100;
}

void CellAssembly::fail(long line, long id, const std::string& what) const {
  throw InputError(path_, line, noun_ + " " + std::to_string(id) + ": " + what);
}

void CellAssembly::add(int vtk_type, const int64_t* nodes, int count, int region, long id, long line,
                       long type_line) {
  if (type_line == 0) type_line = line;
  const bool second = vtk_type == 24 || vtk_type == 25 || vtk_type == 26;
  CellType t;
  try {
    t = second ? mesh::first_order_of_vtk(vtk_type) : mesh::cell_type_from_vtk(vtk_type);
  } catch (const std::invalid_argument&) {
    fail(type_line, id, "unsupported VTK cell type " + std::to_string(vtk_type) +
                       " (supported: 5 triangle, 9 quad, 10 tet, 12 hex, 13 wedge, 24 tet10, 25 hex20, 26 wedge15)");
  }
  const int expected = mesh::node_count(t) + (second ? mesh::edge_count(t) : 0);
  if (count != expected)
    fail(line, id, "has " + std::to_string(count) + " nodes, expected " + std::to_string(expected) + " for VTK type " +
                       std::to_string(vtk_type));
  const int order = second ? 2 : 1;
  if (order_ == 0) {
    order_ = order;
    first_id_ = id;
    first_line_ = type_line;
  } else if (order != order_) {
    fail(type_line, id, std::string("is ") + (second ? "second" : "first") + " order, but " + noun_ + " " +
                       std::to_string(first_id_) + " (line " + std::to_string(first_line_) + ") is " +
                       (second ? "first" : "second") + " order: a mesh of mixed order is not supported");
  }
  int n[20];
  for (int j = 0; j < count; ++j) n[j] = static_cast<int>(nodes[j]);
  if (second) {
    mids_.emplace_back();
    mids_.back().fill(-1);
    std::copy(n + mesh::node_count(t), n + count, mids_.back().begin());
    builder_.add(t, n, region);
  } else if (t == CellType::Hex) {
    std::array<int, 8> h;
    std::copy(n, n + 8, h.begin());
    try {
      const mesh::DegenerateHex d = mesh::classify_hex_nodes(h);
      builder_.add(d.type, d.nodes.data(), region);
    } catch (const std::invalid_argument& e) {
      fail(line, id, e.what());
    }
  } else {
    builder_.add(t, n, region);
  }
}

mesh::Mesh CellAssembly::finish(Eigen::MatrixXd points) {
  mesh::Mesh m = builder_.finish(std::move(points));
  if (order_ == 2) {
    m.mid.resize(static_cast<Eigen::Index>(mids_.size()), 12);
    for (size_t c = 0; c < mids_.size(); ++c)
      for (int e = 0; e < 12; ++e) m.mid(static_cast<Eigen::Index>(c), e) = mids_[c][e];
    try {
      mesh::mid_edge_ends(m);
    } catch (const GeometryError& e) {
      throw InputError(path_, 0, e.what());
    }
  }
  return m;
}

}  // namespace hexdom::io
