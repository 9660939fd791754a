// The ray-Gaussian kernel shared by every tracer: the generalised Gaussian response at the
// ray's closest approach in the Gaussian's local frame (paper appendix A.1), the alpha of
// a hit, and the proxy ellipsoid that bounds every hit that can count.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/cpu_gpu.h"
#include "math/mat3.h"
#include "math/quat.h"
#include "math/vec.h"
#include "raytrace/trace_settings.h"
#include "scene/gaussians.h"

namespace glint {

// x^p, with the small integer powers (the kernel powers 1 to 4 that runs use) as products:
// within an ulp of std::pow and several times faster, as the fast tracer's lanes compute
// them, so the backward pass re-evaluates what the forward pass did.
template <typename T>
GLINT_CPU_GPU inline T kernelPow(T x, T p) {
  if (p == T(1)) return x;
  if (p == T(2)) return x * x;
  if (p == T(3)) return (x * x) * x;
  if (p == T(4)) return (x * x) * (x * x);
  return std::pow(x, p);
}

// G(r^2) = exp(-(r^2)^p / (2p)): r is the distance in units of the scales (Mahalanobis
// distance); p = 1 gives the ordinary Gaussian exp(-r^2 / 2).
template <typename T>
GLINT_CPU_GPU inline T gaussianResponse(T r2, T power) {
  return std::exp(-kernelPow(r2, power) / (T(2) * power));
}

// Radius (in local, scale units) of the ellipsoid on which kMaxAlpha * opacity * G equals
// alphaMin: solving exp(-(r^2)^p / 2p) = alphaMin / (kMaxAlpha o) for r. Returns 0 when
// the Gaussian can never reach alphaMin (it then contributes nothing and has no proxy).
template <typename T>
GLINT_CPU_GPU inline T proxyRadius(T opacity, const TraceSettings& s) {
  T peak = T(kMaxAlpha) * opacity;
  if (!(peak > T(s.alphaMin))) return T(0);
  T p = T(s.kernelPower);
  T r2 = std::pow(T(2) * p * std::log(peak / T(s.alphaMin)), T(1) / p);
  return std::sqrt(r2);
}

// Opacity from its logit, o = sigmoid(logit) (derivations D8).
template <typename T>
GLINT_CPU_GPU T opacityFromLogit(T logit) {
  return T(1) / (T(1) + std::exp(-logit));
}

// Row r of W is column r of R (local axis r in world space) divided by scale r, so
// W (x - mean) gives x in the Gaussian's scale-normalised frame.
template <typename T>
GLINT_CPU_GPU Mat3<T> worldToLocal(const Quat<T>& q, const Vec3<T>& logScale) {
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

// ---- The ray in the local frame (D5) ----

// The ray o + t d restarted at t0 (evaluateGaussian uses t0 = (mean - o) . d, the closest
// point to the mean, for precision), in local coordinates: oL = W (o + d t0 - mean),
// dL = W d. The closest approach does not depend on t0 (D5), so the backward pass holds
// t0 fixed and has no term through it.
template <typename T>
struct LocalRay {
  Vec3<T> origin;     // oL
  Vec3<T> direction;  // dL (not unit: its length is 1 / the scale along d)
};

template <typename T>
GLINT_CPU_GPU LocalRay<T> localRay(const Mat3<T>& W, const Vec3<T>& mean, const Vec3<T>& o, const Vec3<T>& d, T t0) {
  return {W * (o + d * t0 - mean), W * d};
}

// ---- Closest approach of the local ray to the centre (D6) ----

template <typename T>
struct ClosestApproach {
  T tc = 0;     // ray parameter of the closest approach, from the local origin
  T r2 = 0;     // squared Mahalanobis distance there
  Vec3<T> pL;   // the closest-approach point, local coordinates
};

// tc = -oL . dL / dL . dL, pL = oL + dL tc, r2 = pL . pL (dL must be non-zero).
template <typename T>
GLINT_CPU_GPU ClosestApproach<T> closestApproach(const LocalRay<T>& ray) {
  ClosestApproach<T> c;
  T dd = dot(ray.direction, ray.direction);
  c.tc = -dot(ray.origin, ray.direction) / dd;
  c.pL = ray.origin + ray.direction * c.tc;
  c.r2 = dot(c.pL, c.pL);
  return c;
}

// Alpha = kMaxAlpha * opacity * G (D8).
template <typename T>
GLINT_CPU_GPU T hitAlpha(T opacity, T response) {
  return T(kMaxAlpha) * opacity * response;
}

// The key of evaluateGaussian, the depth the compositor accumulates.
template <typename T>
GLINT_CPU_GPU T hitKey(T tPeak, T tEnter, T tExit, T tMin) {
  return std::clamp(tPeak, std::max(tEnter, tMin), tExit);
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
GLINT_CPU_GPU bool evaluateGaussian(const GaussianFrame<T>& g, const Vec3<T>& o, const Vec3<T>& d, T tMin,
                      const TraceSettings& s, KernelHit<T>* hit) {
  if (!(g.proxyRadius > T(0))) return false;
  T t0 = dot(g.mean - o, d);
  LocalRay<T> local = localRay(g.worldToLocal, g.mean, o, d, t0);
  T dd = dot(local.direction, local.direction);
  if (!(dd > T(0))) return false;
  ClosestApproach<T> c = closestApproach(local);
  T R2 = g.proxyRadius * g.proxyRadius;
  if (c.r2 > R2) return false;
  T half = std::sqrt((R2 - c.r2) / dd);
  hit->tPeak = t0 + c.tc;
  hit->tEnter = hit->tPeak - half;
  hit->tExit = hit->tPeak + half;
  if (hit->tExit < tMin) return false;
  hit->key = hitKey(hit->tPeak, hit->tEnter, hit->tExit, tMin);
  hit->response = gaussianResponse(c.r2, T(s.kernelPower));
  hit->alpha = hitAlpha(g.opacity, hit->response);
  if (hit->alpha < T(s.alphaMin)) return false;
  hit->localPoint = c.pL;
  return true;
}

}  // namespace glint
