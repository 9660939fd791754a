// Vector-Jacobian products of the quaternion operations in math/quat.h (normalisation and
// rotation matrix), for the backward pass; derivations D1-D2 in docs/derivations.md.
#pragma once

#include "core/cpu_gpu.h"

#include "math/mat3.h"
#include "math/quat.h"

namespace glint {

// Adjoint of u = q / |q| (Quat::normalized): v_q = (v_u - u (u . v_u)) / |q|, the part of
// v_u orthogonal to u, scaled by 1/|q| (derivations D1). The primal maps q = 0 to the
// constant identity, whose adjoint is 0.
template <typename T>
GLINT_CPU_GPU Quat<T> quatNormalize_vjp(const Quat<T>& q, const Quat<T>& v_u) {
  T n = q.norm();
  if (!(n > T(0))) return Quat<T>{0, 0, 0, 0};
  Quat<T> u = q.normalized();
  T uDotV = u.w * v_u.w + u.x * v_u.x + u.y * v_u.y + u.z * v_u.z;
  return Quat<T>{(v_u.w - u.w * uDotV) / n, (v_u.x - u.x * uDotV) / n, (v_u.y - u.y * uDotV) / n,
                 (v_u.z - u.z * uDotV) / n};
}

// Adjoint of quatToRotation(q) = R(q / |q|): v_R holds dL/dR_ij (row i, column j). First
// through the quadratic entries of R(u) (derivations D2), then through the normalisation
// (D1).
template <typename T>
GLINT_CPU_GPU Quat<T> quatToRotation_vjp(const Quat<T>& q, const Mat3<T>& v_R) {
  Quat<T> u = q.normalized();
  T w = u.w, x = u.x, y = u.y, z = u.z;
  const Vec3<T>* v = v_R.m;  // v[i][j] = dL/dR_ij
  // Rotation of a unit quaternion: each entry of R is quadratic in (w, x, y, z) (D2).
  Quat<T> v_u;
  v_u.w = T(2) * (-z * v[0][1] + y * v[0][2] + z * v[1][0] - x * v[1][2] - y * v[2][0] + x * v[2][1]);
  v_u.x = T(2) * (y * v[0][1] + z * v[0][2] + y * v[1][0] - T(2) * x * v[1][1] - w * v[1][2] + z * v[2][0] +
                  w * v[2][1] - T(2) * x * v[2][2]);
  v_u.y = T(2) * (-T(2) * y * v[0][0] + x * v[0][1] + w * v[0][2] + x * v[1][0] + z * v[1][2] - w * v[2][0] +
                  z * v[2][1] - T(2) * y * v[2][2]);
  v_u.z = T(2) * (-T(2) * z * v[0][0] - w * v[0][1] + x * v[0][2] + w * v[1][0] - T(2) * z * v[1][1] +
                  y * v[1][2] + x * v[2][0] + y * v[2][1]);
  // Normalisation u = q / |q| (D1).
  return quatNormalize_vjp(q, v_u);
}

}  // namespace glint
