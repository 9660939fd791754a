// Tests of 4x4 affine transforms: camera frames, inverses, quaternion rotations, normal
// transformation under non-uniform scale, and the affinity check.
#include "math/mat4.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "math/rng.h"

namespace glint {
namespace {

double determinant3(const Mat4& a) {
  const auto& m = a.m;
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// Largest entry-wise difference.
double maxDifference(const Mat4& a, const Mat4& b) {
  double d = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) d = std::max(d, std::abs(a.m[i][j] - b.m[i][j]));
  return d;
}

// The upper-left 3x3 block has orthonormal columns.
void expectOrthonormal(const Mat4& r, double tolerance) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(dot(r.column(i), r.column(j)), i == j ? 1.0 : 0.0, tolerance) << "columns " << i << ", " << j;
}

void expectNear(const Vec3d& a, const Vec3d& b, double tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

Vec3d randomVector(Rng& rng, double scale) {
  return Vec3d(rng.uniformDouble() * 2 - 1, rng.uniformDouble() * 2 - 1, rng.uniformDouble() * 2 - 1) * scale;
}

// Rotation from a random quaternion, uniform over rotations: rejection sampling in the 4-ball.
Mat4 randomRotationMatrix(Rng& rng) {
  while (true) {
    double q[4];
    double n2 = 0;
    for (double& c : q) {
      c = rng.uniformDouble() * 2 - 1;
      n2 += c * c;
    }
    if (n2 > 1e-3 && n2 <= 1) return Mat4::rotation(q[0], q[1], q[2], q[3]);
  }
}

// A random affine map: translation x rotation x scale (scales in [0.2, 3] with random signs).
Mat4 randomAffine(Rng& rng) {
  Vec3d s;
  for (int i = 0; i < 3; ++i) s[i] = (0.2 + 2.8 * rng.uniformDouble()) * (rng.uniform() < 0.5f ? -1 : 1);
  return Mat4::translation(randomVector(rng, 10)) * randomRotationMatrix(rng) * Mat4::scale(s);
}

TEST(Mat4, IdentityAndProducts) {
  Mat4 t = Mat4::translation({1, 2, 3});
  Mat4 s = Mat4::scale({2, 3, 4});
  expectNear((t * s).transformPoint({1, 1, 1}), {3, 5, 7}, 1e-12);  // scale first, then translate
  expectNear((s * t).transformPoint({1, 1, 1}), {4, 9, 16}, 1e-12);
  expectNear(t.transformVector({1, 1, 1}), {1, 1, 1}, 1e-12);       // vectors ignore translation
  EXPECT_EQ(maxDifference(Mat4::identity() * t, t), 0.0);
}

TEST(Mat4, LookAtBuildsACameraFrame) {
  Rng rng(11);
  for (int k = 0; k < 200; ++k) {
    Vec3d eye = randomVector(rng, 5), target = randomVector(rng, 5);
    if (length(eye - target) < 0.1) continue;
    Mat4 c = Mat4::lookAt(eye, target, {0, 1, 0});
    expectOrthonormal(c, 1e-12);
    EXPECT_NEAR(determinant3(c), 1.0, 1e-12);  // right-handed: x right, y up, z back
    expectNear(c.column(3), eye, 1e-12);
    expectNear(c.transformPoint({0, 0, 0}), eye, 1e-12);
    Vec3d forward = normalize(target - eye);
    expectNear(c.transformVector({0, 0, -1}), forward, 1e-12);
    // The target lies on the camera's -z axis at its distance.
    expectNear(c.inverse().transformPoint(target), {0, 0, -length(target - eye)}, 1e-9);
    // Up stays up: the camera's y axis leans towards world +y, its x axis stays horizontal.
    EXPECT_GE(c.column(1).y, -1e-12);
    EXPECT_NEAR(c.column(0).y, 0.0, 1e-12);
    EXPECT_TRUE(c.isAffine());
  }
}

TEST(Mat4, LookAtAlongTheUpVectorStaysOrthonormal) {
  for (Vec3d target : {Vec3d(0, -3, 0), Vec3d(0, 3, 0)}) {
    Mat4 c = Mat4::lookAt({0, 0, 0}, target, {0, 1, 0});
    expectOrthonormal(c, 1e-12);
    EXPECT_NEAR(determinant3(c), 1.0, 1e-12);
    expectNear(c.transformVector({0, 0, -1}), normalize(target), 1e-12);
  }
}

TEST(Mat4, InverseOfRandomAffineMatrices) {
  Rng rng(12);
  for (int k = 0; k < 500; ++k) {
    Mat4 m = randomAffine(rng);
    Mat4 inv = m.inverse();
    EXPECT_LT(maxDifference(inv * m, Mat4::identity()), 1e-12) << "matrix " << k;
    EXPECT_LT(maxDifference(m * inv, Mat4::identity()), 1e-12) << "matrix " << k;
    EXPECT_TRUE(inv.isAffine());
    Vec3d p = randomVector(rng, 4);
    expectNear(inv.transformPoint(m.transformPoint(p)), p, 1e-12);
  }
}

TEST(Mat4, InverseOfSingularMatrixIsZero) {
  Mat4 flat = Mat4::scale({1, 0, 1});
  EXPECT_EQ(maxDifference(flat.inverse(), Mat4{}), 0.0);
}

TEST(Mat4, RotationFromQuaternionIsProperOrthonormal) {
  Rng rng(13);
  for (int k = 0; k < 500; ++k) {
    Mat4 r = randomRotationMatrix(rng);
    expectOrthonormal(r, 1e-12);
    EXPECT_NEAR(determinant3(r), 1.0, 1e-12);
    EXPECT_TRUE(r.isAffine());
    expectNear(r.column(3), {0, 0, 0}, 0);
  }
}

TEST(Mat4, RotationMatchesKnownQuarterTurns) {
  // q = (cos 45deg, sin 45deg * axis): a right-handed quarter turn about the axis.
  double h = std::sqrt(0.5);
  Mat4 aboutZ = Mat4::rotation(h, 0, 0, h);
  expectNear(aboutZ.transformVector({1, 0, 0}), {0, 1, 0}, 1e-15);
  expectNear(aboutZ.transformVector({0, 1, 0}), {-1, 0, 0}, 1e-15);
  expectNear(aboutZ.transformVector({0, 0, 1}), {0, 0, 1}, 1e-15);
  Mat4 aboutX = Mat4::rotation(h, h, 0, 0);
  expectNear(aboutX.transformVector({0, 1, 0}), {0, 0, 1}, 1e-15);
  Mat4 aboutY = Mat4::rotation(h, 0, h, 0);
  expectNear(aboutY.transformVector({0, 0, 1}), {1, 0, 0}, 1e-15);
  // q and -q are the same rotation; an unnormalised quaternion is normalised first.
  EXPECT_LT(maxDifference(Mat4::rotation(-h, 0, 0, -h), aboutZ), 1e-15);
  EXPECT_LT(maxDifference(Mat4::rotation(3, 0, 0, 3), aboutZ), 1e-15);
  EXPECT_EQ(maxDifference(Mat4::rotation(1, 0, 0, 0), Mat4::identity()), 0.0);
}

TEST(Mat4, TransformNormalStaysPerpendicularUnderNonUniformScale) {
  Rng rng(14);
  for (int k = 0; k < 300; ++k) {
    Mat4 m = Mat4::translation(randomVector(rng, 3)) * randomRotationMatrix(rng) * Mat4::scale({0.3, 2.5, 7.0});
    // A surface point's normal and two tangents spanning its plane.
    Vec3d n = normalize(randomVector(rng, 1) + Vec3d(0, 0, 1e-3));
    Vec3d helper = std::abs(n.x) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
    Vec3d t1 = normalize(cross(n, helper)), t2 = cross(n, t1);
    Vec3d nT = normalize(m.transformNormal(n));
    EXPECT_NEAR(dot(nT, normalize(m.transformVector(t1))), 0.0, 1e-12);
    EXPECT_NEAR(dot(nT, normalize(m.transformVector(t2))), 0.0, 1e-12);
    // Still the outward side: the transformed normal agrees with the transformed tangent cross product.
    EXPECT_GT(dot(nT, cross(m.transformVector(t1), m.transformVector(t2))), 0.0);
  }
  // The naive transform (same as vectors) would fail: check the test can tell.
  Mat4 s = Mat4::scale({1, 4, 1});
  Vec3d n = normalize(Vec3d(1, 1, 0)), t = normalize(Vec3d(1, -1, 0));
  EXPECT_GT(std::abs(dot(normalize(s.transformVector(n)), normalize(s.transformVector(t)))), 0.1);
}

TEST(Mat4, IsAffineRejectsBadLastRowAndNonFiniteEntries) {
  Mat4 m = Mat4::translation({1, 2, 3}) * Mat4::rotation(0.5, 0.5, 0.5, 0.5);
  EXPECT_TRUE(m.isAffine());
  Mat4 projective = m;
  projective.m[3][2] = -1;
  EXPECT_FALSE(projective.isAffine());
  Mat4 scaledW = m;
  scaledW.m[3][3] = 2;
  EXPECT_FALSE(scaledW.isAffine());
  Mat4 slightlyOff = m;
  slightlyOff.m[3][0] = 1e-9;
  EXPECT_TRUE(slightlyOff.isAffine());
  EXPECT_FALSE(slightlyOff.isAffine(1e-12));
  Mat4 withNan = m;
  withNan.m[1][2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(withNan.isAffine());
  Mat4 withInf = m;
  withInf.m[0][3] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(withInf.isAffine());
  Mat4 nanLastRow = m;
  nanLastRow.m[3][3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(nanLastRow.isAffine());
  EXPECT_FALSE(Mat4{}.isAffine());  // all zeros: last row (0 0 0 0)
}

}  // namespace
}  // namespace glint
