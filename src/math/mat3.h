// 3x3 matrices in float or double: rotations and the Gaussians' local frames.
#pragma once

#include "core/cpu_gpu.h"
#include "math/vec.h"

namespace glint {

template <typename T>
struct Mat3 {
  // Rows: m[r] is row r. Vectors are columns: v' = M v.
  Vec3<T> m[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  GLINT_CPU_GPU Vec3<T> operator*(const Vec3<T>& v) const { return {dot(m[0], v), dot(m[1], v), dot(m[2], v)}; }
  GLINT_CPU_GPU Mat3 operator*(const Mat3& b) const {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r.m[i][j] = m[i].x * b.m[0][j] + m[i].y * b.m[1][j] + m[i].z * b.m[2][j];
    return r;
  }
  GLINT_CPU_GPU Mat3 transposed() const {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r.m[i][j] = m[j][i];
    return r;
  }
  GLINT_CPU_GPU Vec3<T> column(int c) const { return {m[0][c], m[1][c], m[2][c]}; }
  // M^T v without forming the transpose.
  GLINT_CPU_GPU Vec3<T> transposeTimes(const Vec3<T>& v) const { return m[0] * v.x + m[1] * v.y + m[2] * v.z; }
};

using Mat3f = Mat3<float>;
using Mat3d = Mat3<double>;

}  // namespace glint
