// Disjoint sets of the integers 0..n-1 (union-find with path halving).
#pragma once

#include <numeric>
#include <vector>

namespace hexdom {

/// Starts with every element in a set of its own. find(x) is the same for two elements exactly
/// when a chain of unite() calls joins them.
class DisjointSets {
 public:
  explicit DisjointSets(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int size() const { return static_cast<int>(parent_.size()); }
  /// The representative of x's set.
  int find(int x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  /// Joins the sets of x and y; y's representative becomes the joined set's. Returns whether they
  /// were apart.
  bool unite(int x, int y) {
    x = find(x), y = find(y);
    if (x == y) return false;
    parent_[x] = y;
    return true;
  }

 private:
  std::vector<int> parent_;
};

}  // namespace hexdom
