#include "mrslam/robot/chi_square.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace mrslam::robot {
namespace {

TEST(ChiSquareTest, CdfMatchesClosedForms) {
  // dof 2: 1 − e^{−x/2}; dof 1: erf(√(x/2)).
  for (const double x : {0.1, 1.0, 3.0, 10.0, 40.0}) {
    EXPECT_NEAR(chiSquareCdf(x, 2), 1.0 - std::exp(-x / 2), 1e-12) << x;
    EXPECT_NEAR(chiSquareCdf(x, 1), std::erf(std::sqrt(x / 2)), 1e-12) << x;
  }
  EXPECT_EQ(chiSquareCdf(0.0, 3), 0.0);
}

TEST(ChiSquareTest, QuantilesMatchTables) {
  EXPECT_NEAR(chiSquareQuantile(0.95, 1), 3.8415, 1e-4);
  EXPECT_NEAR(chiSquareQuantile(0.95, 3), 7.8147, 1e-4);
  EXPECT_NEAR(chiSquareQuantile(0.999, 3), 16.2662, 1e-4);
  EXPECT_NEAR(chiSquareQuantile(0.025, 30), 16.7908, 1e-4);
  EXPECT_NEAR(chiSquareQuantile(0.975, 30), 46.9792, 1e-4);
  EXPECT_NEAR(chiSquareQuantile(0.975, 300), 349.874, 1e-2);
}

TEST(ChiSquareTest, BadArgumentsThrow) {
  EXPECT_THROW(chiSquareQuantile(1.0, 3), std::invalid_argument);
  EXPECT_THROW(chiSquareQuantile(0.0, 3), std::invalid_argument);
  EXPECT_THROW(chiSquareCdf(1.0, 0), std::invalid_argument);
}

}  // namespace
}  // namespace mrslam::robot
