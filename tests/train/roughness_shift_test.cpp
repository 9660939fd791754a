// ResidualHistogram: its median against the sample median of the same residuals (a
// statistical test over seeded draws), the interpolation inside a bin, merging, and the
// ends of the range.
#include "train/roughness_shift.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "math/rng.h"

namespace glint {
namespace {

constexpr double kBin = 2.0 / ResidualHistogram::kBins;

// A residual like a biased roughness prior's: offset + Gaussian noise (Box-Muller), with
// the clamp of the prior at 0 for a mirror's pixels (a third of them).
double biasedResidual(Rng& rng, double offset, double sigma) {
  const double u1 = std::max(rng.uniformDouble(), 1e-300), u2 = rng.uniformDouble();
  const double noise = sigma * std::sqrt(-2 * std::log(u1)) * std::cos(2 * 3.141592653589793 * u2);
  const bool mirror = rng.uniformDouble() < 1.0 / 3.0;
  const double truth = mirror ? 0.0 : 0.2 + 0.7 * rng.uniformDouble();
  const double prior = std::clamp(truth + offset + noise, 0.0, 1.0);
  return prior - truth;
}

TEST(ResidualHistogram, MedianMatchesTheSampleMedianToABinWidth) {
  for (uint64_t seed : {1u, 2u, 3u}) {
    Rng rng(seed);
    ResidualHistogram h;
    std::vector<double> samples;
    for (int i = 0; i < 20000; ++i) {
      samples.push_back(biasedResidual(rng, 0.05, 0.05));
      h.add(samples.back());
    }
    std::nth_element(samples.begin(), samples.begin() + samples.size() / 2, samples.end());
    const double sampleMedian = samples[samples.size() / 2];
    EXPECT_EQ(h.count(), 20000);
    EXPECT_NEAR(h.median(), sampleMedian, kBin) << "seed " << seed;
    // And the offset it estimates, 0.05: the clamp moves only residuals below the median,
    // and 20,000 draws put the sample median within 0.002 of the population's (7 standard
    // deviations), the histogram's within a bin more.
    EXPECT_NEAR(h.median(), 0.05, 0.002 + kBin);
  }
}

TEST(ResidualHistogram, InterpolatesInsideTheMedianBin) {
  ResidualHistogram h;
  // Four residuals in the bin starting at 0.25: the median sits halfway into it.
  const double start = -1.0 + kBin * std::floor((0.25 + 1.0) / kBin);
  for (int i = 0; i < 4; ++i) h.add(start + 0.5 * kBin);
  EXPECT_NEAR(h.median(), start + 0.5 * kBin, 1e-12);
  // Two below and two above a gap: the median is the top of the lower bin.
  ResidualHistogram split;
  split.add(-0.5), split.add(-0.5), split.add(0.5), split.add(0.5);
  const double lowBinTop = -1.0 + kBin * (std::floor((-0.5 + 1.0) / kBin) + 1);
  EXPECT_NEAR(split.median(), lowBinTop, 1e-12);
}

TEST(ResidualHistogram, EmptyIsZeroAndOutOfRangeCountsAtTheEnds) {
  ResidualHistogram h;
  EXPECT_EQ(h.count(), 0);
  EXPECT_EQ(h.median(), 0.0);
  h.add(-7.0), h.add(std::nan("")), h.add(-1.5);
  EXPECT_EQ(h.count(), 3);
  EXPECT_LT(h.median(), -1.0 + kBin);
  h.clear();
  h.add(3.0), h.add(1.0), h.add(1.0);
  EXPECT_GT(h.median(), 1.0 - kBin);
  EXPECT_LE(h.median(), 1.0);
}

TEST(ResidualHistogram, MergingEqualsAddingEverythingToOne) {
  Rng rng(9);
  ResidualHistogram a, b, all;
  for (int i = 0; i < 1000; ++i) {
    const double r = rng.uniformDouble() * 1.6 - 0.8;
    (i % 3 ? a : b).add(r);
    all.add(r);
  }
  a.merge(b);
  EXPECT_EQ(a.count(), all.count());
  EXPECT_EQ(a.median(), all.median());
  const auto ac = a.counts(), allc = all.counts();
  EXPECT_TRUE(std::equal(ac.begin(), ac.end(), allc.begin()));
}

}  // namespace
}  // namespace glint
