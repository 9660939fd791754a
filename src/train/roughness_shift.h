// The offset between a roughness prior and the model's roughness, which the shift-invariant
// roughness term (TrainConfig::roughnessShiftInvariant, beyond the paper) takes out.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace glint {

// Residuals p - r (prior minus model roughness) of a batch's surface pixels, counted in
// bins over [-1, 1]. Their median is the offset b that minimises the L1 term
// sum |r + b - p| over b. The counts are integers, so threads and MPI ranks merge them
// exactly and in any order.
class ResidualHistogram {
 public:
  static constexpr int kBins = 512;  // 1/256 wide: an 8-bit roughness step
  static constexpr double kLow = -1.0, kHigh = 1.0;

  void add(double residual);  // values outside [-1, 1] count in the end bins
  void merge(const ResidualHistogram& other);
  void clear() { counts_.fill(0); }
  int64_t count() const;
  // The median, interpolated linearly inside its bin (accurate to a bin's width); 0 when
  // the histogram is empty.
  double median() const;
  std::span<int64_t> counts() { return counts_; }  // for a sum over MPI ranks

 private:
  std::array<int64_t, kBins> counts_{};
};

}  // namespace glint
