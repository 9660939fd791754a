// Vector-Jacobian products of the 3x3 matrix operations in math/mat3.h used by the
// backward pass; derivation D3 in docs/derivations.md.
#pragma once

#include "core/cpu_gpu.h"

#include "math/mat3.h"
#include "math/vec.h"

namespace glint {

// The zero matrix (Mat3 default-constructs to the identity), to start adjoint sums.
template <typename T>
GLINT_CPU_GPU Mat3<T> zeroMat3() {
  Mat3<T> r;
  for (int i = 0; i < 3; ++i) r.m[i] = Vec3<T>(T(0));
  return r;
}

// Adjoint of y = M x (Mat3::operator*): v_M = v_y x^T, v_x = M^T v_y (derivations D3).
// The results are added to *v_M and *v_x so several products can share one adjoint.
template <typename T>
GLINT_CPU_GPU void matVec_vjp(const Mat3<T>& M, const Vec3<T>& x, const Vec3<T>& v_y, Mat3<T>* v_M, Vec3<T>* v_x) {
  if (v_M)
    for (int i = 0; i < 3; ++i) v_M->m[i] += x * v_y[i];  // row i of v_y x^T
  if (v_x) *v_x += M.transposeTimes(v_y);
}

}  // namespace glint
