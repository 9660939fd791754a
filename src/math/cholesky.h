// Cholesky factorisation and solve of small dense symmetric positive definite systems (the
// normal equations of least-squares fits: spherical harmonics, camera poses).
#pragma once

#include <cmath>

namespace glint {

// Factors the n x n matrix a (row-major with row stride `stride`, lower triangle read) into
// L L^T in place, L in the lower triangle. False when a is not positive definite.
inline bool choleskyFactor(double* a, int n, int stride) {
  for (int j = 0; j < n; ++j) {
    double diagonal = a[j * stride + j];
    for (int k = 0; k < j; ++k) diagonal -= a[j * stride + k] * a[j * stride + k];
    if (!(diagonal > 0)) return false;
    a[j * stride + j] = std::sqrt(diagonal);
    for (int i = j + 1; i < n; ++i) {
      double s = a[i * stride + j];
      for (int k = 0; k < j; ++k) s -= a[i * stride + k] * a[j * stride + k];
      a[i * stride + j] = s / a[j * stride + j];
    }
  }
  return true;
}

// Solves L L^T x = b in place (x holds b on entry) with the factor of choleskyFactor. T is a
// scalar or a vector of right-hand sides solved together (e.g. Vec3d: one per colour channel).
template <typename T>
void choleskySolve(const double* l, int n, int stride, T* x) {
  for (int i = 0; i < n; ++i) {  // L z = b
    T s = x[i];
    for (int k = 0; k < i; ++k) s -= x[k] * l[i * stride + k];
    x[i] = s / l[i * stride + i];
  }
  for (int i = n - 1; i >= 0; --i) {  // L^T x = z
    T s = x[i];
    for (int k = i + 1; k < n; ++k) s -= x[k] * l[k * stride + i];
    x[i] = s / l[i * stride + i];
  }
}

}  // namespace glint
