// Blending SH colours along a hit list as a 3DGS viewer does: front to back with the hits'
// alphas, each Gaussian's colour for the direction from the eye to its mean, clamped at 0.
#include "render/splat_blend.h"

#include <gtest/gtest.h>

#include "math/spherical_harmonics.h"

namespace glint {
namespace {

TEST(SplatBlend, ColourIsTheBasePlusTheShTermsForTheDirection) {
  SplatColour colour;
  colour.shDegree = 1;
  colour.base = {Rgb(0.5f, 0.4f, 0.3f)};
  colour.sh = {Rgb(0.1f, 0.0f, 0.0f), Rgb(0.0f, 0.2f, 0.0f), Rgb(0.0f, 0.0f, -0.3f)};
  const Vec3f d = normalize(Vec3f(1.0f, 2.0f, -2.0f));
  float b[4];
  shBasis(d, 1, b);
  const Rgb c = splatColourAt(colour, 0, d);
  EXPECT_NEAR(c.x, 0.5f + 0.1f * b[1], 1e-6f);
  EXPECT_NEAR(c.y, 0.4f + 0.2f * b[2], 1e-6f);
  EXPECT_NEAR(c.z, 0.3f - 0.3f * b[3], 1e-6f);
}

TEST(SplatBlend, CompositesFrontToBackWithEachGaussiansOwnDirection) {
  GaussianScene scene;
  scene.resize(2);
  scene.position = {Vec3f(0, 0, -1), Vec3f(0.5f, 0, -3)};
  SplatColour colour;
  colour.shDegree = 1;
  colour.base = {Rgb(0.2f), Rgb(0.6f)};
  // Gaussian 1, seen towards +x (B_3 = -C1 x < 0), turns redder and its green goes below 0.
  colour.sh = {Rgb(0.0f), Rgb(0.0f), Rgb(0.0f), Rgb(0.0f), Rgb(0.0f), Rgb(-10.0f, 10.0f, 0.0f)};
  HitList hits;
  hits.hits = {{0, 1.0f, 0.5f}, {1, 3.0f, 0.8f}};
  const Rgb shown = blendSplatColour(scene, colour, Vec3f(0.0f), hits);
  const Rgb far = splatColourAt(colour, 1, normalize(scene.position[1]));
  ASSERT_LT(far.y, 0.0f);  // clamped to 0 before blending
  EXPECT_NEAR(shown.x, 0.5f * 0.2f + 0.5f * 0.8f * far.x, 1e-6f);
  EXPECT_NEAR(shown.y, 0.5f * 0.2f, 1e-6f);
  EXPECT_NEAR(shown.z, 0.5f * 0.2f + 0.5f * 0.8f * 0.6f, 1e-6f);
}

}  // namespace
}  // namespace glint
