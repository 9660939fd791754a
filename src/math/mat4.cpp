// 4x4 affine transform construction, products and inversion.
#include "math/mat4.h"

#include <cmath>

namespace glint {

Mat4 Mat4::identity() {
  Mat4 r;
  for (int i = 0; i < 4; ++i) r.m[i][i] = 1.0;
  return r;
}

Mat4 Mat4::translation(const Vec3d& t) {
  Mat4 r = identity();
  r.m[0][3] = t.x;
  r.m[1][3] = t.y;
  r.m[2][3] = t.z;
  return r;
}

Mat4 Mat4::scale(const Vec3d& s) {
  Mat4 r = identity();
  r.m[0][0] = s.x;
  r.m[1][1] = s.y;
  r.m[2][2] = s.z;
  return r;
}

Mat4 Mat4::rotation(double w, double x, double y, double z) {
  double n = std::sqrt(w * w + x * x + y * y + z * z);
  w /= n, x /= n, y /= n, z /= n;
  Mat4 r = identity();
  r.m[0][0] = 1 - 2 * (y * y + z * z);
  r.m[0][1] = 2 * (x * y - w * z);
  r.m[0][2] = 2 * (x * z + w * y);
  r.m[1][0] = 2 * (x * y + w * z);
  r.m[1][1] = 1 - 2 * (x * x + z * z);
  r.m[1][2] = 2 * (y * z - w * x);
  r.m[2][0] = 2 * (x * z - w * y);
  r.m[2][1] = 2 * (y * z + w * x);
  r.m[2][2] = 1 - 2 * (x * x + y * y);
  return r;
}

Mat4 Mat4::lookAt(const Vec3d& eye, const Vec3d& target, const Vec3d& up) {
  Vec3d back = normalize(eye - target);  // camera +z points away from what it looks at
  Vec3d right = normalize(cross(up, back));
  if (length(right) == 0) right = normalize(cross(Vec3d(0, 0, 1), back));
  Vec3d trueUp = cross(back, right);
  Mat4 r = identity();
  for (int i = 0; i < 3; ++i) {
    r.m[i][0] = right[i];
    r.m[i][1] = trueUp[i];
    r.m[i][2] = back[i];
    r.m[i][3] = eye[i];
  }
  return r;
}

Mat4 Mat4::operator*(const Mat4& b) const {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += m[i][k] * b.m[k][j];
      r.m[i][j] = s;
    }
  return r;
}

Vec3d Mat4::transformPoint(const Vec3d& p) const {
  return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
          m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
          m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
}

Vec3d Mat4::transformNormal(const Vec3d& n) const {
  Mat4 inv = inverse();
  return {inv.m[0][0] * n.x + inv.m[1][0] * n.y + inv.m[2][0] * n.z,
          inv.m[0][1] * n.x + inv.m[1][1] * n.y + inv.m[2][1] * n.z,
          inv.m[0][2] * n.x + inv.m[1][2] * n.y + inv.m[2][2] * n.z};
}

Mat4 Mat4::inverse() const {
  // General 4x4 inverse by Gauss-Jordan elimination with partial pivoting.
  double a[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      a[i][j] = m[i][j];
      a[i][j + 4] = (i == j) ? 1.0 : 0.0;
    }
  for (int col = 0; col < 4; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 4; ++r)
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    if (pivot != col)
      for (int j = 0; j < 8; ++j) std::swap(a[col][j], a[pivot][j]);
    double p = a[col][col];
    if (p == 0) return Mat4{};  // singular: all zeros
    for (int j = 0; j < 8; ++j) a[col][j] /= p;
    for (int r = 0; r < 4; ++r) {
      if (r == col) continue;
      double f = a[r][col];
      for (int j = 0; j < 8; ++j) a[r][j] -= f * a[col][j];
    }
  }
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = a[i][j + 4];
  return r;
}

bool Mat4::isAffine(double tolerance) const {
  for (const auto& row : m)
    for (double v : row)
      if (!std::isfinite(v)) return false;
  return std::abs(m[3][0]) <= tolerance && std::abs(m[3][1]) <= tolerance && std::abs(m[3][2]) <= tolerance &&
         std::abs(m[3][3] - 1.0) <= tolerance;
}

}  // namespace glint
