// The real spherical-harmonics basis of degree <= 3 exactly as 3D Gaussian Splatting
// evaluates view-dependent colour (Kerbl et al. 2023, utils/sh_utils.py, eval_sh), so that
// coefficients fitted or written here mean the same thing in every 3DGS viewer.
#pragma once

#include <array>

#include "math/vec.h"

namespace glint {

constexpr int kMaxShDegree = 3;
constexpr int kMaxShCoefficients = 16;  // (kMaxShDegree + 1)^2

// Coefficients per colour channel up to `degree`, the constant (DC) term included.
constexpr int shCoefficientCount(int degree) { return (degree + 1) * (degree + 1); }

// B_k(d) for k < shCoefficientCount(degree), d a unit direction from the viewer towards the
// Gaussian. 3DGS's colour is 0.5 + sum_k f_k B_k(d), clamped at 0; B_0 = Y_0^0, and each
// higher B_k is the real harmonic Y_l^m with 3DGS's sign convention (for l = 1:
// -C1 y, C1 z, -C1 x). Entries from shCoefficientCount(degree) on are left untouched.
template <typename T>
void shBasis(const Vec3<T>& d, int degree, T* basis) {
  const T x = d.x, y = d.y, z = d.z;
  basis[0] = T(0.28209479177387814);
  if (degree < 1) return;
  constexpr T c1 = T(0.4886025119029199);
  basis[1] = -c1 * y;
  basis[2] = c1 * z;
  basis[3] = -c1 * x;
  if (degree < 2) return;
  const T xx = x * x, yy = y * y, zz = z * z;
  basis[4] = T(1.0925484305920792) * x * y;
  basis[5] = T(-1.0925484305920792) * y * z;
  basis[6] = T(0.31539156525252005) * (2 * zz - xx - yy);
  basis[7] = T(-1.0925484305920792) * x * z;
  basis[8] = T(0.5462742152960396) * (xx - yy);
  if (degree < 3) return;
  basis[9] = T(-0.5900435899266435) * y * (3 * xx - yy);
  basis[10] = T(2.890611442640554) * x * y * z;
  basis[11] = T(-0.4570457994644658) * y * (4 * zz - xx - yy);
  basis[12] = T(0.3731763325901154) * z * (2 * zz - 3 * xx - 3 * yy);
  basis[13] = T(-0.4570457994644658) * x * (4 * zz - xx - yy);
  basis[14] = T(1.445305721320277) * z * (xx - yy);
  basis[15] = T(-0.5900435899266435) * x * (xx - 3 * yy);
}

// The sign B_k takes when the world turns half a turn about x, (x, y, z) -> (x, -y, -z):
// (-1)^(power of y + power of z) in its polynomial above. Formats whose axes differ from
// the PLY convention that way (.spz stores y up, z back) store f_k times this sign.
constexpr std::array<int, kMaxShCoefficients> kShSignUnderTurnAboutX = {
    +1,                               // 1
    -1, -1, +1,                       // y, z, x
    -1, +1, +1, -1, +1,               // xy, yz, 2zz-xx-yy, xz, xx-yy
    -1, +1, -1, -1, +1, -1, +1};      // y(.), xyz, y(.), z(.), x(.), z(xx-yy), x(.)

}  // namespace glint
