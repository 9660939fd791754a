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

#include "common/finite_difference.h"
#include "math/rng.h"

namespace glint {
namespace {

// Per Gaussian: mean (3), rotation (4), log-scale (3), opacity logit, diffuse (3),
// normal (3), roughness, F0 (3).
constexpr int kParams = 21;
using Outputs = std::array<double, 11>;  // diffuse, depth, normal, roughness, f0

struct DoubleGaussian {
  KernelParams<double> kernel;
  Vec3d diffuse, normal, f0;
  double roughness;
};

DoubleGaussian unpack(const std::vector<double>& x, size_t i) {
  const double* p = x.data() + i * kParams;
  DoubleGaussian g;
  g.kernel = {{p[0], p[1], p[2]}, Quatd{p[3], p[4], p[5], p[6]}, {p[7], p[8], p[9]}, p[10]};
  g.diffuse = {p[11], p[12], p[13]};
  g.normal = {p[14], p[15], p[16]};
  g.roughness = p[17];
  g.f0 = {p[18], p[19], p[20]};
  return g;
}

std::vector<double> flatten(const HitGradient<double>& g) {
  return {g.v_position.x, g.v_position.y, g.v_position.z, g.v_rotation.w, g.v_rotation.x, g.v_rotation.y,
          g.v_rotation.z, g.v_logScale.x, g.v_logScale.y, g.v_logScale.z, g.v_opacityLogit, g.v_diffuse.x,
          g.v_diffuse.y, g.v_diffuse.z, g.v_normal.x, g.v_normal.y, g.v_normal.z, g.v_roughness,
          g.v_f0.x, g.v_f0.y, g.v_f0.z};
}

GaussianScene toScene(const std::vector<double>& x) {
  GaussianScene s;
  s.resize(x.size() / kParams);
  for (size_t i = 0; i < s.size(); ++i) {
    DoubleGaussian g = unpack(x, i);
    s.position[i] = Vec3f(g.kernel.mean);
    const Quatd& q = g.kernel.rotation;
    s.rotation[i] = Quatf{float(q.w), float(q.x), float(q.y), float(q.z)};
    s.logScale[i] = Vec3f(g.kernel.logScale);
    s.opacityLogit[i] = float(g.kernel.opacityLogit);
    s.diffuse[i] = Rgb(g.diffuse);
    s.normal[i] = Vec3f(g.normal);
    s.roughness[i] = float(g.roughness);
    s.f0[i] = Rgb(g.f0);
  }
  return s;
}

struct Hit {
  uint32_t id;
  KernelHit<double> kernel;
};

// The tail of a truncated ray with its colour and ratio held fixed (what the backward
// pass differentiates, D12): out = C + tau_n * background.
struct DetachedTail {
  std::vector<uint32_t> order;  // the composited hits, front to back
  Outputs background{};
};

// The obviously-correct forward in double precision: every Gaussian against the ray,
// a full sort by (key, id), compositing until minTransmittance, the exact tail. With
// `detached`, the hits and their order are those given and the tail is the fixed one.
struct Forward {
  Outputs out{};
  std::vector<Hit> composited;
  double tauN = 1, finalT = 1;
  bool truncated = false;
  double minKeyGap = 1e30;        // between consecutive composited keys (ties at tMin excepted)
  double minBoundaryMargin = 1e30;  // relative distance of any Gaussian to its proxy / alphaMin cut
};

Forward traceDouble(const std::vector<double>& x, const TraceRay& ray, const TraceSettings& s,
                    const DetachedTail* detached = nullptr) {
  Forward f;
  Vec3d o(ray.origin), d(ray.direction);
  size_t n = x.size() / kParams;
  std::vector<Hit> hits;
  for (size_t i = 0; i < n; ++i) {
    GaussianFrame<double> frame = gaussianFrame(unpack(x, i).kernel, s);
    // Margins: how far the closest approach is from the proxy boundary, relatively.
    LocalRay<double> local = localRay(frame.worldToLocal, frame.mean, o, d, dot(frame.mean - o, d));
    double r2 = closestApproach(local).r2, R2 = frame.proxyRadius * frame.proxyRadius;
    f.minBoundaryMargin = std::min(f.minBoundaryMargin, std::abs(r2 - R2) / R2);
    KernelHit<double> h;
    if (evaluateGaussian(frame, o, d, double(ray.tMin), s, &h)) {
      f.minBoundaryMargin = std::min(f.minBoundaryMargin, std::abs(h.tExit - ray.tMin));
      hits.push_back({uint32_t(i), h});
    }
  }
  std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) {
    return a.kernel.key != b.kernel.key ? a.kernel.key < b.kernel.key : a.id < b.id;
  });
  if (detached) {
    std::vector<Hit> ordered;
    for (uint32_t id : detached->order)
      for (const Hit& h : hits)
        if (h.id == id) ordered.push_back(h);
    EXPECT_EQ(ordered.size(), detached->order.size()) << "a hit vanished under a finite-difference step";
    hits = ordered;
  }
  double T = 1;
  for (const Hit& h : hits) {
    if (f.truncated && !detached) {
      f.finalT *= 1 - h.kernel.alpha;
      continue;
    }
    DoubleGaussian g = unpack(x, h.id);
    double w = T * h.kernel.alpha;
    Outputs a = {g.diffuse.x, g.diffuse.y, g.diffuse.z, h.kernel.key, g.normal.x, g.normal.y, g.normal.z,
                 g.roughness, g.f0.x, g.f0.y, g.f0.z};
    for (int k = 0; k < 11; ++k) f.out[k] += w * a[k];
    if (!f.composited.empty()) {
      double gap = h.kernel.key - f.composited.back().kernel.key;
      if (!(h.kernel.key == ray.tMin && gap == 0)) f.minKeyGap = std::min(f.minKeyGap, gap);
    }
    f.composited.push_back(h);
    T *= 1 - h.kernel.alpha;
    if (!detached && T < s.minTransmittance) {
      f.truncated = true;
      f.tauN = f.finalT = T;
    }
  }
  if (detached) {
    for (int k = 0; k < 11; ++k) f.out[k] += T * detached->background[k];
  } else if (s.exactTail && f.truncated) {
    double scale = (f.tauN - f.finalT) / (1 - f.tauN);
    for (double& v : f.out) v *= 1 + scale;
  }
  if (!f.truncated) f.tauN = f.finalT = T;
  return f;
}

double lossOf(const Outputs& out, const RayResultAdjoint& v) {
  return v.v_diffuse.x * out[0] + v.v_diffuse.y * out[1] + v.v_diffuse.z * out[2] + v.v_depth * out[3] +
         v.v_normal.x * out[4] + v.v_normal.y * out[5] + v.v_normal.z * out[6] + v.v_roughness * out[7] +
         v.v_f0.x * out[8] + v.v_f0.y * out[9] + v.v_f0.z * out[10];
}

double symmetric(Rng& rng) { return 2 * rng.uniformDouble() - 1; }

// Gaussians spread along the z axis in front of a ray origin at z = -3, parameters rounded
// to float (so that the float scene and the double forward agree exactly).
std::vector<double> randomScene(Rng& rng, size_t n) {
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
  HitList hits;
  for (const Hit& h : f.composited)
    hits.hits.push_back({h.id, float(h.kernel.key), float(h.kernel.alpha), float(h.kernel.response),
                         Vec3f(h.kernel.localPoint)});
  RayResult result;
  result.truncated = f.truncated;
  result.transmittance = float(f.finalT);
  std::vector<double> gradient(x.size(), 0.0);
  RayBackwardScratch<double> scratch;
  int calls = 0;
  backwardRay<double>(scene, s, ray, hits, result, v, scratch, [&](uint32_t id, const HitGradient<double>& g) {
    std::vector<double> flat = flatten(g);
    for (int k = 0; k < kParams; ++k) gradient[id * kParams + k] += flat[k];
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
    c.x = randomScene(rng, 8);
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

void expectBackwardMatches(double power, bool truncated, bool startInside, uint64_t seed) {
  Rng rng(seed);
  TraceSettings s;
  s.kernelPower = float(power);
  s.alphaMin = 0.01f;
  s.exactTail = true;
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
                                 (startInside ? ", starting inside" : "") + ", trial " + std::to_string(trial));
  }
}

TEST(RayBackward, MatchesFiniteDifferencesGaussianKernel) { expectBackwardMatches(1.0, false, false, 11); }
TEST(RayBackward, MatchesFiniteDifferencesPowerThree) { expectBackwardMatches(3.0, false, false, 12); }
TEST(RayBackward, MatchesFiniteDifferencesTruncatedGaussianKernel) { expectBackwardMatches(1.0, true, false, 13); }
TEST(RayBackward, MatchesFiniteDifferencesTruncatedPowerThree) { expectBackwardMatches(3.0, true, false, 14); }
TEST(RayBackward, MatchesFiniteDifferencesStartingInside) { expectBackwardMatches(3.0, false, true, 15); }

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
  HitList hits;
  for (const Hit& h : c.forward.composited)
    hits.hits.push_back({h.id, float(h.kernel.key), float(h.kernel.alpha), float(h.kernel.response),
                         Vec3f(h.kernel.localPoint)});
  RayResult result;
  result.truncated = true;
  result.transmittance = float(c.forward.finalT);
  RayBackwardScratch<float> scratch;
  std::vector<double> single(c.x.size(), 0.0);
  backwardRay<float>(scene, s, c.ray, hits, result, v, scratch, [&](uint32_t id, const HitGradient<float>& g) {
    HitGradient<double> gd;
    gd.v_position = Vec3d(g.v_position);
    gd.v_rotation = Quatd{g.v_rotation.w, g.v_rotation.x, g.v_rotation.y, g.v_rotation.z};
    gd.v_logScale = Vec3d(g.v_logScale);
    gd.v_opacityLogit = g.v_opacityLogit;
    gd.v_diffuse = Vec3d(g.v_diffuse);
    gd.v_normal = Vec3d(g.v_normal);
    gd.v_roughness = g.v_roughness;
    gd.v_f0 = Vec3d(g.v_f0);
    std::vector<double> flat = flatten(gd);
    for (int k = 0; k < kParams; ++k) single[id * kParams + k] += flat[k];
  });
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
