#include "hexdom/io/inp.h"

#include <cstdio>
#include <map>
#include <ostream>
#include <vector>

#include "hexdom/io/text.h"

namespace hexdom::io {

using mesh::CellType;

void write_inp(const std::string& path, const mesh::Mesh& m) {
  write_atomically(path, false, [&](std::ostream& out) {
    char buf[256];
    out << "*HEADING\nHexDom mesh (" << m.count(CellType::Hex) << " hex, "
        << m.count(CellType::Wedge) << " prism, " << m.count(CellType::Tet) << " tet)\n*NODE\n";
    for (int i = 0; i < m.num_nodes(); ++i) {
      std::snprintf(buf, sizeof buf, "%d, %.17g, %.17g, %.17g\n", i + 1, m.V(i, 0), m.V(i, 1), m.V(i, 2));
      out << buf;
    }
    struct Block { CellType type; const char* name; std::vector<int> order; };
    // Second order: the VTK node lists (corners, then mid-edge nodes in cell_edges order); C3D20
    // and C3D10 number theirs the same way, C3D15 follows its reversed corners.
    const std::vector<Block> blocks =
        m.second_order()
            ? std::vector<Block>{{CellType::Hex, "C3D20", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19}},
                                 {CellType::Wedge, "C3D15", {0, 2, 1, 3, 5, 4, 8, 7, 6, 11, 10, 9, 12, 14, 13}},
                                 {CellType::Tet, "C3D10", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}}}
            : std::vector<Block>{{CellType::Hex, "C3D8", {0, 1, 2, 3, 4, 5, 6, 7}},
                                 {CellType::Wedge, "C3D6", {0, 2, 1, 3, 5, 4}},
                                 {CellType::Tet, "C3D4", {0, 1, 2, 3}},
                                 {CellType::Quad, "S4", {0, 1, 2, 3}},
                                 {CellType::Triangle, "S3", {0, 1, 2}}};
    int nodes[20];
    std::map<int, std::vector<int>> regions;
    std::vector<int> volume;
    for (const Block& b : blocks) {
      if (m.count(b.type) == 0) continue;
      out << "*ELEMENT, TYPE=" << b.name << "\n";
      for (int c = 0; c < m.num_cells(); ++c) {
        if (m.type(c) != b.type) continue;
        mesh::cell_nodes(m, c, nodes);
        out << c + 1;
        for (size_t j = 0; j < b.order.size(); ++j)  // Abaqus: at most 16 entries on a data line
          out << (j == 15 ? ",\n" : ", ") << nodes[b.order[j]] + 1;
        out << '\n';
        regions[m.region(c)].push_back(c + 1);
        if (mesh::is_volume(b.type)) volume.push_back(c + 1);
      }
    }
    auto write_set = [&](const std::string& name, const std::vector<int>& ids) {
      out << "*ELSET, ELSET=" << name << "\n";
      for (size_t i = 0; i < ids.size(); ++i)
        out << ids[i] << ((i + 1) % 16 == 0 || i + 1 == ids.size() ? "\n" : ", ");
    };
    for (const auto& [r, ids] : regions) write_set("REGION_" + std::to_string(r), ids);
    if (!volume.empty()) write_set("EALL", volume);
  });
}

}  // namespace hexdom::io
