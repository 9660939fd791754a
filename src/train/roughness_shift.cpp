// ResidualHistogram: counting residuals and reading back their median.
#include "train/roughness_shift.h"

#include <algorithm>
#include <numeric>

namespace glint {

namespace {
constexpr double kBinWidth = (ResidualHistogram::kHigh - ResidualHistogram::kLow) / ResidualHistogram::kBins;
}  // namespace

void ResidualHistogram::add(double residual) {
  const double position = (residual - kLow) / kBinWidth;
  // Below -1 (and NaN, for which the comparison is false) counts in bin 0.
  const int bin = position >= 0 ? int(std::min(position, double(kBins - 1))) : 0;
  ++counts_[size_t(bin)];
}

void ResidualHistogram::merge(const ResidualHistogram& other) {
  for (size_t i = 0; i < counts_.size(); ++i) counts_[i] += other.counts_[i];
}

int64_t ResidualHistogram::count() const { return std::accumulate(counts_.begin(), counts_.end(), int64_t(0)); }

double ResidualHistogram::median() const {
  const int64_t total = count();
  if (total == 0) return 0.0;
  const double half = 0.5 * double(total);
  double below = 0;  // residuals in the bins before bin i
  for (int i = 0; i < kBins; ++i) {
    const double inBin = double(counts_[size_t(i)]);
    if (below + inBin >= half && inBin > 0)
      return kLow + kBinWidth * (i + (half - below) / inBin);
    below += inBin;
  }
  return kHigh;  // unreachable: the counts sum to total
}

}  // namespace glint
