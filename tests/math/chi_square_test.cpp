// Checks of the test helpers themselves: incomplete gamma, p-values, pooling, quadrature.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/chi_square.h"
#include "common/quadrature.h"

namespace glint::test {
namespace {

TEST(ChiSquareHelper, PValueMatchesClosedForms) {
  // Two degrees of freedom: the survival function is exp(-x / 2).
  for (double x : {0.1, 1.0, 2.5, 7.0, 30.0}) EXPECT_NEAR(chiSquarePValue(x, 2), std::exp(-x / 2), 1e-12) << x;
  // One degree of freedom: erfc(sqrt(x / 2)).
  for (double x : {0.01, 0.5, 3.0, 10.0}) EXPECT_NEAR(chiSquarePValue(x, 1), std::erfc(std::sqrt(x / 2)), 1e-12) << x;
  // Four degrees of freedom: exp(-x / 2) (1 + x / 2).
  for (double x : {0.3, 4.0, 12.0}) EXPECT_NEAR(chiSquarePValue(x, 4), std::exp(-x / 2) * (1 + x / 2), 1e-12) << x;
}

TEST(ChiSquareHelper, PValueOfLargeDofIsNearNormalApproximation) {
  // For k dof the statistic has mean k and variance 2k; at the mean p is a little below 1/2.
  double p = chiSquarePValue(200, 200);
  EXPECT_GT(p, 0.45);
  EXPECT_LT(p, 0.5);
  // Three standard deviations above the mean is far in the tail.
  EXPECT_LT(chiSquarePValue(200 + 3 * 20, 200), 5e-3);
  EXPECT_DOUBLE_EQ(chiSquarePValue(0, 10), 1.0);
}

TEST(ChiSquareHelper, SidakCorrection) {
  EXPECT_NEAR(sidakSignificance(0.01, 1), 0.01, 1e-15);
  double perTest = sidakSignificance(0.01, 10);
  EXPECT_NEAR(1 - std::pow(1 - perTest, 10), 0.01, 1e-12);
}

TEST(ChiSquareHelper, PearsonPoolsSparseCellsAndRejectsImpossibleSamples) {
  std::vector<double> expected = {1000, 1000, 1000, 2, 2, 2};
  std::vector<double> observed = {1010, 990, 1003, 1, 3, 2};
  ChiSquareResult ok = pearsonChiSquare(observed, expected, 0.01);
  EXPECT_TRUE(ok.passed) << ok.message;
  EXPECT_EQ(ok.dof, 3);  // three full cells and one pool, minus one

  std::vector<double> biased = {1200, 900, 900, 2, 2, 2};
  EXPECT_FALSE(pearsonChiSquare(biased, expected, 0.01).passed);

  std::vector<double> impossible = {1000, 1000, 999, 1};
  std::vector<double> zeroExpected = {1000, 1000, 1000, 0};
  EXPECT_FALSE(pearsonChiSquare(impossible, zeroExpected, 0.01).passed);
}

TEST(Quadrature, IntegratesKnownFunctions) {
  EXPECT_NEAR(integrate1D([](double x) { return std::sin(x); }, 0, std::numbers::pi, 1e-10), 2.0, 1e-9);
  // A narrow peak (width 1e-3) found thanks to the forced initial refinement.
  auto peak = [](double x) { return 1e3 / std::numbers::pi / (1 + 1e6 * (x - 0.3) * (x - 0.3)); };
  double exact = (std::atan(700.0) + std::atan(1300.0)) / std::numbers::pi;
  EXPECT_NEAR(integrate1D(peak, -1, 1, 1e-10, 12), exact, 1e-8);
  auto bell = [](double x, double y) { return std::exp(-(x * x + y * y)); };
  double gaussian = integrateRect(bell, -6, 6, -6, 6, 1e-10, 4, 4);
  EXPECT_NEAR(gaussian, std::numbers::pi, 1e-8);
}

}  // namespace
}  // namespace glint::test
