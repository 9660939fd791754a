// Weighted least-squares fit of a view-dependent colour by spherical harmonics of degree
// <= 3 in the 3DGS basis (math/spherical_harmonics.h), with a ridge term on the
// view-dependent part: the solver behind baking reflections into splat colours.
#pragma once

#include <array>

#include "math/spherical_harmonics.h"
#include "math/vec.h"

namespace glint {

// Accumulates the normal equations of samples (d_j, y_j, w_j) for the model
// c(d) = g + sum_{k >= 1} f_k B_k(d), then solves
//   min  sum_j w_j |c(d_j) - y_j|^2 + lambda W sum_{k >= 1} |f_k|^2,   W = sum_j w_j,
// per colour channel. The ridge scales with W so that lambda means the same for any
// number of samples; it pulls what the samples do not determine toward a constant colour.
class ShFit {
 public:
  explicit ShFit(int degree);

  // One sample: unit direction d (viewer towards the Gaussian), value y, weight w >= 0.
  void add(const Vec3d& d, const Vec3d& y, double w);
  double totalWeight() const { return weight_; }
  int degree() const { return degree_; }

  // The constant g and the coefficients f_1 .. f_{count-1} (rest[k - 1]); false (outputs
  // untouched) when the total weight is zero.
  bool solve(double lambda, Vec3d* constant, Vec3d* rest) const;

 private:
  int degree_;
  int count_;  // shCoefficientCount(degree_)
  std::array<double, kMaxShCoefficients * kMaxShCoefficients> normal_{};  // sum w b b^T, row-major
  std::array<Vec3d, kMaxShCoefficients> rhs_{};                           // sum w y b
  double weight_ = 0;
};

}  // namespace glint
