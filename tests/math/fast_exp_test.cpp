// expNonPositive against the double-precision exponential over its whole domain.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "math/fast_exp.h"

namespace glint {
namespace {

// Distance in units in the last place between a float and the exact value.
double ulps(float got, double exact) {
  float rounded = float(exact);
  double ulp = double(std::nextafter(rounded, INFINITY)) - double(rounded);
  return std::abs(double(got) - exact) / ulp;
}

TEST(FastExp, WithinOneUlpOverTheDomainAndZeroBelowIt) {
  double worst = 0.0;
  int tested = 0;
  // A million evenly spaced points of [-87, 0], and the floats next to the reduction's
  // interval ends (n ln2 +- ln2 / 2), where the polynomial's error is largest.
  for (int k = 0; k <= 1000000; ++k) {
    float x = -87.0f * float(k) / 1e6f;
    worst = std::max(worst, ulps(expNonPositive(x), std::exp(double(x))));
    ++tested;
  }
  for (int n = -125; n <= 0; ++n) {
    float edge = float((n + 0.5) * std::log(2.0));
    for (float x : {std::nextafter(edge, -INFINITY), edge, std::nextafter(edge, INFINITY)}) {
      if (!(x <= 0.0f && x >= -87.0f)) continue;
      worst = std::max(worst, ulps(expNonPositive(x), std::exp(double(x))));
      ++tested;
    }
  }
  EXPECT_GT(tested, 100000);
  EXPECT_LE(worst, 1.0);  // measured 0.90
  EXPECT_EQ(expNonPositive(0.0f), 1.0f);
  EXPECT_EQ(expNonPositive(-0.0f), 1.0f);
  EXPECT_LE(ulps(expNonPositive(-87.0f), std::exp(-87.0)), 1.0);
  EXPECT_EQ(expNonPositive(-88.0f), 0.0f);
  EXPECT_EQ(expNonPositive(-INFINITY), 0.0f);
  EXPECT_EQ(expNonPositive(std::nanf("")), 0.0f);
}

#ifdef __AVX2__
TEST(FastExp, Avx2IsBitIdenticalToTheScalarOne) {
  std::vector<float> xs = {0.0f, -0.0f, -87.0f, -87.5f, -1e30f, -INFINITY, std::nanf("")};
  for (int k = 0; k <= 100000; ++k) xs.push_back(-90.0f * float(k) / 1e5f);
  while (xs.size() % 8) xs.push_back(-1.0f);
  for (size_t i = 0; i < xs.size(); i += 8) {
    alignas(32) float got[8];
    _mm256_store_ps(got, expNonPositiveAvx2(_mm256_loadu_ps(&xs[i])));
    for (int l = 0; l < 8; ++l) ASSERT_EQ(got[l], expNonPositive(xs[i + l])) << "x = " << xs[i + l];
  }
}
#endif

}  // namespace
}  // namespace glint
