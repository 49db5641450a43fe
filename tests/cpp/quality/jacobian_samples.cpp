#include <algorithm>
#include <cmath>
#include <random>

#include "hexdom/quality/jacobian_samples.h"
#include "hexdom/quality/metrics.h"
#include "test_common.h"

using namespace hexdom;
using mesh::CellType;

namespace {

struct Samples {
  int n = 0;
  double s[quality::kMaxJacobianSamples];
  double min() const { return *std::min_element(s, s + n); }
};

Samples samples_of(CellType t, const quality::CellPoints& P) {
  double p[8][3];
  for (int i = 0; i < mesh::node_count(t); ++i)
    for (int d = 0; d < 3; ++d) p[i][d] = P(i, d);
  Samples S;
  S.n = quality::jacobian_samples(t, p, S.s);
  return S;
}

bool at_most(CellType t, const quality::CellPoints& P, double threshold) {
  double p[8][3];
  for (int i = 0; i < mesh::node_count(t); ++i)
    for (int d = 0; d < 3; ++d) p[i][d] = P(i, d);
  return quality::some_jacobian_sample_at_most(t, p, threshold);
}

quality::CellPoints ideal(CellType t) {
  return t == CellType::Hex ? test::unit_hex() : t == CellType::Wedge ? test::unit_wedge() : test::unit_tet();
}

// The ideal cell with every corner moved by up to `amount` in each coordinate: valid, poor and
// inverted cells for the larger amounts.
quality::CellPoints perturbed(CellType t, double amount, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-amount, amount);
  quality::CellPoints P = ideal(t);
  for (int i = 0; i < mesh::node_count(t); ++i)
    for (int d = 0; d < 3; ++d) P(i, d) += u(rng);
  return P;
}

const CellType kTypes[3] = {CellType::Hex, CellType::Wedge, CellType::Tet};

}  // namespace

TEST(JacobianSamples, CountsAndIdealCells) {
  EXPECT_EQ(samples_of(CellType::Hex, test::unit_hex()).n, 9);
  EXPECT_EQ(samples_of(CellType::Wedge, test::unit_wedge()).n, 6);
  EXPECT_EQ(samples_of(CellType::Tet, test::unit_tet()).n, 4);
  for (CellType t : kTypes) EXPECT_NEAR(samples_of(t, ideal(t)).min(), quality::scaled_jacobian(t, ideal(t)), 1e-15);
}

// The minimum of the samples is Verdict's scaled Jacobian (quality::scaled_jacobian) for hexes and
// wedges, valid or inverted, and for valid tets; for inverted tets it is at most it.
TEST(JacobianSamples, MinimumIsTheScaledJacobianOfRandomCells) {
  std::mt19937 rng(7);
  int inverted[3] = {0, 0, 0}, valid[3] = {0, 0, 0};
  for (int ti = 0; ti < 3; ++ti) {
    const CellType t = kTypes[ti];
    for (double amount : {0.05, 0.2, 0.4, 0.8, 2.0})
      for (int r = 0; r < 400; ++r) {
        const quality::CellPoints P = perturbed(t, amount, rng);
        const double sj = quality::scaled_jacobian(t, P), m = samples_of(t, P).min();
        if (sj > 0) ++valid[ti];
        else ++inverted[ti];
        if (t != CellType::Tet || sj > 0) {
          EXPECT_NEAR(m, sj, 1e-12) << mesh::type_name(t) << " amount " << amount << " run " << r;
        } else {
          EXPECT_LE(m, sj + 1e-12) << "tet amount " << amount << " run " << r;
          EXPECT_LE(m, 0.0);
        }
        // "Some sample at most t" is "min <= t" (away from rounding at the threshold).
        for (double th : {0.0, 0.2, 0.5, 0.9}) {
          if (std::fabs(m - th) > 1e-9) {
            EXPECT_EQ(at_most(t, P, th), m <= th) << mesh::type_name(t) << " " << th;
          }
        }
      }
  }
  for (int ti = 0; ti < 3; ++ti) {  // not vacuous: both kinds of cells were drawn
    EXPECT_GT(valid[ti], 100);
    EXPECT_GT(inverted[ti], 100);
  }
}

// Degenerate cells: a zero-length edge gives a sample of -1 (scaled_jacobian: DBL_MAX), both read
// as inverted; a flattened cell has a zero minimum, as scaled_jacobian says.
TEST(JacobianSamples, DegenerateCellsAreInverted) {
  const int hex_edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  const int wedge_edges[9][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}};
  const int tet_edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  auto check = [](CellType t, const int (*edges)[2], int ne) {
    for (int e = 0; e < ne; ++e) {
      quality::CellPoints P = ideal(t);
      P.row(edges[e][1]) = P.row(edges[e][0]);
      const double sj = quality::scaled_jacobian(t, P), m = samples_of(t, P).min();
      EXPECT_TRUE(quality::is_inverted(sj)) << mesh::type_name(t) << " edge " << e;
      EXPECT_LE(m, 0.0) << mesh::type_name(t) << " edge " << e;
      EXPECT_TRUE(at_most(t, P, 0.0));
      if (t != CellType::Tet) {
        EXPECT_EQ(m, -1.0);
      }
    }
  };
  check(CellType::Hex, hex_edges, 12);
  check(CellType::Wedge, wedge_edges, 9);
  check(CellType::Tet, tet_edges, 6);
  // Flattened onto z = 0 (sheared first, so that no edge collapses): every sample is zero.
  for (CellType t : kTypes) {
    quality::CellPoints P = ideal(t);
    P.col(0) += 0.5 * P.col(2);
    P.col(2).setZero();
    const double sj = quality::scaled_jacobian(t, P), m = samples_of(t, P).min();
    EXPECT_NEAR(m, 0.0, 1e-15) << mesh::type_name(t);
    EXPECT_NEAR(sj, 0.0, 1e-15) << mesh::type_name(t);
    EXPECT_TRUE(at_most(t, P, 0.0));
  }
}

// Moving local node lv changes exactly the samples jacobian_samples_of_node names (and only them).
TEST(JacobianSamples, SamplesOfANodeAreTheOnesItMoves) {
  std::mt19937 rng(11);
  for (CellType t : kTypes)
    for (int lv = 0; lv < mesh::node_count(t); ++lv) {
      const unsigned mask = quality::jacobian_samples_of_node(t, lv);
      for (int r = 0; r < 20; ++r) {
        const quality::CellPoints P = perturbed(t, 0.2, rng);
        quality::CellPoints Q = P;
        Q.row(lv) += Eigen::RowVector3d(0.1, -0.07, 0.05);
        const Samples a = samples_of(t, P), b = samples_of(t, Q);
        for (int k = 0; k < a.n; ++k) {
          if (mask >> k & 1u) {
            EXPECT_NE(a.s[k], b.s[k]) << mesh::type_name(t) << " node " << lv << " sample " << k;
          } else {
            EXPECT_EQ(a.s[k], b.s[k]) << mesh::type_name(t) << " node " << lv << " sample " << k;
          }
        }
      }
    }
  EXPECT_EQ(quality::jacobian_samples_of_node(CellType::Hex, 0), (1u << 0) | (1u << 1) | (1u << 3) | (1u << 4) | (1u << 8));
}

// The corner neighbours are the cell's edges: each corner's three neighbours are joined to it by
// an edge, and a valid cell's corner determinant is positive in that order.
TEST(JacobianSamples, CornerNeighboursAreEdgesInPositiveOrder) {
  for (CellType t : kTypes) {
    const quality::CellPoints P = ideal(t);
    const int (*E)[3] = quality::corner_neighbours(t);
    for (int k = 0; k < mesh::node_count(t); ++k) {
      Eigen::Matrix3d J;
      for (int q = 0; q < 3; ++q) J.col(q) = (P.row(E[k][q]) - P.row(k)).transpose();
      EXPECT_GT(J.determinant(), 0) << mesh::type_name(t) << " corner " << k;
    }
  }
}
