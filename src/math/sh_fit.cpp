// Normal equations and their Cholesky solve for ShFit.
#include "math/sh_fit.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "math/cholesky.h"

namespace glint {

ShFit::ShFit(int degree) : degree_(degree), count_(shCoefficientCount(degree)) {
  GLINT_CHECK(degree >= 0 && degree <= kMaxShDegree, "ShFit: SH degree must be 0..3");
}

void ShFit::add(const Vec3d& d, const Vec3d& y, double w) {
  if (!(w > 0)) return;
  double b[kMaxShCoefficients];
  shBasis(d, degree_, b);
  b[0] = 1.0;  // the constant term g
  for (int r = 0; r < count_; ++r) {
    for (int c = 0; c <= r; ++c) normal_[size_t(r * kMaxShCoefficients + c)] += w * b[r] * b[c];
    rhs_[size_t(r)] += y * (w * b[r]);
  }
  weight_ += w;
}

bool ShFit::solve(double lambda, Vec3d* constant, Vec3d* rest) const {
  if (!(weight_ > 0)) return false;
  // A = the lower triangle accumulated above, plus the ridge (and a trace of it on g,
  // which keeps A positive definite when every sample has one direction).
  constexpr int N = kMaxShCoefficients;
  double a[N][N] = {};
  for (int r = 0; r < count_; ++r)
    for (int c = 0; c <= r; ++c) a[r][c] = normal_[size_t(r * N + c)];
  a[0][0] += 1e-12 * weight_;
  for (int k = 1; k < count_; ++k) a[k][k] += std::max(lambda, 1e-12) * weight_;
  if (!choleskyFactor(&a[0][0], count_, N)) return false;
  Vec3d f[N];
  for (int i = 0; i < count_; ++i) f[i] = rhs_[size_t(i)];
  choleskySolve(&a[0][0], count_, N, f);
  *constant = f[0];
  for (int k = 1; k < count_; ++k) rest[k - 1] = f[k];
  return true;
}

}  // namespace glint
