// Cholesky solve of small symmetric positive definite systems: exact on a known system, a
// vector right-hand side solved channel by channel, and indefinite matrices refused.
#include "math/cholesky.h"

#include <gtest/gtest.h>

#include <cmath>

#include "math/vec.h"

namespace glint {
namespace {

// A = B B^T + I for a fixed B: positive definite; b = A x for a known x.
TEST(Cholesky, SolvesAPositiveDefiniteSystem) {
  constexpr int n = 6;
  double b[n][n], a[n][n] = {};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) b[i][j] = std::sin(1.3 * i + 0.7 * j + 0.2) + (i == j ? 1.5 : 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < n; ++k) a[i][j] += b[i][k] * b[j][k];
      if (i == j) a[i][j] += 1.0;
    }
  const double x[n] = {1.0, -2.0, 0.5, 3.0, -0.25, 2.0};
  double rhs[n] = {};
  Vec3d rhs3[n];
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) rhs[i] += a[i][j] * x[j];
    rhs3[i] = Vec3d(rhs[i], 2.0 * rhs[i], -rhs[i]);
  }
  ASSERT_TRUE(choleskyFactor(&a[0][0], n, n));
  choleskySolve(&a[0][0], n, n, rhs);
  choleskySolve(&a[0][0], n, n, rhs3);
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(rhs[i], x[i], 1e-10);
    EXPECT_NEAR(rhs3[i].y, 2.0 * x[i], 1e-10);
    EXPECT_NEAR(rhs3[i].z, -x[i], 1e-10);
  }
}

TEST(Cholesky, RefusesAnIndefiniteMatrix) {
  double a[2][2] = {{1.0, 2.0}, {2.0, 1.0}};  // eigenvalues 3 and -1
  EXPECT_FALSE(choleskyFactor(&a[0][0], 2, 2));
  double zero[1][1] = {{0.0}};
  EXPECT_FALSE(choleskyFactor(&zero[0][0], 1, 1));
}

}  // namespace
}  // namespace glint
