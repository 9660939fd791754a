// Finite-difference tests of the quaternion VJPs (normalisation and rotation matrix) on
// random, deliberately non-normalised quaternions.
#include "math/quat_vjp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/finite_difference.h"
#include "math/rng.h"

namespace glint {
namespace {

Quatd quatFrom(const std::vector<double>& x) { return Quatd{x[0], x[1], x[2], x[3]}; }
std::vector<double> componentsOf(const Quatd& q) { return {q.w, q.x, q.y, q.z}; }

using test::symmetric;

// A random quaternion whose norm lies between 0.3 and 3.
Quatd randomQuat(Rng& rng) {
  Quatd q{symmetric(rng), symmetric(rng), symmetric(rng), symmetric(rng)};
  double scale = (0.3 + 2.7 * rng.uniformDouble()) / q.norm();
  return Quatd{q.w * scale, q.x * scale, q.y * scale, q.z * scale};
}

Mat3d randomMat3(Rng& rng) {
  Mat3d m;
  for (int i = 0; i < 3; ++i) m.m[i] = {symmetric(rng), symmetric(rng), symmetric(rng)};
  return m;
}

double frobenius(const Mat3d& a, const Mat3d& b) {
  return dot(a.m[0], b.m[0]) + dot(a.m[1], b.m[1]) + dot(a.m[2], b.m[2]);
}

TEST(QuatVjp, NormalizeMatchesFiniteDifferences) {
  Rng rng(401);
  for (int trial = 0; trial < 50; ++trial) {
    Quatd q = randomQuat(rng);
    Quatd v_u{symmetric(rng), symmetric(rng), symmetric(rng), symmetric(rng)};
    auto loss = [&](const std::vector<double>& x) {
      Quatd u = quatFrom(x).normalized();
      return v_u.w * u.w + v_u.x * u.x + v_u.y * u.y + v_u.z * u.z;
    };
    test::expectGradientNear(componentsOf(quatNormalize_vjp(q, v_u)),
                             test::centralGradient(loss, componentsOf(q)), 1e-6, "normalize");
  }
}

TEST(QuatVjp, NormalizeOfZeroIsZero) {
  Quatd v = quatNormalize_vjp(Quatd{0, 0, 0, 0}, Quatd{1, 2, 3, 4});
  EXPECT_EQ(v.w, 0.0);
  EXPECT_EQ(v.x, 0.0);
  EXPECT_EQ(v.y, 0.0);
  EXPECT_EQ(v.z, 0.0);
}

TEST(QuatVjp, RotationMatchesFiniteDifferences) {
  Rng rng(402);
  for (int trial = 0; trial < 50; ++trial) {
    Quatd q = randomQuat(rng);
    Mat3d v_R = randomMat3(rng);
    auto loss = [&](const std::vector<double>& x) { return frobenius(v_R, quatToRotation(quatFrom(x))); };
    test::expectGradientNear(componentsOf(quatToRotation_vjp(q, v_R)),
                             test::centralGradient(loss, componentsOf(q)), 1e-6, "rotation");
  }
}

// Scaling q does not change R, so the adjoint is orthogonal to q.
TEST(QuatVjp, RotationAdjointIsOrthogonalToQ) {
  Rng rng(403);
  for (int trial = 0; trial < 20; ++trial) {
    Quatd q = randomQuat(rng);
    Quatd v = quatToRotation_vjp(q, randomMat3(rng));
    EXPECT_NEAR(v.w * q.w + v.x * q.x + v.y * q.y + v.z * q.z, 0.0, 1e-12);
  }
}

TEST(QuatVjp, FloatAgreesWithDouble) {
  Rng rng(404);
  Quatd q = randomQuat(rng);
  Mat3d v_R = randomMat3(rng);
  Quatf qf{float(q.w), float(q.x), float(q.y), float(q.z)};
  Mat3f v_Rf;
  for (int i = 0; i < 3; ++i) v_Rf.m[i] = Vec3f(v_R.m[i]);
  Mat3d v_Rd;
  for (int i = 0; i < 3; ++i) v_Rd.m[i] = Vec3d(v_Rf.m[i]);
  Quatd vd = quatToRotation_vjp(Quatd{qf.w, qf.x, qf.y, qf.z}, v_Rd);
  Quatf vf = quatToRotation_vjp(qf, v_Rf);
  double scale = std::sqrt(vd.w * vd.w + vd.x * vd.x + vd.y * vd.y + vd.z * vd.z);
  EXPECT_NEAR(vf.w, vd.w, 1e-5 * scale);
  EXPECT_NEAR(vf.x, vd.x, 1e-5 * scale);
  EXPECT_NEAR(vf.y, vd.y, 1e-5 * scale);
  EXPECT_NEAR(vf.z, vd.z, 1e-5 * scale);
}

}  // namespace
}  // namespace glint
