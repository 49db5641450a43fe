// Internal to generation: the lattice of a subdivided block. A block of type hex, wedge or tet with
// n cells per edge holds the lattice points (i, j, k), 0 <= i, j, k <= n (wedge: i + j <= n; tet:
// i + j + k <= n); its local vertex v sits at n x corner_table(type)[v]. Local faces are
// mesh::cell_faces's, outward.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "hexdom/mesh/mesh.h"

namespace hexdom::generation {

/// Lattice coordinates (0 or 1) of each local vertex of a hex, wedge and tet block.
inline constexpr int kHexCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                         {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
inline constexpr int kWedgeCorner[6][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
inline constexpr int kTetCorner[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
/// The table above for a block type.
const int (*corner_table(mesh::CellType type))[3];

/// Lattice neighbour offsets for the harmonic fill of a triangle face, a wedge and a tet block.
inline constexpr int kTriNb[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {1, -1, 0}, {-1, 1, 0}};
inline constexpr int kWedgeNb[8][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0},
                                       {1, -1, 0}, {-1, 1, 0}, {0, 0, 1}, {0, 0, -1}};
inline constexpr int kTetNb[12][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1},
                                      {1, -1, 0}, {-1, 1, 0}, {1, 0, -1}, {-1, 0, 1}, {0, 1, -1}, {0, -1, 1}};

/// Is lattice point (i, j, k) inside the lattice of a block of type t with n cells per edge?
bool in_lattice(mesh::CellType t, int n, int i, int j, int k);
/// Is it on the block's boundary?
bool on_block_boundary(mesh::CellType t, int n, int i, int j, int k);
/// Integer interpolation weights of lattice point (i, j, k) on the block's local vertices, written
/// to w (one per local vertex; returns their number), scaled so that they sum to n^3 for every
/// block type: a point on a shared face or edge gets the same weights from every block holding it.
int weights(mesh::CellType t, int n, int i, int j, int k, int* w);

/// Index of lattice point (i, j, k) in a block's (n + 1)^3 array, n1 = n + 1.
inline int lattice_index(int n1, int i, int j, int k) { return (k * n1 + j) * n1 + i; }

/// A lattice point on block boundaries, identified by its non-zero weights on structure vertices:
/// up to four (vertex << 32 | weight) in increasing order, -1 after them.
using Key = std::array<long long, 4>;

/// Open-addressing table from keys to node ids (linear probing; sized once for the most keys a run
/// can insert, so it never rehashes): a std::unordered_map allocates a node per key.
class KeyTable {
 public:
  explicit KeyTable(size_t max_keys);
  /// The id of `k`, inserting it with id `fresh` when absent; `inserted` says which.
  int find_or_insert(const Key& k, int fresh, bool& inserted);

 private:
  std::vector<Key> keys_;
  std::vector<int> ids_;
  size_t mask_ = 0;
};

}  // namespace hexdom::generation
