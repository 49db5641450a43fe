#include <cmath>
#include <limits>

#include "hexdom/quality/metrics.h"
#include "test_common.h"

using namespace hexdom;

TEST(IsInverted, OnlyPositiveFiniteValuesAreValid) {
  EXPECT_FALSE(quality::is_inverted(1.0));
  EXPECT_FALSE(quality::is_inverted(1e-12));
  EXPECT_TRUE(quality::is_inverted(0.0));
  EXPECT_TRUE(quality::is_inverted(-0.0));
  EXPECT_TRUE(quality::is_inverted(-0.5));
  EXPECT_TRUE(quality::is_inverted(1e30));  // Verdict's DBL_MAX: degenerate
  EXPECT_TRUE(quality::is_inverted(std::numeric_limits<double>::quiet_NaN()));
}
