// Normal equations and their Cholesky solve for ShFit.
#include "math/sh_fit.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

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
  // Cholesky A = L L^T in place (lower triangle).
  for (int j = 0; j < count_; ++j) {
    double diagonal = a[j][j];
    for (int k = 0; k < j; ++k) diagonal -= a[j][k] * a[j][k];
    if (!(diagonal > 0)) return false;
    a[j][j] = std::sqrt(diagonal);
    for (int i = j + 1; i < count_; ++i) {
      double s = a[i][j];
      for (int k = 0; k < j; ++k) s -= a[i][k] * a[j][k];
      a[i][j] = s / a[j][j];
    }
  }
  // L z = rhs, then L^T f = z.
  Vec3d f[N];
  for (int i = 0; i < count_; ++i) {
    Vec3d s = rhs_[size_t(i)];
    for (int k = 0; k < i; ++k) s -= f[k] * a[i][k];
    f[i] = s / a[i][i];
  }
  for (int i = count_ - 1; i >= 0; --i) {
    Vec3d s = f[i];
    for (int k = i + 1; k < count_; ++k) s -= f[k] * a[k][i];
    f[i] = s / a[i][i];
  }
  *constant = f[0];
  for (int k = 1; k < count_; ++k) rest[k - 1] = f[k];
  return true;
}

}  // namespace glint
