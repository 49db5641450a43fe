#include "hexdom/generation/block_lattice.h"

namespace hexdom::generation {

using mesh::CellType;

const int (*corner_table(CellType t))[3] {
  if (t == CellType::Hex) return kHexCorner;
  if (t == CellType::Wedge) return kWedgeCorner;
  return kTetCorner;
}

bool in_lattice(CellType t, int n, int i, int j, int k) {
  if (i < 0 || j < 0 || k < 0 || i > n || j > n || k > n) return false;
  if (t == CellType::Wedge) return i + j <= n;
  if (t == CellType::Tet) return i + j + k <= n;
  return true;
}

bool on_block_boundary(CellType t, int n, int i, int j, int k) {
  if (t == CellType::Hex) return i == 0 || j == 0 || k == 0 || i == n || j == n || k == n;
  if (t == CellType::Wedge) return i == 0 || j == 0 || k == 0 || k == n || i + j == n;
  return i == 0 || j == 0 || k == 0 || i + j + k == n;
}

int weights(CellType t, int n, int i, int j, int k, int* w) {
  if (t == CellType::Hex) {
    for (int v = 0; v < 8; ++v)
      w[v] = (kHexCorner[v][0] ? i : n - i) * (kHexCorner[v][1] ? j : n - j) * (kHexCorner[v][2] ? k : n - k);
    return 8;
  }
  if (t == CellType::Wedge) {
    int bary[3] = {n - i - j, i, j};
    for (int v = 0; v < 3; ++v) {
      w[v] = bary[v] * (n - k) * n;
      w[v + 3] = bary[v] * k * n;
    }
    return 6;
  }
  int bary[4] = {n - i - j - k, i, j, k};
  for (int v = 0; v < 4; ++v) w[v] = bary[v] * n * n;
  return 4;
}

KeyTable::KeyTable(size_t max_keys) {
  size_t cap = 16;
  while (cap < 2 * max_keys) cap *= 2;
  keys_.resize(cap);
  ids_.assign(cap, -1);
  mask_ = cap - 1;
}

int KeyTable::find_or_insert(const Key& k, int fresh, bool& inserted) {
  uint64_t h = 0x9e3779b97f4a7c15ull;
  for (long long x : k) {
    h ^= static_cast<uint64_t>(x);
    h *= 0xbf58476d1ce4e5b9ull;
    h ^= h >> 31;
  }
  for (size_t i = h & mask_;; i = (i + 1) & mask_) {
    if (ids_[i] < 0) {
      keys_[i] = k;
      ids_[i] = fresh;
      inserted = true;
      return fresh;
    }
    if (keys_[i] == k) {
      inserted = false;
      return ids_[i];
    }
  }
}

}  // namespace hexdom::generation
