// 4x4 affine transforms in double precision (camera poses, object placement).
#pragma once

#include <array>

#include "core/cpu_gpu.h"
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
  GLINT_CPU_GPU Vec3d transformVector(const Vec3d& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  // Transforms a normal by the inverse transpose (for non-uniform scale).
  Vec3d transformNormal(const Vec3d& n) const;
  Mat4 inverse() const;
  // True when every entry is finite and the last row is (0 0 0 1).
  bool isAffine(double tolerance = 1e-6) const;
  GLINT_CPU_GPU Vec3d column(int c) const { return {m[0][c], m[1][c], m[2][c]}; }
};

}  // namespace glint
