// The value below which a fraction of a set of numbers lies (a median at one half): healing's
// spacing and ring coverage, the light search's brightness and size scales.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace glint {

// The element at index floor(fraction x n) of the sorted values (the upper median at 0.5),
// 0 for none. Takes a copy, which it reorders.
inline float percentileOf(std::vector<float> values, double fraction) {
  if (values.empty()) return 0.0f;
  const size_t index = std::min(values.size() - 1, size_t(double(values.size()) * fraction));
  auto at = values.begin() + std::ptrdiff_t(index);
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

}  // namespace glint
