// Finite-difference tests of the fused backward pass (raytrace/ray_backward.h): the
// gradient of a random linear loss of a ray's blended outputs with respect to every
// parameter of every Gaussian, against central differences of a double-precision forward
// (p = 1 and p = 3, several hits per ray, rays starting inside Gaussians, with and without
// truncation).
#include "raytrace/ray_backward.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <vector>

#include "common/double_compositor.h"
#include "common/finite_difference.h"
#include "math/rng.h"

namespace glint {
namespace {

using test::DetachedTail;
using test::Forward;
using test::Hit;
using test::kParams;
using test::Outputs;
using test::toScene;
using test::traceDouble;
using test::unpack;

double lossOf(const Outputs& out, const RayResultAdjoint& v) {
  return v.v_diffuse.x * out[0] + v.v_diffuse.y * out[1] + v.v_diffuse.z * out[2] + v.v_depth * out[3] +
         v.v_normal.x * out[4] + v.v_normal.y * out[5] + v.v_normal.z * out[6] + v.v_roughness * out[7] +
         v.v_f0.x * out[8] + v.v_f0.y * out[9] + v.v_f0.z * out[10];
}

using test::symmetric;

// Gaussians spread along the z axis in front of a ray origin at z = -3, parameters rounded
// to float (so that the float scene and the double forward agree exactly).
std::vector<double> randomSceneParams(Rng& rng, size_t n) {
  std::vector<double> x(n * kParams);
  for (size_t i = 0; i < n; ++i) {
    double* p = x.data() + i * kParams;
    p[0] = 0.6 * symmetric(rng), p[1] = 0.6 * symmetric(rng), p[2] = 4.0 * rng.uniformDouble();
    for (int k = 3; k < 7; ++k) p[k] = symmetric(rng);
    p[3] += 1.2;  // keep the quaternion away from zero
    for (int k = 7; k < 10; ++k) p[k] = std::log(0.25 + 0.5 * rng.uniformDouble());
    p[10] = -1.0 + 3.5 * rng.uniformDouble();
    for (int k = 11; k < 21; ++k) p[k] = rng.uniformDouble();
    for (int k = 14; k < 17; ++k) p[k] = symmetric(rng);
    for (int k = 0; k < kParams; ++k) p[k] = double(float(p[k]));
  }
  return x;
}

RayResultAdjoint randomAdjoint(Rng& rng) {
  RayResultAdjoint v;
  v.v_diffuse = Rgb(float(symmetric(rng)), float(symmetric(rng)), float(symmetric(rng)));
  v.v_depth = float(symmetric(rng));
  v.v_normal = Vec3f(float(symmetric(rng)), float(symmetric(rng)), float(symmetric(rng)));
  v.v_roughness = float(symmetric(rng));
  v.v_f0 = Rgb(float(symmetric(rng)), float(symmetric(rng)), float(symmetric(rng)));
  return v;
}

// The backward pass's gradient of every parameter (zero for Gaussians not hit).
std::vector<double> analyticGradient(const std::vector<double>& x, const TraceRay& ray, const TraceSettings& s,
                                     const Forward& f, const RayResultAdjoint& v) {
  GaussianScene scene = toScene(x);
  HitList hits = test::hitListOf(f);
  RayResult result;
  result.truncated = f.truncated;
  result.transmittance = float(f.finalT);
  std::vector<double> gradient(x.size(), 0.0);
  RayBackwardScratch<double> scratch;
  int calls = 0;
  backwardRay<double>(scene, s, ray, hits, result, v, scratch, [&](uint32_t id, const HitGradient<double>& g) {
    test::accumulate(&gradient, id, g);
    ++calls;
  });
  EXPECT_EQ(calls, int(f.composited.size()));
  return gradient;
}

struct Case {
  std::vector<double> x;
  TraceRay ray;
  Forward forward;
};

// Draws scenes and rays until one is safely away from every discontinuity of the forward
// (proxy and alphaMin cut-offs, order swaps, the termination threshold) and has at least
// minHits composited hits.
Case drawCase(Rng& rng, const TraceSettings& s, size_t minHits, bool wantTruncated, bool startInside) {
  for (int attempt = 0; attempt < 5000; ++attempt) {
    Case c;
    c.x = randomSceneParams(rng, 8);
    Vec3f target(float(0.3 * symmetric(rng)), float(0.3 * symmetric(rng)), 4.0f);
    c.ray.origin = Vec3f(float(0.3 * symmetric(rng)), float(0.3 * symmetric(rng)), -3.0f);
    if (startInside) c.ray.origin = Vec3f(unpack(c.x, 0).kernel.mean) + Vec3f(0.02f, -0.03f, -0.05f);
    c.ray.direction = normalize(target - c.ray.origin);
    c.ray.tMin = startInside ? 0.0f : 0.5f;
    c.forward = traceDouble(c.x, c.ray, s);
    const Forward& f = c.forward;
    if (f.composited.size() < minHits || f.truncated != wantTruncated) continue;
    if (f.minKeyGap < 1e-3 || f.minBoundaryMargin < 0.05) continue;
    bool nearAlphaMin = false;
    for (const Hit& h : f.composited) nearAlphaMin |= h.kernel.alpha < 1.2 * s.alphaMin;
    if (nearAlphaMin) continue;
    // The threshold must not be crossed by a finite-difference step.
    if (wantTruncated && f.tauN > 0.8 * s.minTransmittance) continue;
    return c;
  }
  ADD_FAILURE() << "no suitable random case found";
  return {};
}

void expectBackwardMatches(double power, bool truncated, bool startInside, uint64_t seed, bool exactTail = true) {
  Rng rng(seed);
  TraceSettings s;
  s.kernelPower = float(power);
  s.alphaMin = 0.01f;
  s.exactTail = exactTail;
  s.minTransmittance = truncated ? 0.2f : 1e-4f;
  for (int trial = 0; trial < 6; ++trial) {
    Case c = drawCase(rng, s, truncated ? 2 : 3, truncated, startInside);
    RayResultAdjoint v = randomAdjoint(rng);
    std::vector<double> analytic = analyticGradient(c.x, c.ray, s, c.forward, v);
    std::optional<DetachedTail> tail;
    if (truncated) {
      // Hold the tail's colour C / (1 - tau_n) and its ratio T_f / tau_n at their values.
      tail.emplace();
      for (const Hit& h : c.forward.composited) tail->order.push_back(h.id);
      Outputs front = traceDouble(c.x, c.ray, s, &*tail).out;  // background still zero: C
      double ratio = c.forward.finalT / c.forward.tauN;
      for (int k = 0; k < 11; ++k) tail->background[k] = (1 - ratio) * front[k] / (1 - c.forward.tauN);
      double full = lossOf(traceDouble(c.x, c.ray, s, &*tail).out, v);
      ASSERT_NEAR(full, lossOf(c.forward.out, v), 1e-9) << "the detached forward must agree at the base point";
    }
    auto loss = [&](const std::vector<double>& x) {
      return lossOf(traceDouble(x, c.ray, s, tail ? &*tail : nullptr).out, v);
    };
    std::vector<double> numeric = test::centralGradient(loss, c.x);
    test::expectGradientNear(analytic, numeric, 2e-5,
                             "p = " + std::to_string(power) + (truncated ? ", truncated" : "") +
                                 (exactTail ? "" : ", opaque tail") +
                                 (startInside ? ", starting inside" : "") + ", trial " + std::to_string(trial));
  }
}

TEST(RayBackward, MatchesFiniteDifferencesGaussianKernel) { expectBackwardMatches(1.0, false, false, 11); }
TEST(RayBackward, MatchesFiniteDifferencesPowerThree) { expectBackwardMatches(3.0, false, false, 12); }
TEST(RayBackward, MatchesFiniteDifferencesTruncatedGaussianKernel) { expectBackwardMatches(1.0, true, false, 13); }
TEST(RayBackward, MatchesFiniteDifferencesTruncatedPowerThree) { expectBackwardMatches(3.0, true, false, 14); }
// Early termination: the tail estimate takes T_f = 0 (an opaque tail).
TEST(RayBackward, MatchesFiniteDifferencesTruncatedOpaqueTail) { expectBackwardMatches(3.0, true, false, 17, false); }
TEST(RayBackward, MatchesFiniteDifferencesStartingInside) { expectBackwardMatches(3.0, false, true, 15); }

// An adjoint on the blended roughness and F0 with the weights held (L_r's material gradient,
// D15) reaches each hit's own roughness and F0 as the plain adjoint does, and nothing else:
// no opacity, position, shape, diffuse or normal gradient.
TEST(RayBackward, WeightsHeldAdjointReachesOnlyRoughnessAndF0) {
  Rng rng(18);
  TraceSettings s;
  s.alphaMin = 0.01f;
  s.minTransmittance = 1e-4f;
  Case c = drawCase(rng, s, 3, false, false);
  RayResultAdjoint plain;
  plain.v_roughness = -0.7f;
  plain.v_f0 = Rgb(0.4f, -0.3f, 0.9f);
  RayResultAdjoint held;
  held.v_roughnessWeightsHeld = plain.v_roughness;
  held.v_f0WeightsHeld = plain.v_f0;
  EXPECT_FALSE(held.isZero());
  const std::vector<double> gPlain = analyticGradient(c.x, c.ray, s, c.forward, plain);
  const std::vector<double> gHeld = analyticGradient(c.x, c.ray, s, c.forward, held);
  constexpr int kRoughnessParam = test::kNormalParam + 3;  // then F0's three
  double plainGeometry = 0, heldMaterials = 0;
  for (size_t i = 0; i < gPlain.size(); ++i) {
    if (int(i % kParams) >= kRoughnessParam) {
      EXPECT_NEAR(gHeld[i], gPlain[i], 1e-12) << "parameter " << i;
      heldMaterials += std::abs(gHeld[i]);
    } else {
      EXPECT_EQ(gHeld[i], 0.0) << "parameter " << i;
      plainGeometry += std::abs(gPlain[i]);
    }
  }
  EXPECT_GT(heldMaterials, 1e-3);
  EXPECT_GT(plainGeometry, 1e-3);  // the plain adjoint does move the hits' opacity and shape
}

// In float, from the records a fast trace leaves, the gradient agrees with the double one.
TEST(RayBackward, FloatRecordsAgreeWithDouble) {
  Rng rng(16);
  TraceSettings s;
  s.alphaMin = 0.01f;
  s.minTransmittance = 0.05f;
  s.exactTail = true;
  Case c = drawCase(rng, s, 2, true, false);
  RayResultAdjoint v = randomAdjoint(rng);
  std::vector<double> reference = analyticGradient(c.x, c.ray, s, c.forward, v);
  GaussianScene scene = toScene(c.x);
  HitList hits = test::hitListOf(c.forward);
  RayResult result;
  result.truncated = true;
  result.transmittance = float(c.forward.finalT);
  RayBackwardScratch<float> scratch;
  std::vector<double> single(c.x.size(), 0.0);
  backwardRay<float>(scene, s, c.ray, hits, result, v, scratch,
                     [&](uint32_t id, const HitGradient<float>& g) { test::accumulate(&single, id, g); });
  test::expectGradientNear(single, reference, 1e-3, "float backward");
}

TEST(RayBackward, CapacityBoundCoversTheWorstRay) {
  TraceSettings s;  // alphaMin 0.005, minTransmittance 0.01
  size_t n = hitCapacityWithoutOverflow(s);
  EXPECT_GE(std::pow(1.0 - s.alphaMin, double(n - 1)), 0.0);
  EXPECT_LT(std::pow(1.0 - double(s.alphaMin), double(n) - 2.0), double(s.minTransmittance) * 1.0001);
  EXPECT_LT(n, 1000u);
}

}  // namespace
}  // namespace glint
