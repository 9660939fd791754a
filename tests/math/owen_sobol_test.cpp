// Tests of the stratified sampler: the (0,2)-sequence's net property survives scrambling and
// shuffling, single samples are uniform across streams (chi-square), streams differ, and the
// dimensions of one stream pair their samples without correlation.
#include "math/owen_sobol.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "common/chi_square.h"

namespace glint {
namespace {

constexpr int kChiSquareTests = 3;
const double kSignificance = test::sidakSignificance(0.01, kChiSquareTests);

// True when the points put exactly one point in every 2^a x 2^b cell, a + b = log2(count).
bool isNet(const std::vector<Vec2f>& points) {
  int m = 0;
  while ((size_t(1) << m) < points.size()) ++m;
  if ((size_t(1) << m) != points.size()) return false;
  for (int a = 0; a <= m; ++a) {
    const int columns = 1 << a, rows = 1 << (m - a);
    std::vector<int> count(size_t(columns) * rows, 0);
    for (const Vec2f& p : points) {
      int cx = std::min(int(p.x * columns), columns - 1), cy = std::min(int(p.y * rows), rows - 1);
      if (++count[size_t(cy) * columns + cx] > 1) return false;
    }
  }
  return true;
}

TEST(OwenSobol, ReverseBitsAndSobolDimensionsAreCorrect) {
  EXPECT_EQ(reverseBits32(1u), 0x80000000u);
  EXPECT_EQ(reverseBits32(0x00000006u), 0x60000000u);
  EXPECT_EQ(reverseBits32(reverseBits32(0x12345678u)), 0x12345678u);
  // Sobol's second dimension in index order (not Gray-code order): direction numbers 1/2,
  // 3/4, 5/8, so index 5 = 101b gives 5/8 xor 1/2 = 1/8.
  const double expected[] = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
  for (uint32_t i = 0; i < 8; ++i) EXPECT_DOUBLE_EQ(sobolDimension1(i) * 0x1p-32, expected[i]) << i;
  EXPECT_DOUBLE_EQ(sobolDimension0(3) * 0x1p-32, 0.75);
}

TEST(OwenSobol, ScramblingIsABijectionThatKeepsTheLeadingBitsOrder) {
  // Each bit depends only on the bits above it: values sharing their top k bits keep
  // sharing them after scrambling, and no two values collide.
  std::set<uint32_t> seen;
  for (uint32_t i = 0; i < 4096; ++i) {
    uint32_t x = i << 20;
    seen.insert(owenScramble(x, 0x9e3779b9u));
    EXPECT_EQ(owenScramble(x, 77u) >> 20, owenScramble(x | 0x000fffffu, 77u) >> 20) << i;
  }
  EXPECT_EQ(seen.size(), 4096u);
}

TEST(OwenSobol, EveryPowerOfTwoBlockOfAStreamIsANet) {
  for (uint64_t key : {hashKeys({0, 1, 2, 1}), hashKeys({5, 0, 77, 3}), uint64_t(0)})
    for (int count : {1, 2, 4, 16, 64, 256, 1024}) {
      for (uint32_t first : {0u, uint32_t(count), uint32_t(3 * count)}) {
        std::vector<Vec2f> points;
        for (int i = 0; i < count; ++i) points.push_back(stratifiedSample2(key, first + uint32_t(i)));
        EXPECT_TRUE(isNet(points)) << "key " << key << " count " << count << " first " << first;
      }
    }
}

TEST(OwenSobol, PointsAreInTheUnitSquare) {
  for (uint32_t i = 0; i < 10000; ++i) {
    Vec2f p = stratifiedSample2(hashKeys({1, i}), i);
    ASSERT_GE(p.x, 0.0f);
    ASSERT_LT(p.x, 1.0f);
    ASSERT_GE(p.y, 0.0f);
    ASSERT_LT(p.y, 1.0f);
  }
}

// Any fixed sample index, taken across many streams (pixels), is uniform on the square: the
// scrambling makes each point uniformly random, so estimators stay unbiased.
TEST(OwenSobol, OneSampleAcrossStreamsIsUniform) {
  const int cells = 16;  // 16 x 16 grid
  for (uint32_t index : {0u, 5u}) {
    std::vector<double> observed(cells * cells, 0.0);
    const int streams = 51200;
    for (int s = 0; s < streams; ++s) {
      Vec2f p = stratifiedSample2(hashKeys({7, 3, uint64_t(s), 1}), index);
      observed[size_t(int(p.y * cells) * cells + int(p.x * cells))] += 1;
    }
    std::vector<double> expected(observed.size(), double(streams) / observed.size());
    test::ChiSquareResult r = test::pearsonChiSquare(observed, expected, kSignificance);
    EXPECT_TRUE(r.passed) << "index " << index << ": chi2 " << r.statistic << " p " << r.pValue;
  }
}

// Two dimensions of a path (two stream keys of one pixel) pair their samples independently:
// the joint distribution of (x of dimension 1, x of dimension 2) over a pixel's 1024 samples
// is uniform on an 8 x 8 grid. Unshuffled, the same index would pair strata in lock step.
TEST(OwenSobol, DimensionsOfOnePixelAreNotCorrelated) {
  const int cells = 8, count = 1024;
  std::vector<double> observed(cells * cells, 0.0);
  for (int i = 0; i < count; ++i) {
    Vec2f a = stratifiedSample2(hashKeys({0, 4, 99, 1}), uint32_t(i));
    Vec2f b = stratifiedSample2(hashKeys({0, 4, 99, 2}), uint32_t(i));
    observed[size_t(int(b.x * cells) * cells + int(a.x * cells))] += 1;
  }
  std::vector<double> expected(observed.size(), double(count) / observed.size());
  test::ChiSquareResult r = test::pearsonChiSquare(observed, expected, kSignificance);
  EXPECT_TRUE(r.passed) << "chi2 " << r.statistic << " p " << r.pValue;
}

// The point of stratification: the mean of a smooth integrand over a pixel's samples has
// a far smaller error than with independent samples (here 64 samples of x y, mean 1/4).
TEST(OwenSobol, IntegratesASmoothFunctionFarBetterThanIndependentSamples) {
  double stratifiedError = 0, independentError = 0;
  const int pixels = 200, count = 64;
  for (int p = 0; p < pixels; ++p) {
    Rng rng = Rng::forKeys({11, uint64_t(p)});
    double stratified = 0, independent = 0;
    for (int i = 0; i < count; ++i) {
      Vec2f s = stratifiedSample2(hashKeys({11, uint64_t(p), 1}), uint32_t(i));
      Vec2f u = rng.uniform2();
      stratified += double(s.x) * s.y;
      independent += double(u.x) * u.y;
    }
    stratifiedError += std::pow(stratified / count - 0.25, 2);
    independentError += std::pow(independent / count - 0.25, 2);
  }
  // Independent samples: variance 7/144 / 64 per pixel. Owen-scrambled nets converge as
  // n^-3 for smooth integrands, so 64 samples gain far more than 10x.
  EXPECT_LT(stratifiedError * 10, independentError);
}

}  // namespace
}  // namespace glint
