// Mesh edges as 64-bit keys: the one encoding every stage's edge tables use.
#pragma once

#include <algorithm>
#include <cstdint>

namespace hexdom::mesh {

/// An edge between vertex ids a and b (both >= 0) packed as a << 32 | b. Keys sort by first vertex,
/// then second.
using EdgeKey = long long;

/// The edge from a to b: directed_edge(a, b) != directed_edge(b, a).
inline EdgeKey directed_edge(int a, int b) { return (static_cast<EdgeKey>(a) << 32) | static_cast<std::uint32_t>(b); }

/// The edge {a, b} whatever the order: directed_edge(min, max).
inline EdgeKey undirected_edge(int a, int b) { return directed_edge(std::min(a, b), std::max(a, b)); }

/// The vertices of a key, in the order it was made.
inline int edge_from(EdgeKey k) { return static_cast<int>(k >> 32); }
inline int edge_to(EdgeKey k) { return static_cast<int>(k & 0xffffffff); }

}  // namespace hexdom::mesh
