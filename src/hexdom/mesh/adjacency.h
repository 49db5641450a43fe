// Which cells hold each node of a mesh.
#pragma once

#include <vector>

#include "hexdom/mesh/mesh.h"

namespace hexdom::mesh {

/// Node -> cell lists of a mesh in one array: the cells holding node v are
/// cells[start[v]] .. cells[start[v + 1] - 1], in increasing order, each once per time the cell
/// lists v (once for a valid cell). start has num_nodes() + 1 entries.
struct NodeCells {
  std::vector<int> start, cells;
  int begin(int v) const { return start[v]; }
  int end(int v) const { return start[v + 1]; }

  /// The cells of one node, as a range (for loops, size, indexing).
  struct Range {
    const int *first, *last;
    const int* begin() const { return first; }
    const int* end() const { return last; }
    size_t size() const { return static_cast<size_t>(last - first); }
    bool empty() const { return first == last; }
    int operator[](size_t i) const { return first[i]; }
  };
  Range operator[](int v) const { return {cells.data() + start[v], cells.data() + start[v + 1]}; }
};

/// The node -> cell lists of every cell of `mesh` (any cell type; its first node_count(type) slots).
NodeCells node_cells(const Mesh& mesh);

}  // namespace hexdom::mesh
