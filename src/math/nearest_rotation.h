// The rotation nearest a 3x3 matrix (the mean of rotations that differ by a few degrees) and a
// rotation's angle: camera frames compared or refined together.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "math/mat3.h"

namespace glint {

// The inverse of a 3x3 matrix by its cofactors (the caller keeps it invertible).
inline Mat3d inverseOf(const Mat3d& a) {
  const Vec3d c0 = cross(a.m[1], a.m[2]), c1 = cross(a.m[2], a.m[0]), c2 = cross(a.m[0], a.m[1]);
  const double det = dot(a.m[0], c0);
  Mat3d r;
  for (int i = 0; i < 3; ++i) r.m[i] = Vec3d(c0[i], c1[i], c2[i]) / det;
  return r;
}

// The orthogonal polar factor of m (the rotation nearest it in the Frobenius norm, for m of
// positive determinant), by Higham's iteration m <- (m + m^-T) / 2, which converges
// quadratically; a sum of rotations a few degrees apart needs 5-6 of the 30 steps.
inline Mat3d nearestRotation(Mat3d m) {
  for (int k = 0; k < 30; ++k) {
    const Mat3d inverseTransposed = inverseOf(m).transposed();
    for (int i = 0; i < 3; ++i) m.m[i] = (m.m[i] + inverseTransposed.m[i]) * 0.5;
  }
  return m;
}

// The angle of rotation r in degrees, from its trace: 1 + 2 cos(angle).
inline double rotationAngleDegrees(const Mat3d& r) {
  const double cosine = std::clamp((r.m[0].x + r.m[1].y + r.m[2].z - 1.0) * 0.5, -1.0, 1.0);
  return std::acos(cosine) * 180.0 / std::numbers::pi;
}

}  // namespace glint
