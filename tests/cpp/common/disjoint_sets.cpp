// DisjointSets against connected components found by a search over the same pairs.
#include <gtest/gtest.h>

#include <random>
#include <utility>
#include <vector>

#include "hexdom/common/disjoint_sets.h"

using namespace hexdom;

TEST(DisjointSets, TwoElementsShareARepresentativeExactlyWhenAChainOfPairsJoinsThem) {
  std::mt19937 rng(7);
  const int n = 200;
  for (int round = 0; round < 5; ++round) {
    DisjointSets sets(n);
    std::vector<std::vector<int>> adjacent(n);
    std::uniform_int_distribution<int> pick(0, n - 1);
    for (int k = 0; k < 120; ++k) {
      const int a = pick(rng), b = pick(rng);
      const bool apart = sets.find(a) != sets.find(b);
      EXPECT_EQ(sets.unite(a, b), apart);
      EXPECT_EQ(sets.find(a), sets.find(b));
      adjacent[a].push_back(b);
      adjacent[b].push_back(a);
    }
    // Components by a depth-first search.
    std::vector<int> component(n, -1);
    for (int s = 0; s < n; ++s) {
      if (component[s] >= 0) continue;
      std::vector<int> stack{s};
      component[s] = s;
      while (!stack.empty()) {
        const int v = stack.back();
        stack.pop_back();
        for (int u : adjacent[v])
          if (component[u] < 0) component[u] = s, stack.push_back(u);
      }
    }
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b) EXPECT_EQ(sets.find(a) == sets.find(b), component[a] == component[b]) << a << " " << b;
  }
}

// unite(x, y) makes y's representative the joined set's (the callers that kept their own
// union-find relied on it: the order of their sets' representatives is unchanged).
TEST(DisjointSets, TheSecondSetsRepresentativeRepresentsTheUnion) {
  DisjointSets sets(4);
  sets.unite(0, 1);
  EXPECT_EQ(sets.find(0), 1);
  sets.unite(2, 3);
  sets.unite(1, 3);
  for (int x = 0; x < 4; ++x) EXPECT_EQ(sets.find(x), 3);
  EXPECT_FALSE(sets.unite(0, 2));
  EXPECT_EQ(sets.size(), 4);
}
