// The reference tracer against closed-form answers: response of a single Gaussian, the
// closest approach of a rotated anisotropic one, ordering, termination, the exact tail.
#include "raytrace/reference/reference_tracer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "math/rng.h"

namespace glint {
namespace {

// Appends one Gaussian; scale is the standard deviation per local axis.
void addGaussian(GaussianScene& scene, Vec3f position, Vec3f scale, float opacity, Rgb colour,
                 Quatf rotation = Quatf{}) {
  size_t i = scene.size();
  scene.resize(i + 1);
  scene.position[i] = position;
  scene.logScale[i] = {std::log(scale.x), std::log(scale.y), std::log(scale.z)};
  scene.rotation[i] = rotation;
  scene.opacityLogit[i] = logit(opacity);
  scene.diffuse[i] = colour;
  scene.normal[i] = {0, 0, 1};
  scene.roughness[i] = 0.25f;
  scene.f0[i] = Rgb(0.04f);
}

TEST(ReferenceTracer, SingleIsotropicGaussianHasTheClosedFormResponse) {
  GaussianScene scene;
  const float sigma = 0.5f, opacity = 0.8f, b = 0.3f;
  addGaussian(scene, {0, b, 0}, Vec3f(sigma), opacity, Rgb(1.0f, 0.5f, 0.25f));
  TraceSettings settings;
  settings.kernelPower = 1.0f;
  ReferenceTracer tracer;
  tracer.build(scene, settings);
  HitList hits;
  RayResult r = tracer.trace({{0, 0, -5}, {0, 0, 1}}, &hits);
  double alpha = 0.9999 * opacity * std::exp(-0.5 * (b * b) / (sigma * sigma));
  ASSERT_EQ(r.hitCount, 1);
  EXPECT_NEAR(r.diffuse.x, alpha, 1e-6);
  EXPECT_NEAR(r.diffuse.y, 0.5 * alpha, 1e-6);
  EXPECT_NEAR(r.depth, 5.0 * alpha, 1e-5);  // the peak is at t = 5
  EXPECT_NEAR(r.transmittance, 1 - alpha, 1e-6);
  EXPECT_NEAR(r.normalLength, alpha, 1e-6);
  ASSERT_EQ(hits.hits.size(), 1u);
  EXPECT_NEAR(hits.hits[0].alpha, alpha, 1e-6);
}

TEST(ReferenceTracer, RotatedAnisotropicGaussianRespondsAtTheMahalanobisClosestApproach) {
  Rng rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    GaussianScene scene;
    Quatf q{rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f};
    Vec3f scale(0.2f + rng.uniform(), 0.2f + rng.uniform(), 0.2f + rng.uniform());
    Vec3f mean(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f);
    addGaussian(scene, mean, scale, 0.9f, Rgb(1.0f), q);
    for (float p : {1.0f, 3.0f}) {
      TraceSettings settings;
      settings.kernelPower = p;
      ReferenceTracer tracer;
      tracer.build(scene, settings);
      Vec3f origin(-4, rng.uniform() * 0.6f - 0.3f, rng.uniform() * 0.6f - 0.3f);
      Vec3f dir = normalize(Vec3f(1, 0.1f * (rng.uniform() - 0.5f), 0.1f * (rng.uniform() - 0.5f)));
      HitList hits;
      RayResult r = tracer.trace({origin, dir}, &hits);
      // Brute force: the smallest Mahalanobis distance over a fine sampling of the ray.
      Mat3d rt = quatToRotation(Quatd{q.w, q.x, q.y, q.z}).transposed();
      double best = 1e30, bestT = 0;
      for (int k = 0; k <= 80000; ++k) {
        double t = 8.0 * k / 80000;
        Vec3d local = rt * (Vec3d(origin) + Vec3d(dir) * t - Vec3d(mean));
        Vec3d u(local.x / scale.x, local.y / scale.y, local.z / scale.z);
        if (dot(u, u) < best) best = dot(u, u), bestT = t;
      }
      double response = std::exp(-std::pow(best, double(p)) / (2 * p));
      if (0.9999 * 0.9 * response < settings.alphaMin) {
        EXPECT_EQ(r.hitCount, 0);
        continue;
      }
      ASSERT_EQ(hits.hits.size(), 1u);
      EXPECT_NEAR(hits.hits[0].alpha, 0.9999 * 0.9 * response, 2e-4);
      EXPECT_NEAR(hits.hits[0].t, bestT, 2e-3);
    }
  }
}

TEST(ReferenceTracer, HitsCompositeFrontToBackWhateverTheirIndex) {
  GaussianScene scene;
  addGaussian(scene, {0, 0, 3}, Vec3f(0.2f), 0.5f, Rgb(0, 0, 1));  // far, index 0
  addGaussian(scene, {0, 0, 1}, Vec3f(0.2f), 0.5f, Rgb(1, 0, 0));  // near, index 1
  ReferenceTracer tracer;
  tracer.build(scene, TraceSettings{});
  HitList hits;
  RayResult r = tracer.trace({{0, 0, 0}, {0, 0, 1}}, &hits);
  double a = 0.9999 * 0.5;
  ASSERT_EQ(hits.hits.size(), 2u);
  EXPECT_EQ(hits.hits[0].id, 1u);
  EXPECT_EQ(hits.hits[1].id, 0u);
  EXPECT_NEAR(r.diffuse.x, a, 1e-6);
  EXPECT_NEAR(r.diffuse.z, (1 - a) * a, 1e-6);
  EXPECT_NEAR(r.depth, a * 1 + (1 - a) * a * 3, 1e-5);
  EXPECT_NEAR(r.transmittance, (1 - a) * (1 - a), 1e-6);
}

TEST(ReferenceTracer, StopsBelowTheMinimumTransmittanceAndEstimatesTheTail) {
  GaussianScene scene;
  for (int i = 0; i < 10; ++i) addGaussian(scene, {0, 0, 1.0f + i}, Vec3f(0.1f), 0.6f, Rgb(1.0f));
  TraceSettings settings;
  settings.minTransmittance = 0.01f;
  ReferenceTracer tracer;
  tracer.build(scene, settings);
  RayResult r = tracer.trace({{0, 0, 0}, {0, 0, 1}});
  double a = 0.9999 * 0.6;
  // (1 - a)^5 = 0.0103 > 0.01, (1 - a)^6 = 0.0041: six hits.
  EXPECT_EQ(r.hitCount, 6);
  EXPECT_TRUE(r.truncated);
  // Without the exact tail, the tail estimate takes the rest as opaque: T_f = 0 and the
  // light is the composited part's mean (white here).
  EXPECT_EQ(r.transmittance, 0.0f);
  EXPECT_NEAR(r.diffuse.x, 1.0, 1e-6);

  settings.exactTail = true;
  tracer.build(scene, settings);
  RayResult tail = tracer.trace({{0, 0, 0}, {0, 0, 1}});
  double Ti = std::pow(1 - a, 6), Tf = std::pow(1 - a, 10);
  EXPECT_NEAR(tail.transmittance, Tf, 1e-7);
  // The truncated light is estimated as the mean of the composited part (white here).
  EXPECT_NEAR(tail.diffuse.x, (1 - Ti) + (Ti - Tf), 1e-6);
}

TEST(ReferenceTracer, RaysStartingInsideAGaussianAndGaussiansBehindTheOrigin) {
  GaussianScene scene;
  addGaussian(scene, {0, 0, -0.1f}, Vec3f(0.5f), 0.5f, Rgb(1.0f));  // the origin is inside it
  addGaussian(scene, {0, 0, -3.0f}, Vec3f(0.2f), 0.9f, Rgb(1.0f));  // entirely behind
  ReferenceTracer tracer;
  tracer.build(scene, TraceSettings{});
  HitList hits;
  RayResult r = tracer.trace({{0, 0, 0}, {0, 0, 1}, 0.0f}, &hits);
  ASSERT_EQ(hits.hits.size(), 1u);
  EXPECT_EQ(hits.hits[0].id, 0u);
  // The peak (t = -0.1) lies before tMin: the key is clamped to tMin.
  EXPECT_FLOAT_EQ(hits.hits[0].t, 0.0f);
  EXPECT_NEAR(hits.hits[0].alpha, 0.9999 * 0.5, 1e-6);  // the ray passes through the mean
  EXPECT_EQ(r.depth, 0.0f);
}

TEST(ReferenceTracer, TheProxyBoundsExactlyTheHitsThatReachAlphaMin) {
  for (float p : {1.0f, 2.0f, 3.0f})
    for (float opacity : {0.01f, 0.3f, 0.99f}) {
      TraceSettings s;
      s.kernelPower = p;
      double r = proxyRadius(double(opacity), s);
      if (0.9999 * opacity <= s.alphaMin) {
        EXPECT_EQ(r, 0.0);
        continue;
      }
      double alphaAtBoundary = 0.9999 * opacity * gaussianResponse(r * r, double(p));
      EXPECT_NEAR(alphaAtBoundary, s.alphaMin, 1e-9) << p << " " << opacity;
    }
}

}  // namespace
}  // namespace glint
