// Tests of the deterministic random numbers: reproducible streams per key tuple, ranges,
// moments and chi-square uniformity of floats and integers, and order-sensitive hashing.
#include "math/rng.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "common/chi_square.h"

namespace glint {
namespace {

// Every chi-square test in this file shares one overall significance of 1% (Sidak).
constexpr int kRngChiSquareTests = 5;
const double kRngSignificance = test::sidakSignificance(0.01, kRngChiSquareTests);

std::vector<uint32_t> firstValues(Rng rng, int count) {
  std::vector<uint32_t> values(count);
  for (uint32_t& v : values) v = rng.nextUint();
  return values;
}

// Chi-square test that values fall uniformly into cells (each value is already a cell index).
test::ChiSquareResult uniformCells(const std::vector<uint32_t>& cells, uint32_t cellCount) {
  std::vector<double> observed(cellCount, 0.0);
  for (uint32_t c : cells) observed[c] += 1;
  std::vector<double> expected(cellCount, double(cells.size()) / cellCount);
  return test::pearsonChiSquare(observed, expected, kRngSignificance);
}

TEST(Rng, SameKeysGiveTheSameSequence) {
  EXPECT_EQ(firstValues(Rng::forKeys({7, 3, 12345, 2}), 1000), firstValues(Rng::forKeys({7, 3, 12345, 2}), 1000));
  EXPECT_EQ(firstValues(Rng(99, 5), 1000), firstValues(Rng(99, 5), 1000));
  EXPECT_EQ(firstValues(Rng(), 100), firstValues(Rng(0), 100));
}

TEST(Rng, DifferentKeysGiveDifferentSequences) {
  // Neighbouring pixels, samples and seeds, and permuted keys: all distinct streams.
  std::vector<std::vector<uint32_t>> streams = {
      firstValues(Rng::forKeys({7, 3, 12345, 2}), 8), firstValues(Rng::forKeys({7, 3, 12346, 2}), 8),
      firstValues(Rng::forKeys({7, 3, 12345, 3}), 8), firstValues(Rng::forKeys({8, 3, 12345, 2}), 8),
      firstValues(Rng::forKeys({3, 7, 12345, 2}), 8), firstValues(Rng::forKeys({7, 3, 12345}), 8),
      firstValues(Rng::forKeys({7, 3, 12345, 2, 0}), 8), firstValues(Rng(0), 8),
      firstValues(Rng(1), 8), firstValues(Rng(0, 1), 8)};
  std::set<std::vector<uint32_t>> distinct(streams.begin(), streams.end());
  EXPECT_EQ(distinct.size(), streams.size());
  // Not merely shifted copies of each other either: no value of one appears early in another.
  std::set<uint32_t> seen;
  for (const auto& s : streams) seen.insert(s.begin(), s.end());
  EXPECT_EQ(seen.size(), streams.size() * 8);
}

TEST(Rng, RestoreResumesTheSequence) {
  Rng a(42, 7);
  for (int i = 0; i < 10; ++i) a.nextUint();
  Rng b;
  b.restore(a.state(), a.increment());
  EXPECT_EQ(firstValues(a, 100), firstValues(b, 100));
}

TEST(Rng, HashKeysIsOrderAndLengthSensitive) {
  static_assert(hashKeys({1, 2}) != hashKeys({2, 1}), "usable at compile time");
  EXPECT_NE(hashKeys({1, 2, 3}), hashKeys({1, 3, 2}));
  EXPECT_NE(hashKeys({1, 2, 3}), hashKeys({3, 2, 1}));
  EXPECT_NE(hashKeys({0}), hashKeys({0, 0}));
  EXPECT_NE(hashKeys({}), hashKeys({0}));
  EXPECT_EQ(hashKeys({5, 6, 7}), hashKeys({5, 6, 7}));
  // Small key tuples (a 64 x 64 image, 4 samples) never collide.
  std::set<uint64_t> hashes;
  for (uint64_t x = 0; x < 64; ++x)
    for (uint64_t y = 0; y < 64; ++y)
      for (uint64_t s = 0; s < 4; ++s) hashes.insert(hashKeys({1, x, y, s}));
  EXPECT_EQ(hashes.size(), 64u * 64u * 4u);
}

TEST(Rng, UniformIsInTheHalfOpenUnitInterval) {
  Rng rng(31);
  float lowest = 1, highest = 0;
  for (int i = 0; i < 2000000; ++i) {
    float u = rng.uniform();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    lowest = std::min(lowest, u);
    highest = std::max(highest, u);
    double d = rng.uniformDouble();
    ASSERT_GE(d, 0.0);
    ASSERT_LT(d, 1.0);
  }
  // The range is actually used, up to within a few 2^-24 steps of the ends.
  EXPECT_LT(lowest, 1e-5f);
  EXPECT_GT(highest, 1.0f - 1e-5f);
  // The largest possible output, 24 set bits scaled by 2^-24, is still below 1 in float.
  EXPECT_LT(static_cast<float>(0xFFFFFFFFu >> 8) * 0x1p-24f, 1.0f);
}

TEST(Rng, MeanAndVarianceOfAMillionSamples) {
  constexpr int kCount = 1000000;
  for (bool useDouble : {false, true}) {
    Rng rng(32);
    double sum = 0, sumSquares = 0;
    for (int i = 0; i < kCount; ++i) {
      double u = useDouble ? rng.uniformDouble() : rng.uniform();
      sum += u;
      sumSquares += u * u;
    }
    double mean = sum / kCount;
    double variance = sumSquares / kCount - mean * mean;
    // Uniform on [0, 1): mean 1/2 with standard error sqrt(1/12 / n); variance 1/12 with
    // standard error sqrt((1/80 - 1/144) / n) (fourth central moment 1/80). Five sigma each.
    EXPECT_NEAR(mean, 0.5, 5 * std::sqrt(1.0 / 12 / kCount)) << (useDouble ? "double" : "float");
    EXPECT_NEAR(variance, 1.0 / 12, 5 * std::sqrt((1.0 / 80 - 1.0 / 144) / kCount)) << (useDouble ? "double" : "float");
  }
}

TEST(Rng, UniformChiSquareOver100Bins) {
  Rng rng(33);
  std::vector<uint32_t> cells(500000);
  for (uint32_t& c : cells) c = uint32_t(rng.uniform() * 100);
  auto result = uniformCells(cells, 100);
  EXPECT_TRUE(result.passed) << result.message;
}

TEST(Rng, SuccessivePairsAreIndependent) {
  // Consecutive outputs as points in a 10 x 10 grid: a correlated generator clusters.
  Rng rng(34);
  std::vector<uint32_t> cells(500000);
  for (uint32_t& c : cells) {
    Vec2f u = rng.uniform2();
    c = uint32_t(u.x * 10) * 10 + uint32_t(u.y * 10);
  }
  auto result = uniformCells(cells, 100);
  EXPECT_TRUE(result.passed) << result.message;
}

TEST(Rng, NeighbouringKeysGiveIndependentFirstValues) {
  // Per-pixel streams are only useful if the first number of neighbouring pixels is not related.
  std::vector<uint32_t> cells;
  for (uint64_t pixel = 0; pixel < 200000; ++pixel) cells.push_back(uint32_t(Rng::forKeys({9, 0, pixel, 0}).uniform() * 100));
  auto result = uniformCells(cells, 100);
  EXPECT_TRUE(result.passed) << result.message;
}

TEST(Rng, UniformIntStaysBelowNAndIsUniform) {
  Rng rng(35);
  for (uint32_t n : {7u, 100u}) {
    std::vector<uint32_t> cells(300000);
    for (uint32_t& c : cells) {
      c = rng.uniformInt(n);
      ASSERT_LT(c, n);
    }
    auto result = uniformCells(cells, n);
    EXPECT_TRUE(result.passed) << "n = " << n << ": " << result.message;
  }
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(rng.uniformInt(1), 0u);
  // A range near 2^32: still in range, and both halves used.
  constexpr uint32_t kLarge = 3000000000u;
  int upperHalf = 0;
  for (int i = 0; i < 100000; ++i) {
    uint32_t v = rng.uniformInt(kLarge);
    ASSERT_LT(v, kLarge);
    upperHalf += v >= kLarge / 2;
  }
  EXPECT_NEAR(upperHalf, 50000, 5 * std::sqrt(100000 * 0.25));
}

TEST(Rng, AdvanceSkipsOutputsLikeDrawingThem) {
  for (uint64_t delta : {0ull, 1ull, 2ull, 7ull, 64ull, 1000ull, 123457ull}) {
    Rng drawn = Rng::forKeys({3, 1, 4}), skipped = drawn;
    for (uint64_t i = 0; i < delta; ++i) drawn.nextUint();
    skipped.advance(delta);
    EXPECT_EQ(skipped.nextUint(), drawn.nextUint()) << delta;
    EXPECT_EQ(skipped.state(), drawn.state()) << delta;
  }
}

}  // namespace
}  // namespace glint
