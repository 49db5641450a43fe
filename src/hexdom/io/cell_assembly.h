// Cells read from a file, given in VTK's numbering (cell types and node order), made into a Mesh with
// the checks and messages every mesh reader shares: supported types, node counts, collapsed
// hexahedra, one order for the whole mesh, consistent mid-edge nodes.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hexdom/mesh/mesh.h"

namespace hexdom::io {

/// How well the name of a one-component cell array says it holds region ids, as the writers around
/// us name them: 0 "region", then "BlockId", "RegionId", "gmsh:physical", "medit:ref",
/// "CellEntityIds", "Part" (case-blind); 100 for any other name. Readers keep the best-ranked array.
int region_array_rank(const std::string& name);

class CellAssembly {
 public:
  /// `path` names the file in messages; `noun` the reader's word for a cell ("cell", "element").
  CellAssembly(std::string path, std::string noun) : path_(std::move(path)), noun_(std::move(noun)) {}

  /// Adds one cell: VTK type `vtk_type` (5, 9, 10, 12, 13, or second-order 24, 25, 26), `count`
  /// point indices in VTK order (already checked to be points of the file), a region id, the id the
  /// file gives the cell and the line it is on (for messages; `type_line`, when non-zero, is where
  /// the file gives its type, for the messages about the type and the order). An 8-node hexahedron with repeated
  /// nodes becomes a wedge or a tet (mesh::classify_hex_nodes). Throws InputError "path:line: <noun>
  /// <id>: ..." for an unsupported type, a wrong node count, an unreadable collapsed hexahedron, or
  /// a first-order cell in a second-order mesh (or the reverse).
  void add(int vtk_type, const int64_t* nodes, int count, int region, long id, long line, long type_line = 0);

  /// The mesh of the cells added, on `points` (#V x 3). A second-order mesh's mid-edge nodes are
  /// checked to be shared consistently (mesh::mid_edge_ends); an InputError names the file otherwise.
  mesh::Mesh finish(Eigen::MatrixXd points);

  long size() const { return static_cast<long>(builder_.types.size()); }

 private:
  [[noreturn]] void fail(long line, long id, const std::string& what) const;

  std::string path_, noun_;
  mesh::MeshBuilder builder_;
  std::vector<std::array<int, 12>> mids_;  // per cell of a second-order mesh: its mid-edge nodes
  long first_id_ = 0, first_line_ = 0;    // the first cell (which decides the order of the mesh)
  int order_ = 0;                         // 0 until a cell is added, then 1 or 2
};

}  // namespace hexdom::io
