// The obviously-correct double-precision forward of one ray through a set of Gaussians
// given as a flat parameter vector (every Gaussian against the ray, a full sort, plain
// compositing): the oracle the finite-difference tests of the backward passes differentiate.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "raytrace/gaussian_gradients.h"
#include "raytrace/gaussian_kernel_vjp.h"
#include "raytrace/gaussian_tracer.h"

namespace glint::test {

// Per Gaussian: mean (3), rotation (4), log-scale (3), opacity logit, diffuse (3),
// normal (3), roughness, F0 (3).
constexpr int kParams = 21;
constexpr int kOpacityParam = 10;  // the opacity logit
constexpr int kDiffuseParam = 11;  // first of the diffuse colour's three
constexpr int kNormalParam = 14;   // first of the attributes that only blend: normal, roughness, F0
using Outputs = std::array<double, 11>;  // diffuse, depth, normal, roughness, f0

struct DoubleGaussian {
  KernelParams<double> kernel;
  Vec3d diffuse, normal, f0;
  double roughness;
};

inline DoubleGaussian unpack(const std::vector<double>& x, size_t i) {
  const double* p = x.data() + i * kParams;
  DoubleGaussian g;
  g.kernel = {{p[0], p[1], p[2]}, Quatd{p[3], p[4], p[5], p[6]}, {p[7], p[8], p[9]}, p[10]};
  g.diffuse = {p[11], p[12], p[13]};
  g.normal = {p[14], p[15], p[16]};
  g.roughness = p[17];
  g.f0 = {p[18], p[19], p[20]};
  return g;
}

// A hit's gradient in the order of the parameter vector.
template <typename T>
std::vector<double> flatten(const HitGradient<T>& g) {
  return {double(g.v_position.x), double(g.v_position.y), double(g.v_position.z), double(g.v_rotation.w),
          double(g.v_rotation.x), double(g.v_rotation.y), double(g.v_rotation.z), double(g.v_logScale.x),
          double(g.v_logScale.y), double(g.v_logScale.z), double(g.v_opacityLogit), double(g.v_diffuse.x),
          double(g.v_diffuse.y), double(g.v_diffuse.z), double(g.v_normal.x), double(g.v_normal.y),
          double(g.v_normal.z), double(g.v_roughness), double(g.v_f0.x), double(g.v_f0.y), double(g.v_f0.z)};
}

// Adds hit `id`'s gradient into the whole-scene gradient vector.
template <typename T>
void accumulate(std::vector<double>* gradient, uint32_t id, const HitGradient<T>& g) {
  std::vector<double> flat = flatten(g);
  for (int k = 0; k < kParams; ++k) (*gradient)[id * kParams + k] += flat[k];
}

// The float scene the tracers and backward passes read (exact when x holds float values).
inline GaussianScene toScene(const std::vector<double>& x) {
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

// Rounds every parameter to float, so that the float scene and the double forward agree.
inline void roundToFloat(std::vector<double>* x) {
  for (double& v : *x) v = double(float(v));
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

struct Forward {
  Outputs out{};
  std::vector<Hit> composited;
  double tauN = 1, finalT = 1;
  bool truncated = false;
  double minKeyGap = 1e30;        // between consecutive composited keys (ties at tMin excepted)
  double minBoundaryMargin = 1e30;  // relative distance of any Gaussian to its proxy / alphaMin cut
  // Per Gaussian, its distance to every discontinuity of this ray's forward: the proxy
  // boundary (relative), the proxy's end against tMin and, for back-facing Gaussians, the
  // back-face skip distance (absolute, when the ray meets its proxy).
  std::vector<double> margin;
};

// Every Gaussian against the ray, a full sort by (key, id), compositing until
// minTransmittance, the tail estimate (exact T_f, or opaque); back-facing hits closer than ray.backfaceSkip are
// ignored as the tracers do. With `detached`, the hits and their order are those given
// and the tail is the fixed one.
inline Forward traceDouble(const std::vector<double>& x, const TraceRay& ray, const TraceSettings& s,
                           const DetachedTail* detached = nullptr) {
  Forward f;
  Vec3d o(ray.origin), d(ray.direction);
  size_t n = x.size() / kParams;
  f.margin.assign(n, 1e30);
  std::vector<Hit> hits;
  for (size_t i = 0; i < n; ++i) {
    GaussianFrame<double> frame = gaussianFrame(unpack(x, i).kernel, s);
    // Margins: how far the closest approach is from the proxy boundary, relatively.
    LocalRay<double> local = localRay(frame.worldToLocal, frame.mean, o, d, dot(frame.mean - o, d));
    double r2 = closestApproach(local).r2, R2 = frame.proxyRadius * frame.proxyRadius;
    f.margin[i] = std::abs(r2 - R2) / R2;
    f.minBoundaryMargin = std::min(f.minBoundaryMargin, f.margin[i]);
    KernelHit<double> h;
    bool hit = evaluateGaussian(frame, o, d, double(ray.tMin), s, &h);
    if (r2 < R2) f.margin[i] = std::min(f.margin[i], std::abs(h.tExit - ray.tMin));
    if (!hit) continue;
    // The tracers' compositor tests the float normal against the float direction.
    bool backFacing = dot(Vec3f(unpack(x, i).normal), ray.direction) > 0.0f;
    if (ray.backfaceSkip > 0 && backFacing) {
      f.margin[i] = std::min(f.margin[i], std::abs(h.key - ray.backfaceSkip));
      if (h.key < ray.backfaceSkip) continue;
    }
    f.minBoundaryMargin = std::min(f.minBoundaryMargin, std::abs(h.tExit - ray.tMin));
    hits.push_back({uint32_t(i), h});
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
  } else if (f.truncated) {
    if (!s.exactTail) f.finalT = 0;  // the opaque-tail estimate of early termination
    double scale = (f.tauN - f.finalT) / (1 - f.tauN);
    for (double& v : f.out) v *= 1 + scale;
  }
  if (!f.truncated) f.tauN = f.finalT = T;
  return f;
}

// The hit list a tracer would have recorded for this forward.
inline HitList hitListOf(const Forward& f) {
  HitList hits;
  for (const Hit& h : f.composited)
    hits.hits.push_back({h.id, float(h.kernel.key), float(h.kernel.alpha)});
  return hits;
}

}  // namespace glint::test
