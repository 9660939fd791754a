// Double-precision central finite differences: the oracle every hand-written _vjp is
// tested against (the project rule: every hand-written gradient has such a test).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "math/rng.h"

namespace glint::test {

// A random input in [-1, 1): where the gradients are checked.
inline double symmetric(Rng& rng) { return 2 * rng.uniformDouble() - 1; }

// The gradient of the scalar f at x, dimension by dimension: (f(x + h e_k) - f(x - h e_k))
// / (2 h) with h = relStep * max(|x_k|, 1). With relStep ~1e-6 the truncation error
// (~h^2) and the rounding error (~1e-16 / h) are both near 1e-10 relative.
template <typename F>
std::vector<double> centralGradient(F&& f, std::vector<double> x, double relStep = 1e-6) {
  std::vector<double> gradient(x.size());
  for (size_t k = 0; k < x.size(); ++k) {
    double xk = x[k];
    double h = relStep * std::max(std::abs(xk), 1.0);
    x[k] = xk + h;
    double up = f(x);
    double hi = x[k];
    x[k] = xk - h;
    double down = f(x);
    double lo = x[k];
    x[k] = xk;
    gradient[k] = (up - down) / (hi - lo);  // the steps actually taken, after rounding
  }
  return gradient;
}

// Expects every component of the analytic gradient to match the numeric one within
// relTol of its size; components near zero are judged against the whole gradient's size
// (a 1e-2 share of its largest component), where the difference quotient's rounding
// error would otherwise dominate.
inline void expectGradientNear(const std::vector<double>& analytic, const std::vector<double>& numeric,
                               double relTol, const std::string& what) {
  ASSERT_EQ(analytic.size(), numeric.size()) << what;
  double largest = 0;
  for (double g : numeric) largest = std::max(largest, std::abs(g));
  for (size_t k = 0; k < analytic.size(); ++k) {
    double tolerance = relTol * std::max(std::abs(numeric[k]), 1e-2 * largest) + 1e-12;
    EXPECT_NEAR(analytic[k], numeric[k], tolerance) << what << ", component " << k;
  }
}

}  // namespace glint::test
