// Pearson chi-square goodness-of-fit tests for samplers: p-values, Sidak correction,
// pooling of sparse cells, and a test of direction samplers against their densities.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "common/direction_grid.h"
#include "math/rng.h"
#include "math/vec.h"

namespace glint::test {

// Regularised upper incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a), a > 0.
// Series for P = 1 - Q below x = a + 1, Legendre's continued fraction for Q above it
// (evaluated with the modified Lentz method); both converge fast in their half.
inline double regularizedGammaQ(double a, double x) {
  if (x <= 0) return 1.0;
  double logPrefactor = a * std::log(x) - x - std::lgamma(a);  // log(x^a e^-x / Gamma(a))
  constexpr double kEpsilon = 1e-15;
  if (x < a + 1) {
    // P(a, x) = x^a e^-x / Gamma(a) * sum_n x^n / (a (a+1) ... (a+n)).
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 10000 && term > sum * kEpsilon; ++n) {
      term *= x / (a + n);
      sum += term;
    }
    return std::clamp(1.0 - sum * std::exp(logPrefactor), 0.0, 1.0);
  }
  // Q(a, x) = x^a e^-x / Gamma(a) * 1 / (x+1-a - 1(1-a) / (x+3-a - 2(2-a) / (x+5-a - ...))).
  constexpr double kTiny = 1e-300;
  double b = x + 1 - a;
  double c = 1 / kTiny, d = 1 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1 / d;
    double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1) < kEpsilon) break;
  }
  return std::clamp(std::exp(logPrefactor) * h, 0.0, 1.0);
}

// Probability that a chi-square variable with dof degrees of freedom is at least statistic.
inline double chiSquarePValue(double statistic, int dof) { return regularizedGammaQ(0.5 * dof, 0.5 * statistic); }

// Per-test significance so that numTests independent tests reject a correct sampler with
// overall probability alpha (Sidak 1967).
inline double sidakSignificance(double alpha, int numTests) { return 1.0 - std::pow(1.0 - alpha, 1.0 / numTests); }

struct ChiSquareResult {
  bool passed = false;
  double statistic = 0;
  int dof = 0;
  double pValue = 0;
  std::string message;  // why it failed, or the statistics when it passed
};

// Pearson's test of observed against expected counts per cell. Cells expecting fewer than
// minExpected samples are pooled (smallest first) until the pool reaches minExpected, since
// the chi-square approximation needs every cell to expect a handful of samples. A sample in
// a cell of zero expected count fails outright: the sampler produced an impossible value.
inline ChiSquareResult pearsonChiSquare(const std::vector<double>& observed, const std::vector<double>& expected,
                                        double significance, double minExpected = 5.0) {
  ChiSquareResult result;
  std::vector<size_t> order(expected.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });

  double pooledObserved = 0, pooledExpected = 0;
  int cells = 0;
  size_t worstCell = 0;
  double worstTerm = -1;
  for (size_t i : order) {
    if (expected[i] <= 0) {
      if (observed[i] > 0) {
        std::ostringstream out;
        out << "cell " << i << " received " << observed[i] << " samples but the density integrates to 0 there";
        result.message = out.str();
        return result;
      }
      continue;
    }
    if (expected[i] < minExpected || (pooledExpected > 0 && pooledExpected < minExpected)) {
      pooledObserved += observed[i];
      pooledExpected += expected[i];
      continue;
    }
    double term = (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    if (term > worstTerm) worstTerm = term, worstCell = i;
    result.statistic += term;
    ++cells;
  }
  if (pooledExpected > 0) {
    result.statistic += (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
    ++cells;
  }
  result.dof = cells - 1;  // the total count is fixed, which removes one degree of freedom
  std::ostringstream out;
  if (result.dof < 1) {
    out << "only " << cells << " usable cells; the test needs more samples or coarser cells";
    result.message = out.str();
    return result;
  }
  result.pValue = chiSquarePValue(result.statistic, result.dof);
  result.passed = result.pValue >= significance;
  out << "chi2 = " << result.statistic << " with " << result.dof << " dof, p = " << result.pValue
      << " (significance " << significance << "); largest term from cell " << worstCell << ": observed "
      << observed[worstCell] << ", expected " << expected[worstCell];
  result.message = out.str();
  return result;
}

// Draws sampleCount directions from sample(u) (which may return nothing, e.g. a reflection
// below the horizon: such samples are dropped, matching a pdf that integrates to less
// than 1) and tests them against pdf with Pearson's chi-square over grid. Every
// direction must be finite and of unit length.
inline ChiSquareResult testDirectionSampler(const DirectionGrid& grid,
                                            const std::function<std::optional<Vec3f>(Vec2f)>& sample,
                                            const std::function<double(const Vec3f&)>& pdf, int sampleCount,
                                            uint64_t seed, double significance) {
  std::vector<double> observed(grid.cellCount(), 0.0);
  Rng rng(seed);
  for (int k = 0; k < sampleCount; ++k) {
    std::optional<Vec3f> w = sample(rng.uniform2());
    if (!w) continue;
    if (!isFinite(*w) || std::abs(length(*w) - 1.0f) > 1e-4f) {
      ChiSquareResult failed;
      std::ostringstream out;
      out << "sample " << k << " = (" << w->x << ", " << w->y << ", " << w->z << ") is not a unit direction";
      failed.message = out.str();
      return failed;
    }
    observed[grid.cellOf(*w)] += 1;
  }
  return pearsonChiSquare(observed, grid.expectedCounts(pdf, sampleCount), significance);
}

}  // namespace glint::test
