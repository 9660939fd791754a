// Tests of orthonormal frames built from a normal: orthonormal, right-handed, and exact
// round trips between world and local coordinates, including at and near the poles.
#include "math/frame.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "math/rng.h"
#include "math/sampling.h"

namespace glint {
namespace {

// Unit normals that stress the construction: the poles (where the sign flips), normals a
// hair away from them, the equator, and random directions.
template <typename T>
std::vector<Vec3<T>> testNormals() {
  std::vector<Vec3<T>> normals = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  for (T eps : {T(1e-3), T(1e-5), T(1e-7), T(1e-10), T(1e-20)}) {
    T z = std::sqrt(T(1) - eps * eps);
    for (T sz : {T(1), T(-1)}) {
      normals.push_back({eps, 0, sz * z});
      normals.push_back({0, -eps, sz * z});
      normals.push_back(normalize(Vec3<T>(eps, eps, sz * z)));
    }
  }
  normals.push_back({T(1), T(0), T(-0.0)});  // equator with a negative zero z
  Rng rng(21);
  for (int k = 0; k < 10000; ++k) normals.push_back(Vec3<T>(sampleUniformSphere(rng.uniform2())));
  for (Vec3<T>& n : normals) n = normalize(n);
  return normals;
}

template <typename T>
void checkFrames(T tolerance) {
  for (const Vec3<T>& n : testNormals<T>()) {
    Frame<T> f = Frame<T>::fromNormal(n);
    SCOPED_TRACE(::testing::Message() << "normal (" << n.x << ", " << n.y << ", " << n.z << ")");
    ASSERT_TRUE(isFinite(f.s) && isFinite(f.t));
    EXPECT_EQ(f.n, n);
    EXPECT_NEAR(length(f.s), T(1), tolerance);
    EXPECT_NEAR(length(f.t), T(1), tolerance);
    EXPECT_NEAR(dot(f.s, f.t), T(0), tolerance);
    EXPECT_NEAR(dot(f.s, n), T(0), tolerance);
    EXPECT_NEAR(dot(f.t, n), T(0), tolerance);
    // Right-handed: s x t = n, so local +z is the normal and local (x, y, z) keeps orientation.
    Vec3<T> c = cross(f.s, f.t);
    EXPECT_NEAR(c.x, n.x, tolerance);
    EXPECT_NEAR(c.y, n.y, tolerance);
    EXPECT_NEAR(c.z, n.z, tolerance);
  }
}

TEST(Frame, OrthonormalRightHandedFloat) { checkFrames<float>(2e-6f); }

TEST(Frame, OrthonormalRightHandedDouble) { checkFrames<double>(1e-14); }

TEST(Frame, RoundTripsBetweenWorldAndLocal) {
  Rng rng(22);
  for (const Vec3f& n : testNormals<float>()) {
    Framef f = Framef::fromNormal(n);
    Vec3f v(rng.uniform() * 4 - 2, rng.uniform() * 4 - 2, rng.uniform() * 4 - 2);
    Vec3f back = f.toWorld(f.toLocal(v));
    float tolerance = 1e-5f * (1 + length(v));
    EXPECT_NEAR(back.x, v.x, tolerance);
    EXPECT_NEAR(back.y, v.y, tolerance);
    EXPECT_NEAR(back.z, v.z, tolerance);
    // The other order, and the normal itself.
    Vec3f local = f.toLocal(f.toWorld(v));
    EXPECT_NEAR(local.x, v.x, tolerance);
    EXPECT_NEAR(local.y, v.y, tolerance);
    EXPECT_NEAR(local.z, v.z, tolerance);
    Vec3f nLocal = f.toLocal(n);
    EXPECT_NEAR(nLocal.x, 0, 2e-6f);
    EXPECT_NEAR(nLocal.y, 0, 2e-6f);
    EXPECT_NEAR(nLocal.z, 1, 2e-6f);
  }
}

TEST(Frame, PolesGiveTheExpectedAxes) {
  Framed up = Framed::fromNormal({0, 0, 1});
  EXPECT_EQ(up.s, Vec3d(1, 0, 0));
  EXPECT_EQ(up.t, Vec3d(0, 1, 0));
  Framed down = Framed::fromNormal({0, 0, -1});
  EXPECT_EQ(down.s, Vec3d(1, 0, 0));
  EXPECT_EQ(down.t, Vec3d(0, -1, 0));
}

TEST(Frame, ContinuousAcrossTheNorthPole) {
  // Nearby normals in the upper hemisphere get nearby frames (no flips a shading
  // frame interpolated across a surface would show).
  Framed a = Framed::fromNormal(normalize(Vec3d(1e-6, 0, 1)));
  Framed b = Framed::fromNormal(normalize(Vec3d(-1e-6, 1e-6, 1)));
  EXPECT_LT(length(a.s - b.s), 1e-5);
  EXPECT_LT(length(a.t - b.t), 1e-5);
}

}  // namespace
}  // namespace glint
