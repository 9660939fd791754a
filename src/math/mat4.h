// 4x4 affine transforms in double precision (camera poses, object placement).
#pragma once

#include <array>

#include "math/vec.h"

namespace glint {

struct Mat4 {
  // Row-major: m[row][col]. Points are column vectors: p' = M p.
  std::array<std::array<double, 4>, 4> m{};

  static Mat4 identity();
  static Mat4 translation(const Vec3d& t);
  static Mat4 scale(const Vec3d& s);
  // Rotation from a unit quaternion (w, x, y, z).
  static Mat4 rotation(double w, double x, double y, double z);
  // Camera-to-world matrix in OpenGL camera axes (x right, y up, looking down -z).
  static Mat4 lookAt(const Vec3d& eye, const Vec3d& target, const Vec3d& up);

  Mat4 operator*(const Mat4& b) const;
  Vec3d transformPoint(const Vec3d& p) const;
  Vec3d transformVector(const Vec3d& v) const;
  // Transforms a normal by the inverse transpose (for non-uniform scale).
  Vec3d transformNormal(const Vec3d& n) const;
  Mat4 inverse() const;
  // True when every entry is finite and the last row is (0 0 0 1).
  bool isAffine(double tolerance = 1e-6) const;
  Vec3d column(int c) const { return {m[0][c], m[1][c], m[2][c]}; }
};

}  // namespace glint
