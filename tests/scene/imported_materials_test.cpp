// Imported material defaults: the shortest axis of a rotated Gaussian, a median centre that
// outliers do not move, and normals turned away from it.
#include "scene/imported_materials.h"

#include <gtest/gtest.h>

#include <cmath>

#include "math/quat.h"

namespace glint {
namespace {

void expectNear(const Vec3f& a, const Vec3f& b) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], 1e-6) << k;
}

TEST(ImportedMaterials, ShortestAxisFollowsTheRotationAndTheSmallestScale) {
  const Quatf identity{1, 0, 0, 0};
  expectNear(shortestAxis(identity, {-1.0f, -2.0f, -3.0f}), {0, 0, 1});
  expectNear(shortestAxis(identity, {-5.0f, -2.0f, -3.0f}), {1, 0, 0});
  expectNear(shortestAxis(identity, {-2.0f, -2.0f, -2.0f}), {1, 0, 0});  // ties: the first
  // 90 degrees about z takes local x to world y; an unnormalised quaternion is normalised.
  const Quatf aboutZ = quatFromAxisAngle(Vec3f(0, 0, 1), 0.5f * 3.14159265f);
  expectNear(shortestAxis(Quatf{3 * aboutZ.w, 3 * aboutZ.x, 3 * aboutZ.y, 3 * aboutZ.z}, {-5.0f, 0.0f, 0.0f}),
             {0, 1, 0});
}

TEST(ImportedMaterials, NormalsFaceAwayFromTheMedianPosition) {
  GaussianScene scene;
  scene.resize(5);
  scene.position = {{0, 0, 1}, {0, 0, -1}, {0.5f, 0, 0}, {-0.5f, 0, 0}, {1000, 1000, 1000}};
  for (size_t i = 0; i < scene.size(); ++i) scene.logScale[i] = {-1.0f, -1.0f, -4.0f};  // flat in z
  scene.logScale[2] = scene.logScale[3] = {-4.0f, -1.0f, -1.0f};                        // flat in x
  // One far outlier does not move the median as it would the mean.
  expectNear(medianPosition(scene), {0, 0, 0});
  setShortestAxisNormals(scene, medianPosition(scene));
  expectNear(scene.normal[0], {0, 0, 1});
  expectNear(scene.normal[1], {0, 0, -1});
  expectNear(scene.normal[2], {1, 0, 0});
  expectNear(scene.normal[3], {-1, 0, 0});
  EXPECT_EQ(medianPosition(GaussianScene{}), Vec3f(0.0f));
}

}  // namespace
}  // namespace glint
