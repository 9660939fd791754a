// Statistical tests of the warps and tabulated distributions in math/sampling.h.
#include "math/sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "common/chi_square.h"
#include "math/rng.h"

namespace glint {
namespace {

// Every chi-square test in this file shares one overall significance of 1% (Sidak).
constexpr int kSamplingChiSquareTests = 10;
const double kSamplingSignificance = test::sidakSignificance(0.01, kSamplingChiSquareTests);
constexpr int kSamples = 200000;

TEST(SamplingChiSquare, CosineHemisphere) {
  auto result = test::testDirectionSampler(
      test::DirectionGrid::hemisphere(), [](Vec2f u) { return std::optional(sampleCosineHemisphere(u)); },
      [](const Vec3f& w) { return double(cosineHemispherePdf(w.z)); }, kSamples, 1, kSamplingSignificance);
  EXPECT_TRUE(result.passed) << result.message;
}

TEST(SamplingChiSquare, UniformSphere) {
  auto result = test::testDirectionSampler(
      test::DirectionGrid::sphere(), [](Vec2f u) { return std::optional(sampleUniformSphere(u)); },
      [](const Vec3f&) { return double(uniformSpherePdf()); }, kSamples, 2, kSamplingSignificance);
  EXPECT_TRUE(result.passed) << result.message;
}

TEST(SamplingChiSquare, UniformCone) {
  // Narrow, wide and wider-than-a-hemisphere cones. The grid covers exactly the cone and
  // the cell outside it expects nothing, so a single sample outside the cone fails the test.
  for (float cosThetaMax : {0.95f, 0.5f, -0.3f}) {
    test::DirectionGrid grid{10, 20, cosThetaMax};
    auto pdf = [&](const Vec3f& w) { return w.z >= cosThetaMax ? double(uniformConePdf(cosThetaMax)) : 0.0; };
    auto result = test::testDirectionSampler(
        grid, [&](Vec2f u) { return std::optional(sampleUniformCone(u, cosThetaMax)); }, pdf, kSamples, 3,
        kSamplingSignificance);
    EXPECT_TRUE(result.passed) << "cos(theta max) = " << cosThetaMax << ": " << result.message;
  }
}

TEST(SamplingChiSquare, ConcentricDiskIsUniform) {
  // Cells of equal area: equal steps in r^2 and in phi.
  constexpr int kRings = 10, kSectors = 20;
  std::vector<double> observed(kRings * kSectors, 0.0);
  Rng rng(4);
  for (int k = 0; k < kSamples; ++k) {
    Vec2f p = sampleConcentricDisk(rng.uniform2());
    double r2 = double(p.x) * p.x + double(p.y) * p.y;
    ASSERT_LE(r2, 1.0 + 1e-6);
    double phi = std::atan2(double(p.y), double(p.x));
    if (phi < 0) phi += test::kTwoPi;
    int ring = std::min(int(r2 * kRings), kRings - 1);
    int sector = std::min(int(phi / test::kTwoPi * kSectors), kSectors - 1);
    observed[ring * kSectors + sector] += 1;
  }
  std::vector<double> expected(observed.size(), double(kSamples) / observed.size());
  auto result = test::pearsonChiSquare(observed, expected, kSamplingSignificance);
  EXPECT_TRUE(result.passed) << result.message;
}

TEST(SamplingChiSquare, UniformTriangle) {
  // Split the triangle into k^2 congruent sub-triangles: in barycentric cell (i, j) of size
  // 1/k, the lower half (frac(b0) + frac(b1) < 1) always lies inside, the upper half only
  // when i + j <= k - 2. Each sub-triangle should receive 1 / k^2 of the samples.
  constexpr int k = 8;
  std::vector<double> observed(2 * k * k, 0.0), expected(2 * k * k, 0.0);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; i + j < k; ++j) {
      expected[2 * (i * k + j)] = double(kSamples) / (k * k);
      if (i + j <= k - 2) expected[2 * (i * k + j) + 1] = double(kSamples) / (k * k);
    }
  }
  Rng rng(5);
  double sum0 = 0, sum1 = 0;
  for (int s = 0; s < kSamples; ++s) {
    Vec2f b = sampleUniformTriangle(rng.uniform2());
    ASSERT_GE(b.x, 0.0f);
    ASSERT_GE(b.y, 0.0f);
    ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
    sum0 += b.x, sum1 += b.y;
    double x = double(b.x) * k, y = double(b.y) * k;
    int i = std::min(int(x), k - 1), j = std::min(int(y), k - 1);
    bool upper = (x - i) + (y - j) >= 1.0;
    observed[2 * (i * k + j) + (upper ? 1 : 0)] += 1;
  }
  // The centroid is the mean of uniform barycentrics.
  EXPECT_NEAR(sum0 / kSamples, 1.0 / 3.0, 3e-3);
  EXPECT_NEAR(sum1 / kSamples, 1.0 / 3.0, 3e-3);
  auto result = test::pearsonChiSquare(observed, expected, kSamplingSignificance);
  EXPECT_TRUE(result.passed) << result.message;
}

const std::vector<float> kWeights = {0, 1, 3, 0, 0.5f, 2, 0, 0, 4, 0.25f, 0};

TEST(Distribution1D, FrequenciesMatchWeights) {
  Distribution1D dist(kWeights);
  ASSERT_EQ(dist.size(), kWeights.size());
  EXPECT_FLOAT_EQ(dist.total(), 10.75f);
  std::vector<double> observed(kWeights.size(), 0.0), expected(kWeights.size());
  for (size_t i = 0; i < kWeights.size(); ++i) expected[i] = kSamples * kWeights[i] / 10.75;
  Rng rng(6);
  for (int s = 0; s < kSamples; ++s) {
    float probability = 0;
    size_t index = dist.sample(rng.uniform(), &probability);
    ASSERT_LT(index, kWeights.size());
    EXPECT_FLOAT_EQ(probability, dist.probability(index));
    observed[index] += 1;
  }
  for (size_t i = 0; i < kWeights.size(); ++i) {
    if (kWeights[i] == 0) {
      EXPECT_EQ(observed[i], 0) << "zero-weight bin " << i << " was picked";
    }
    EXPECT_NEAR(dist.probability(i), kWeights[i] / 10.75f, 1e-6f);
  }
  auto result = test::pearsonChiSquare(observed, expected, kSamplingSignificance);
  EXPECT_TRUE(result.passed) << result.message;
}

TEST(Distribution1D, ZeroWeightBinsAreNeverPickedAtCdfEdges) {
  Distribution1D dist(kWeights);
  // The extreme values of u, and u exactly on every CDF step (as float, the way callers pass it).
  std::vector<float> us = {0.0f, 0x1.fffffep-1f};
  double cumulative = 0;
  for (float w : kWeights) {
    cumulative += w;
    float edge = float(cumulative / 10.75);
    us.push_back(edge);
    us.push_back(std::nextafter(edge, 0.0f));
  }
  for (float u : us) {
    if (u >= 1.0f) continue;
    float remapped = -1;
    size_t index = dist.sample(u, nullptr, &remapped);
    EXPECT_GT(kWeights[index], 0.0f) << "u = " << u << " picked zero-weight bin " << index;
    EXPECT_GE(remapped, 0.0f);
    EXPECT_LT(remapped, 1.0f);
  }
}

TEST(Distribution1D, RemappedSampleIsUniform) {
  Distribution1D dist(kWeights);
  constexpr int kBins = 20;
  std::vector<double> observed(kBins, 0.0), expected(kBins, double(kSamples) / kBins);
  Rng rng(7);
  for (int s = 0; s < kSamples; ++s) {
    float remapped = -1;
    dist.sample(rng.uniform(), nullptr, &remapped);
    ASSERT_GE(remapped, 0.0f);
    ASSERT_LT(remapped, 1.0f);
    observed[std::min(int(remapped * kBins), kBins - 1)] += 1;
  }
  auto result = test::pearsonChiSquare(observed, expected, kSamplingSignificance);
  EXPECT_TRUE(result.passed) << result.message;
}

// A 16 x 8 image with a dark row and a few dark pixels, like a sky map with a black ground.
std::vector<float> environmentWeights(int width, int height) {
  std::vector<float> weights(size_t(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      weights[size_t(y) * width + x] = y == 5 || (x + y) % 7 == 0 ? 0.0f : 1.0f + float((x * 3 + y * 5) % 11);
  return weights;
}

TEST(Distribution2D, PdfIntegratesToOne) {
  constexpr int kWidth = 16, kHeight = 8;
  Distribution2D dist(environmentWeights(kWidth, kHeight), kWidth, kHeight);
  // The pdf is constant on each texel, so midpoints of a finer grid integrate it exactly.
  constexpr int kSteps = 4;
  double integral = 0;
  for (int y = 0; y < kHeight * kSteps; ++y)
    for (int x = 0; x < kWidth * kSteps; ++x)
      integral += dist.pdf({(x + 0.5f) / (kWidth * kSteps), (y + 0.5f) / (kHeight * kSteps)});
  integral /= double(kWidth * kSteps) * (kHeight * kSteps);
  EXPECT_NEAR(integral, 1.0, 1e-5);
}

TEST(Distribution2D, SampleHistogramMatchesPdf) {
  constexpr int kWidth = 16, kHeight = 8;
  std::vector<float> weights = environmentWeights(kWidth, kHeight);
  Distribution2D dist(weights, kWidth, kHeight);
  double total = 0;
  for (float w : weights) total += w;
  // Half-texel cells also check that samples are uniform within each texel.
  constexpr int kCellsX = 2 * kWidth, kCellsY = 2 * kHeight;
  std::vector<double> observed(kCellsX * kCellsY, 0.0), expected(kCellsX * kCellsY);
  for (int y = 0; y < kCellsY; ++y)
    for (int x = 0; x < kCellsX; ++x)
      expected[y * kCellsX + x] = kSamples * weights[(y / 2) * kWidth + x / 2] / total / 4;
  Rng rng(8);
  for (int s = 0; s < kSamples; ++s) {
    float pdf = 0;
    Vec2f p = dist.sample(rng.uniform2(), &pdf);
    ASSERT_GE(p.x, 0.0f);
    ASSERT_LT(p.x, 1.0f);
    ASSERT_GE(p.y, 0.0f);
    ASSERT_LT(p.y, 1.0f);
    ASSERT_GT(pdf, 0.0f);
    EXPECT_NEAR(pdf, dist.pdf(p), 1e-4f * pdf);
    observed[std::min(int(p.y * kCellsY), kCellsY - 1) * kCellsX + std::min(int(p.x * kCellsX), kCellsX - 1)] += 1;
  }
  auto result = test::pearsonChiSquare(observed, expected, kSamplingSignificance);
  EXPECT_TRUE(result.passed) << result.message;
}

TEST(Sampling, PowerHeuristic) {
  EXPECT_FLOAT_EQ(powerHeuristic(1, 1), 0.5f);
  EXPECT_FLOAT_EQ(powerHeuristic(3, 0), 1.0f);
  EXPECT_FLOAT_EQ(powerHeuristic(1, 2), 0.2f);
  EXPECT_FLOAT_EQ(powerHeuristic(0, 0), 0.0f);
}

}  // namespace
}  // namespace glint
