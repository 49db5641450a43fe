// A 128-bit hash of a sequence of words, for keying results kept in memory by everything that
// made them (two 64-bit splitmix64 chains from different seeds; the second sees each word
// complemented). Collisions are not detected: two different inputs share a key with probability
// about 2^-128 per pair.
#pragma once

#include <cstdint>
#include <cstring>

namespace hexdom {

struct Hash128 {
  uint64_t h[2] = {0x9e3779b97f4a7c15ull, 0xd1b54a32d192ed03ull};
  void add(uint64_t x) {
    for (uint64_t& k : h) {
      uint64_t z = (k ^ x) + 0x9e3779b97f4a7c15ull;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
      k = z ^ (z >> 31);
      x = ~x;
    }
  }
  /// The double's bits (so -0.0 and 0.0 differ, and every NaN pattern is its own).
  void add(double d) {
    uint64_t x;
    std::memcpy(&x, &d, sizeof x);
    add(x);
  }
  bool operator<(const Hash128& o) const { return h[0] != o.h[0] ? h[0] < o.h[0] : h[1] < o.h[1]; }
  bool operator==(const Hash128& o) const { return h[0] == o.h[0] && h[1] == o.h[1]; }
};

}  // namespace hexdom
