// Unit quaternions (w, x, y, z) for Gaussian orientations; stored unnormalised, normalised on use.
#pragma once

#include <cmath>

#include "math/mat3.h"

namespace glint {

template <typename T>
struct Quat {
  T w = 1, x = 0, y = 0, z = 0;

  T norm() const { return std::sqrt(w * w + x * x + y * y + z * z); }
  Quat normalized() const {
    T n = norm();
    return n > T(0) ? Quat{w / n, x / n, y / n, z / n} : Quat{};
  }
};

// Rotation matrix of q / |q| (the columns are the local axes in world space).
template <typename T>
Mat3<T> quatToRotation(const Quat<T>& q) {
  Quat<T> u = q.normalized();
  T w = u.w, x = u.x, y = u.y, z = u.z;
  Mat3<T> r;
  r.m[0] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)};
  r.m[1] = {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)};
  r.m[2] = {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)};
  return r;
}

using Quatf = Quat<float>;
using Quatd = Quat<double>;

}  // namespace glint
