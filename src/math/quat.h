// Unit quaternions (w, x, y, z) for Gaussian orientations; stored unnormalised, normalised on use.
#pragma once

#include <cmath>

#include "core/cpu_gpu.h"
#include "math/mat3.h"

namespace glint {

template <typename T>
struct Quat {
  T w = 1, x = 0, y = 0, z = 0;

  GLINT_CPU_GPU T norm() const { return std::sqrt(w * w + x * x + y * y + z * z); }
  GLINT_CPU_GPU Quat normalized() const {
    T n = norm();
    return n > T(0) ? Quat{w / n, x / n, y / n, z / n} : Quat{};
  }
};

// Rotation matrix of q / |q| (the columns are the local axes in world space).
template <typename T>
GLINT_CPU_GPU Mat3<T> quatToRotation(const Quat<T>& q) {
  Quat<T> u = q.normalized();
  T w = u.w, x = u.x, y = u.y, z = u.z;
  Mat3<T> r;
  r.m[0] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)};
  r.m[1] = {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)};
  r.m[2] = {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)};
  return r;
}

// Hamilton product: rotating by b, then by a, is rotating by a * b.
template <typename T>
GLINT_CPU_GPU Quat<T> operator*(const Quat<T>& a, const Quat<T>& b) {
  return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
          a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

// The unit quaternion of a right-handed rotation by `radians` about `axis` (any length > 0).
template <typename T>
Quat<T> quatFromAxisAngle(const Vec3<T>& axis, T radians) {
  Vec3<T> u = normalize(axis);
  T s = std::sin(radians / 2);
  return {std::cos(radians / 2), u.x * s, u.y * s, u.z * s};
}

// Index of the component of largest magnitude among four (the first on ties): the one
// "smallest three" encodings of unit quaternions leave out and recover from the norm.
template <typename T>
int largestMagnitudeIndex(const T (&q)[4]) {
  int largest = 0;
  for (int i = 1; i < 4; ++i)
    if (std::abs(q[i]) > std::abs(q[largest])) largest = i;
  return largest;
}

using Quatf = Quat<float>;
using Quatd = Quat<double>;

}  // namespace glint
