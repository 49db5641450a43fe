// write_msh (declared in msh.h): MSH 4.1 ASCII with a physical group per region and per CAD face.
#include <algorithm>
#include <cstdio>
#include <map>
#include <ostream>
#include <vector>

#include "hexdom/io/gmsh_orders.h"
#include "hexdom/io/msh.h"
#include "hexdom/io/text.h"

namespace hexdom::io {

namespace {

using mesh::CellType;

// Gmsh's element type of a cell type (first or second order).
int gmsh_type_of(CellType t, bool second) {
  switch (t) {
    case CellType::Triangle: return 2;
    case CellType::Quad: return 3;
    case CellType::Tet: return second ? 11 : 4;
    case CellType::Hex: return second ? 17 : 5;
    case CellType::Wedge: return second ? 18 : 6;
  }
  return 0;
}

struct Block {
  int dim, entity, type;
  std::vector<std::vector<int>> elements;  // node indices (0-based), Gmsh order
};

// The bounding box of some nodes, "minx miny minz maxx maxy maxz".
std::string box_of(const mesh::Mesh& m, const std::vector<int>& nodes) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(0), hi = lo;
  bool first = true;
  for (int v : nodes) {
    const Eigen::Vector3d p = m.V.row(v).transpose();
    lo = first ? p : Eigen::Vector3d(lo.cwiseMin(p));
    hi = first ? p : Eigen::Vector3d(hi.cwiseMax(p));
    first = false;
  }
  char buf[200];
  std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g %.17g %.17g %.17g", lo(0), lo(1), lo(2), hi(0), hi(1), hi(2));
  return buf;
}

// The boundary faces of each tag as Gmsh surface elements (corners, then the mid-edge nodes of
// their edges for a second-order mesh).
std::map<int, Block> face_blocks(const mesh::Mesh& m, const FaceSets& sets) {
  std::map<int, Block> out;
  for (size_t i = 0; i < sets.faces.size() && i < sets.tag.size(); ++i) {
    if (sets.tag[i] < 1) continue;
    const mesh::BoundaryFace& f = sets.faces[i];
    std::vector<int> nodes = mesh::face_nodes(m, f);
    const int type = f.n == 3 ? (m.second_order() ? 9 : 2) : (m.second_order() ? 16 : 3);
    Block& b = out[sets.tag[i] * 100 + type];  // one block per tag and type
    b.dim = 2;
    b.entity = sets.tag[i];
    b.type = type;
    b.elements.push_back(std::move(nodes));
  }
  return out;
}

}  // namespace

void write_msh(const std::string& path, const mesh::Mesh& m, const FaceSets* sets) {
  const GmshNodeOrders orders;
  const bool second = m.second_order();
  bool volumes = false;
  for (int c = 0; c < m.num_cells(); ++c) volumes = volumes || mesh::is_volume(m.type(c));
  // Entities: one per region (volume, or surface for a mesh of 2D cells), numbered from 1.
  std::map<int, int> entity_of_region;
  for (int c = 0; c < m.num_cells(); ++c) entity_of_region.emplace(m.region(c), 0);
  // Entity and physical tag: the region id itself when every region is at least 1 (so that
  // read_msh gives the regions back), else the ids shifted to start at 1.
  const int shift = entity_of_region.empty() ? 0 : std::max(0, 1 - entity_of_region.begin()->first);
  for (auto& [r, e] : entity_of_region) e = r + shift;
  std::vector<Block> cells;  // in cell order: a new block where the entity or the type changes
  std::map<int, std::vector<int>> nodes_of_entity;
  int nodes[20], gmsh[20];
  for (int c = 0; c < m.num_cells(); ++c) {
    if (volumes && !mesh::is_volume(m.type(c))) continue;
    const int type = gmsh_type_of(m.type(c), second);
    const int n = mesh::cell_nodes(m, c, nodes);
    const int* order = orders.of(type);
    for (int i = 0; i < n; ++i) gmsh[order[i]] = nodes[i];
    const int entity = entity_of_region.at(m.region(c));
    if (cells.empty() || cells.back().entity != entity || cells.back().type != type)
      cells.push_back(Block{volumes ? 3 : 2, entity, type, {}});
    cells.back().elements.emplace_back(gmsh, gmsh + n);
    nodes_of_entity[entity].insert(nodes_of_entity[entity].end(), nodes, nodes + n);
  }
  const std::map<int, Block> faces = volumes && sets ? face_blocks(m, *sets) : std::map<int, Block>{};
  std::map<int, std::vector<int>> nodes_of_face;
  for (const auto& [key, b] : faces)
    for (const auto& e : b.elements) nodes_of_face[b.entity].insert(nodes_of_face[b.entity].end(), e.begin(), e.end());

  write_atomically(path, false, [&](std::ostream& out) {
    out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n"
        << entity_of_region.size() + nodes_of_face.size() << "\n";
    const int dim = volumes ? 3 : 2;
    for (const auto& [r, e] : entity_of_region) out << dim << " " << e << " \"Region" << r << "\"\n";
    for (const auto& [k, v] : nodes_of_face) out << "2 " << k << " \"Face" << k << "\"\n";
    out << "$EndPhysicalNames\n$Entities\n0 0 " << (volumes ? nodes_of_face.size() : entity_of_region.size()) << " "
        << (volumes ? entity_of_region.size() : 0) << "\n";
    // Surfaces first (Gmsh lists entities by dimension), then volumes; bounding entities none.
    if (volumes) {
      for (const auto& [k, v] : nodes_of_face) out << k << " " << box_of(m, v) << " 1 " << k << " 0\n";
    }
    for (const auto& [r, e] : entity_of_region) out << e << " " << box_of(m, nodes_of_entity[e]) << " 1 " << e << " 0\n";
    const int first_entity = entity_of_region.empty() ? 1 : entity_of_region.begin()->second;
    out << "$EndEntities\n$Nodes\n1 " << m.num_nodes() << " 1 " << m.num_nodes() << "\n"
        << dim << " " << first_entity << " 0 " << m.num_nodes() << "\n";
    for (int i = 0; i < m.num_nodes(); ++i) out << i + 1 << "\n";
    char buf[128];
    for (int i = 0; i < m.num_nodes(); ++i) {
      std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g\n", m.V(i, 0), m.V(i, 1), m.V(i, 2));
      out << buf;
    }
    size_t total = 0;
    for (const Block& b : cells) total += b.elements.size();
    for (const auto& [key, b] : faces) total += b.elements.size();
    out << "$EndNodes\n$Elements\n" << cells.size() + faces.size() << " " << total << " 1 " << total << "\n";
    size_t tag = 1;
    auto write_block = [&](const Block& b) {
      out << b.dim << " " << b.entity << " " << b.type << " " << b.elements.size() << "\n";
      for (const auto& e : b.elements) {
        out << tag++;
        for (int v : e) out << " " << v + 1;
        out << "\n";
      }
    };
    for (const Block& b : cells) write_block(b);
    for (const auto& [key, b] : faces) write_block(b);
    out << "$EndElements\n";
  });
}

}  // namespace hexdom::io
