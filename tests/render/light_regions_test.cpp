// Light regions: each compact emitter of a room becomes one region bounding it, most powerful
// first, with or without a normal and whatever dimmer Gaussians touch it; a room lit evenly
// has none, and a huge bright Gaussian is no light and joins none.
#include "render/light_regions.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/gaussian_layers.h"

namespace glint {
namespace {

using test::addLayer;
using test::LayerLook;

// A 2 m floor (0.3) under a dim ceiling (0.5) at z = 1.5, without lamps.
GaussianScene dimRoom() {
  GaussianScene scene;
  LayerLook floor;
  floor.diffuse = Rgb(0.3f);
  addLayer(&scene, 0, 0, 0, 20, 20, 0.1f, floor);
  LayerLook ceiling;
  ceiling.diffuse = Rgb(0.5f);
  ceiling.normal = Vec3f(0, 0, -1);
  addLayer(&scene, 0, 0, 1.5f, 20, 20, 0.1f, ceiling);
  return scene;
}

// A square emitter (20) facing down just under the ceiling, centred on (x, 0).
void addLamp(GaussianScene* scene, float x, int count, float spacing) {
  LayerLook lamp;
  lamp.diffuse = Rgb(20.0f);
  lamp.normal = Vec3f(0, 0, -1);
  addLayer(scene, x, 0, 1.49f, count, count, spacing, lamp);
}

// The dim room with two lamps: 0.4 m wide at x = -1 and 0.2 m wide at x = 1.
GaussianScene twoLampRoom() {
  GaussianScene scene = dimRoom();
  addLamp(&scene, -1, 8, 0.05f);
  addLamp(&scene, 1, 4, 0.05f);
  return scene;
}

TEST(LightRegions, EachEmitterIsOneRegionMostPowerfulFirst) {
  const std::vector<LightRegion> regions = lightRegionsOf(twoLampRoom());
  ASSERT_EQ(regions.size(), 2u);
  EXPECT_LT(length(regions[0].centre - Vec3f(-1, 0, 1.49f)), 0.01f);
  EXPECT_LT(length(regions[1].centre - Vec3f(1, 0, 1.49f)), 0.01f);
  // The sphere holds the square (half-diagonal 0.28 and 0.14 m) and not much more.
  EXPECT_GT(regions[0].radius, 0.2f * std::sqrt(2.0f));
  EXPECT_LT(regions[0].radius, 0.45f);
  EXPECT_GT(regions[1].radius, 0.1f * std::sqrt(2.0f));
  EXPECT_LT(regions[1].radius, 0.3f);
  // Four times the area, four times the power.
  EXPECT_NEAR(regions[0].power / regions[1].power, 4.0f, 0.4f);
}

TEST(LightRegions, AHugeBrightGaussianIsNoLightAndJoinsNone) {
  GaussianScene scene = twoLampRoom();
  const size_t huge = scene.size();
  scene.resize(huge + 1);
  scene.position[huge] = Vec3f(0, 0, 1.49f);  // between the lamps, overlapping both
  scene.logScale[huge] = Vec3f(std::log(3.0f), std::log(3.0f), std::log(0.01f));
  scene.opacityLogit[huge] = logit(0.9f);
  scene.diffuse[huge] = Rgb(30.0f);
  scene.normal[huge] = Vec3f(0, 0, -1);
  const std::vector<LightRegion> regions = lightRegionsOf(scene);
  ASSERT_EQ(regions.size(), 2u);
  EXPECT_LT(regions[0].radius, 0.45f);
  EXPECT_LT(regions[1].radius, 0.3f);
}

// A trained emitter often has no normal, and dimmer Gaussians (blends, floaters above the
// ceiling) touch it: it is still a light, and its sphere holds the lamp, not them.
TEST(LightRegions, ALampWithoutANormalAndDimFloatersAboveIt) {
  GaussianScene scene = twoLampRoom();
  for (size_t i = 0; i < scene.size(); ++i)
    if (luminance(scene.diffuse[i]) > 10) scene.normal[i] = Vec3f(0.0f);
  LayerLook floater;
  floater.diffuse = Rgb(8.0f);  // 40% of the lamps'
  floater.normal = Vec3f(0.0f);
  for (int level = 1; level <= 10; ++level) addLayer(&scene, -1, 0, 1.49f + 0.05f * float(level), 1, 1, 0.05f, floater);
  const std::vector<LightRegion> regions = lightRegionsOf(scene);
  ASSERT_EQ(regions.size(), 2u);
  EXPECT_LT(length(regions[0].centre - Vec3f(-1, 0, 1.49f)), 0.01f);
  EXPECT_LT(regions[0].radius, 0.45f);
  LightRegionSettings everyMember;
  everyMember.coreFraction = 0;
  const std::vector<LightRegion> stretched = lightRegionsOf(scene, everyMember);
  ASSERT_EQ(stretched.size(), 2u);
  EXPECT_GT(stretched[0].radius, 0.5f) << "the floaters are linked to the lamp";
}

// Each light links by its own size: a lamp of large Gaussians (listed first) and one of small
// ones are one region each, whatever order the sizes come in.
TEST(LightRegions, LampsOfDifferentGaussianSizesEachMakeOneRegion) {
  GaussianScene scene = dimRoom();
  addLamp(&scene, 1, 4, 0.1f);     // 0.4 m of large Gaussians
  addLamp(&scene, -1, 8, 0.025f);  // 0.2 m of small ones
  const std::vector<LightRegion> regions = lightRegionsOf(scene);
  ASSERT_EQ(regions.size(), 2u);
  EXPECT_LT(length(regions[0].centre - Vec3f(1, 0, 1.49f)), 0.01f);
  EXPECT_LT(length(regions[1].centre - Vec3f(-1, 0, 1.49f)), 0.01f);
}

TEST(LightRegions, ARoomLitEvenlyHasNone) {
  GaussianScene scene = test::plateRoom().scene;  // a ceiling of 2 over a floor of 0.3
  EXPECT_TRUE(lightRegionsOf(scene).empty());
  LightRegionSettings off;
  off.factor = 0;
  EXPECT_TRUE(lightRegionsOf(twoLampRoom(), off).empty());
}

TEST(LightRegions, KeepsOnlyTheMostPowerful) {
  LightRegionSettings one;
  one.maxRegions = 1;
  const std::vector<LightRegion> regions = lightRegionsOf(twoLampRoom(), one);
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_LT(length(regions[0].centre - Vec3f(-1, 0, 1.49f)), 0.01f);
}

}  // namespace
}  // namespace glint
