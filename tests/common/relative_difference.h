// ||x - y|| / ||y|| in the L2 norm, in double: how far one array of gradients (or any floats)
// is from a reference, where single elements may differ more when their sums cancel.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>

namespace glint::test {

inline double relativeDifference(std::span<const float> x, std::span<const float> y) {
  double diff = 0, norm = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    diff += (double(x[i]) - double(y[i])) * (double(x[i]) - double(y[i]));
    norm += double(y[i]) * double(y[i]);
  }
  return std::sqrt(diff / std::max(norm, 1e-300));
}

}  // namespace glint::test
