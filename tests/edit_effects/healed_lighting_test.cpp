// The healed Gaussians' light factors against brute-force irradiance: a healed floor under an
// occluder takes the occluder's shadow, one lit like its ring keeps the ring's colour, and no
// factor is non-finite or beyond the clamp.
#include "edit_effects/healed_lighting.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <initializer_list>
#include <memory>

#include "render/brute_force_irradiance.h"
#include "render/gaussian_layers.h"

namespace glint {
namespace {

using test::bruteForceIrradiance;
using test::PlateRoom;
using test::plateRoom;
using test::tracerOf;

// The floor Gaussian nearest (x, y).
uint32_t floorAt(const PlateRoom& room, float x, float y) {
  uint32_t best = 0;
  float bestDistance = INFINITY;
  for (size_t i = room.floorBegin; i < room.floorEnd; ++i) {
    const float d = length(room.scene.position[i] - Vec3f(x, y, 0));
    if (d < bestDistance) best = uint32_t(i), bestDistance = d;
  }
  return best;
}

// One healed Gaussian at `healed` continuing the ring Gaussians at `ring`, equally weighted.
HealReport healedAt(const PlateRoom& room, Vec3f healed, std::initializer_list<Vec3f> ring) {
  HealedGaussian h;
  h.index = floorAt(room, healed.x, healed.y);
  for (const Vec3f& p : ring) {
    h.neighbours.push_back(floorAt(room, p.x, p.y));
    h.weights.push_back(1.0f / float(ring.size()));
  }
  HealReport report;
  report.healed.push_back(h);
  return report;
}

// The factor brute force gives: the irradiance at the healed Gaussian over the weighted
// irradiance at its ring.
float bruteForceFactor(const GaussianTracer& tracer, const GaussianScene& scene, const HealedGaussian& h) {
  double ring = 0;
  for (size_t m = 0; m < h.neighbours.size(); ++m)
    ring += h.weights[m] * luminance(bruteForceIrradiance(tracer, scene, h.neighbours[m], 4096));
  return float(luminance(bruteForceIrradiance(tracer, scene, h.index, 4096)) / ring);
}

const std::initializer_list<Vec3f> kOpenRing = {{0.4f, 0.4f, 0}, {-0.4f, 0.4f, 0}, {0.4f, -0.4f, 0}, {-0.4f, -0.4f, 0}};

TEST(HealedLighting, AHealedFloorUnderAnOccluderTakesItsShadow) {
  const PlateRoom room = plateRoom(0.15f);
  const std::unique_ptr<GaussianTracer> tracer = tracerOf(room.scene);
  const HealReport report = healedAt(room, {0, 0, 0}, kOpenRing);
  uint64_t rays = 0;
  const std::vector<float> factors = healedLightFactors(*tracer, room.scene, report, RelightSettings(), &rays);
  ASSERT_EQ(factors.size(), 1u);
  const float truth = bruteForceFactor(*tracer, room.scene, report.healed[0]);
  ASSERT_LT(truth, 0.7f) << "the plate should shade the healed floor";
  EXPECT_NEAR(factors[0], truth, 0.05f * truth);
  // 256 rays (64 x 4) from the healed Gaussian and from each of its 4 ring neighbours.
  EXPECT_EQ(rays, 5u * 256u);
}

TEST(HealedLighting, AHealedFloorLitLikeItsRingKeepsTheRingsColour) {
  const PlateRoom room = plateRoom(0);
  const std::unique_ptr<GaussianTracer> tracer = tracerOf(room.scene);
  const HealReport report = healedAt(room, {0.1f, 0, 0}, {{0.3f, 0.1f, 0}, {-0.2f, 0.25f, 0}, {0.05f, -0.3f, 0}});
  const std::vector<float> factors = healedLightFactors(*tracer, room.scene, report, RelightSettings(), nullptr);
  const float truth = bruteForceFactor(*tracer, room.scene, report.healed[0]);
  ASSERT_NEAR(truth, 1.0f, 0.02f);
  // The shared directions leave less noise than either irradiance alone would.
  EXPECT_NEAR(factors[0], truth, 0.01f);
}

TEST(HealedLighting, FactorsStayFiniteAndWithinTheClamp) {
  // A plate 2 mm above the floor leaves the healed Gaussian under it no light at all.
  const PlateRoom room = plateRoom(0.002f);
  const std::unique_ptr<GaussianTracer> tracer = tracerOf(room.scene);
  RelightSettings settings;
  settings.maxRatio = 16;
  HealReport report = healedAt(room, {0, 0, 0}, kOpenRing);               // dark, from a lit ring
  report.healed.push_back(healedAt(room, {0.4f, 0.4f, 0}, {{0, 0, 0}}).healed[0]);  // lit, from a dark ring
  const std::vector<float> factors = healedLightFactors(*tracer, room.scene, report, settings, nullptr);
  ASSERT_EQ(factors.size(), 2u);
  for (float f : factors) {
    EXPECT_TRUE(std::isfinite(f));
    EXPECT_GE(f, 1.0f / 16);
    EXPECT_LE(f, 16.0f);
  }
  EXPECT_LT(factors[0], 0.1f);
  // A ring that receives no light says nothing of the healed Gaussian's: the factor is 1.
  EXPECT_EQ(factors[1], 1.0f);
}

TEST(HealedLighting, NothingHealedTracesNothing) {
  const PlateRoom room = plateRoom(0.15f);
  const std::unique_ptr<GaussianTracer> tracer = tracerOf(room.scene);
  uint64_t rays = 0;
  EXPECT_TRUE(healedLightFactors(*tracer, room.scene, HealReport(), RelightSettings(), &rays).empty());
  EXPECT_EQ(rays, 0u);
}

TEST(HealedLighting, CancelFlagStopsTheTracing) {
  const PlateRoom room = plateRoom(0.15f);
  const std::unique_ptr<GaussianTracer> tracer = tracerOf(room.scene);
  std::atomic<bool> cancel = true;
  RelightSettings settings;
  settings.cancel = &cancel;
  EXPECT_THROW(healedLightFactors(*tracer, room.scene, healedAt(room, {0, 0, 0}, kOpenRing), settings, nullptr),
               RelightCancelled);
}

}  // namespace
}  // namespace glint
