// Finite-difference test of the matrix-vector product VJP.
#include "math/mat3_vjp.h"

#include <gtest/gtest.h>

#include <vector>

#include "common/finite_difference.h"
#include "math/rng.h"

namespace glint {
namespace {

using test::symmetric;

TEST(Mat3Vjp, MatVecMatchesFiniteDifferences) {
  Rng rng(411);
  for (int trial = 0; trial < 20; ++trial) {
    // Parameters: the 9 entries of M (row by row), then x.
    std::vector<double> params(12);
    for (double& p : params) p = 3 * symmetric(rng);
    Vec3d v_y{symmetric(rng), symmetric(rng), symmetric(rng)};
    auto unpack = [](const std::vector<double>& p, Mat3d* M, Vec3d* x) {
      for (int i = 0; i < 3; ++i) M->m[i] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
      *x = {p[9], p[10], p[11]};
    };
    auto loss = [&](const std::vector<double>& p) {
      Mat3d M;
      Vec3d x;
      unpack(p, &M, &x);
      return dot(v_y, M * x);
    };
    Mat3d M;
    Vec3d x;
    unpack(params, &M, &x);
    Mat3d v_M = zeroMat3<double>();
    Vec3d v_x;
    matVec_vjp(M, x, v_y, &v_M, &v_x);
    std::vector<double> analytic;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) analytic.push_back(v_M.m[i][j]);
    for (int j = 0; j < 3; ++j) analytic.push_back(v_x[j]);
    test::expectGradientNear(analytic, test::centralGradient(loss, params), 1e-6, "M x");
  }
}

TEST(Mat3Vjp, AccumulatesIntoExistingAdjoints) {
  Mat3d M;  // identity
  Mat3d v_M = zeroMat3<double>();
  v_M.m[0][0] = 1;
  Vec3d v_x(1.0);
  matVec_vjp(M, Vec3d(2.0, 0.0, 0.0), Vec3d(3.0, 0.0, 0.0), &v_M, &v_x);
  EXPECT_EQ(v_M.m[0][0], 7.0);
  EXPECT_EQ(v_M.m[1][1], 0.0);
  EXPECT_EQ(v_x.x, 4.0);
  EXPECT_EQ(v_x.y, 1.0);
}

}  // namespace
}  // namespace glint
