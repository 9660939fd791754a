// The ray-Gaussian kernel shared by every tracer: the generalised Gaussian response at the
// ray's closest approach in the Gaussian's local frame (paper appendix A.1), the alpha of
// a hit, and the proxy ellipsoid that bounds every hit that can count.
#pragma once

#include <algorithm>
#include <cmath>

#include "math/mat3.h"
#include "math/quat.h"
#include "math/vec.h"
#include "raytrace/trace_settings.h"
#include "scene/gaussians.h"

namespace glint {

// G(r^2) = exp(-(r^2)^p / (2p)): r is the distance in units of the scales (Mahalanobis
// distance); p = 1 gives the ordinary Gaussian exp(-r^2 / 2).
template <typename T>
inline T gaussianResponse(T r2, T power) {
  return std::exp(-std::pow(r2, power) / (T(2) * power));
}

// Radius (in local, scale units) of the ellipsoid on which kMaxAlpha * opacity * G equals
// alphaMin: solving exp(-(r^2)^p / 2p) = alphaMin / (kMaxAlpha o) for r. Returns 0 when
// the Gaussian can never reach alphaMin (it then contributes nothing and has no proxy).
template <typename T>
inline T proxyRadius(T opacity, const TraceSettings& s) {
  T peak = T(kMaxAlpha) * opacity;
  if (!(peak > T(s.alphaMin))) return T(0);
  T p = T(s.kernelPower);
  T r2 = std::pow(T(2) * p * std::log(peak / T(s.alphaMin)), T(1) / p);
  return std::sqrt(r2);
}

// Opacity from its logit, o = sigmoid(logit) (derivations D8).
template <typename T>
T opacityFromLogit(T logit) {
  return T(1) / (T(1) + std::exp(-logit));
}

// Row r of W is column r of R (local axis r in world space) divided by scale r, so
// W (x - mean) gives x in the Gaussian's scale-normalised frame.
template <typename T>
Mat3<T> worldToLocal(const Quat<T>& q, const Vec3<T>& logScale) {
  Mat3<T> rt = quatToRotation(q).transposed();
  Mat3<T> w;
  for (int r = 0; r < 3; ++r) w.m[r] = rt.m[r] * std::exp(-logScale[r]);
  return w;
}

// Everything about one Gaussian that ray evaluation needs, derived from its parameters.
template <typename T>
struct GaussianFrame {
  Vec3<T> mean;
  Mat3<T> worldToLocal;  // S^-1 R^T: world offsets to local, scale-normalised coordinates
  T opacity = 0;
  T proxyRadius = 0;     // in local units; 0 = never contributes
};

template <typename T>
GaussianFrame<T> makeGaussianFrame(const GaussianScene& scene, size_t i, const TraceSettings& s) {
  GaussianFrame<T> g;
  g.mean = Vec3<T>(scene.position[i]);
  const Quatf& q = scene.rotation[i];
  g.worldToLocal = worldToLocal(Quat<T>{T(q.w), T(q.x), T(q.y), T(q.z)}, Vec3<T>(scene.logScale[i]));
  g.opacity = opacityFromLogit(T(scene.opacityLogit[i]));
  g.proxyRadius = proxyRadius(g.opacity, s);
  return g;
}

// A ray's encounter with one Gaussian.
template <typename T>
struct KernelHit {
  T tPeak;    // distance of the closest approach (may be before tMin when the ray starts inside)
  T tEnter;   // where the ray enters the proxy ellipsoid
  T tExit;    // where it leaves
  T key;      // sort key: tPeak clamped into [max(tEnter, tMin), tExit]
  T response; // G at the closest approach
  T alpha;    // kMaxAlpha * opacity * G
  Vec3<T> localPoint;  // closest-approach point in local coordinates
};

// Intersects the ray o + t d (d unit length), t >= tMin, with a Gaussian's proxy and
// evaluates the kernel. Returns false when the ray misses the proxy, the proxy lies
// entirely before tMin, or alpha < alphaMin.
//
// Precision: the ray origin is first moved, in world space, to the ray's closest point to
// the mean (t0 = (mean - o) . d), so the local-frame solve never subtracts large numbers.
template <typename T>
bool evaluateGaussian(const GaussianFrame<T>& g, const Vec3<T>& o, const Vec3<T>& d, T tMin,
                      const TraceSettings& s, KernelHit<T>* hit) {
  if (!(g.proxyRadius > T(0))) return false;
  T t0 = dot(g.mean - o, d);
  Vec3<T> oL = g.worldToLocal * (o + d * t0 - g.mean);
  Vec3<T> dL = g.worldToLocal * d;
  T dd = dot(dL, dL);
  if (!(dd > T(0))) return false;
  // Closest approach of the local ray to the origin (the Gaussian's centre).
  T tc = -dot(oL, dL) / dd;
  Vec3<T> pL = oL + dL * tc;
  T r2 = dot(pL, pL);
  T R2 = g.proxyRadius * g.proxyRadius;
  if (r2 > R2) return false;
  T half = std::sqrt((R2 - r2) / dd);
  hit->tPeak = t0 + tc;
  hit->tEnter = hit->tPeak - half;
  hit->tExit = hit->tPeak + half;
  if (hit->tExit < tMin) return false;
  hit->key = std::clamp(hit->tPeak, std::max(hit->tEnter, tMin), hit->tExit);
  hit->response = gaussianResponse(r2, T(s.kernelPower));
  hit->alpha = T(kMaxAlpha) * g.opacity * hit->response;
  if (hit->alpha < T(s.alphaMin)) return false;
  hit->localPoint = pL;
  return true;
}

}  // namespace glint
