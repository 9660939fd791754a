// Vector-Jacobian products of the ray-Gaussian kernel (raytrace/gaussian_kernel.h): the
// gradients of one hit's alpha and sort key (the depth the compositor accumulates) with
// respect to the Gaussian's mean, rotation, log-scales and opacity logit. The kernel is
// split into small steps (the primal ones in gaussian_kernel.h, where evaluateGaussian is
// built from them, so forward and backward cannot drift apart); derivations D1-D10 in
// docs/derivations.md.
#pragma once

#include "core/cpu_gpu.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "math/mat3.h"
#include "math/mat3_vjp.h"
#include "math/quat.h"
#include "math/quat_vjp.h"
#include "math/vec.h"
#include "raytrace/gaussian_kernel.h"
#include "raytrace/trace_settings.h"
#include "scene/gaussians.h"

namespace glint {

// The trainable parameters that shape a Gaussian's hits, in the precision of the pass.
template <typename T>
struct KernelParams {
  Vec3<T> mean;
  Quat<T> rotation;  // (w, x, y, z), not necessarily unit: normalised on use
  Vec3<T> logScale;
  T opacityLogit = 0;
};

// Their adjoints (dL/d of each parameter); zero-initialised so they can be summed into.
template <typename T>
struct KernelGrad {
  Vec3<T> v_mean;
  Quat<T> v_rotation{0, 0, 0, 0};
  Vec3<T> v_logScale;
  T v_opacityLogit = 0;
};

// The kernel's parameters of every Gaussian as arrays: the scene's own (CPU), or their
// copies in GPU memory, so that the backward pass reads them the same way on both.
struct KernelParamArrays {
  const Vec3f* position = nullptr;
  const Quatf* rotation = nullptr;
  const Vec3f* logScale = nullptr;
  const float* opacityLogit = nullptr;

  static KernelParamArrays of(const GaussianScene& scene) {
    return {scene.position.data(), scene.rotation.data(), scene.logScale.data(), scene.opacityLogit.data()};
  }
};

template <typename T>
GLINT_CPU_GPU KernelParams<T> kernelParams(const KernelParamArrays& arrays, size_t i) {
  const Quatf& q = arrays.rotation[i];
  return {Vec3<T>(arrays.position[i]), Quat<T>{T(q.w), T(q.x), T(q.y), T(q.z)}, Vec3<T>(arrays.logScale[i]),
          T(arrays.opacityLogit[i])};
}

template <typename T>
KernelParams<T> kernelParams(const GaussianScene& scene, size_t i) {
  return kernelParams<T>(KernelParamArrays::of(scene), i);
}

// ---- Opacity: o = sigmoid(logit) (D8) ----

// d sigmoid / d logit = o (1 - o), written with the primal output o.
template <typename T>
GLINT_CPU_GPU T opacityFromLogit_vjp(T opacity, T v_opacity) {
  return v_opacity * opacity * (T(1) - opacity);
}

// ---- World-to-local matrix W = S^-1 R^T, S = diag(exp(logScale)) (D2-D4) ----

// W_rj = exp(-s_r) R_jr: v_R_jr = exp(-s_r) v_W_rj and v_s_r = -sum_j v_W_rj W_rj (D4).
template <typename T>
GLINT_CPU_GPU void worldToLocal_vjp(const Quat<T>& q, const Vec3<T>& logScale, const Mat3<T>& v_W, Quat<T>* v_q,
                      Vec3<T>* v_logScale) {
  Mat3<T> w = worldToLocal(q, logScale);
  Mat3<T> v_R;
  for (int r = 0; r < 3; ++r) {
    T invScale = std::exp(-logScale[r]);
    for (int j = 0; j < 3; ++j) v_R.m[j][r] = v_W.m[r][j] * invScale;
    (*v_logScale)[r] = -dot(v_W.m[r], w.m[r]);
  }
  *v_q = quatToRotation_vjp(q, v_R);
}

// The frame makeGaussianFrame builds from a scene, built from KernelParams instead (the
// same operations, so the same values to rounding).
template <typename T>
GLINT_CPU_GPU GaussianFrame<T> gaussianFrame(const KernelParams<T>& p, const TraceSettings& s) {
  GaussianFrame<T> g;
  g.mean = p.mean;
  g.worldToLocal = worldToLocal(p.rotation, p.logScale);
  g.opacity = opacityFromLogit(p.opacityLogit);
  g.proxyRadius = proxyRadius(g.opacity, s);
  return g;
}

// ---- The ray in the local frame (D5; primal localRay in gaussian_kernel.h) ----

// Adds dL/dW to *v_W and returns dL/dmean (D3, D5).
template <typename T>
GLINT_CPU_GPU Vec3<T> localRay_vjp(const Mat3<T>& W, const Vec3<T>& mean, const Vec3<T>& o, const Vec3<T>& d, T t0,
                     const LocalRay<T>& v_local, Mat3<T>* v_W) {
  Vec3<T> v_offset;  // adjoint of o + d t0 - mean
  matVec_vjp(W, o + d * t0 - mean, v_local.origin, v_W, &v_offset);
  matVec_vjp(W, d, v_local.direction, v_W, static_cast<Vec3<T>*>(nullptr));
  return -v_offset;
}

// ---- Closest approach of the local ray to the centre (D6; primal closestApproach) ----

// dr2/doL = 2 pL, dr2/ddL = 2 tc pL, dtc/doL = -dL / dd, dtc/ddL = -(oL + 2 tc dL) / dd (D6).
template <typename T>
GLINT_CPU_GPU LocalRay<T> closestApproach_vjp(const LocalRay<T>& ray, const ClosestApproach<T>& c, T v_tc, T v_r2) {
  const Vec3<T>& oL = ray.origin;
  const Vec3<T>& dL = ray.direction;
  T dd = dot(dL, dL);
  LocalRay<T> v;
  v.origin = c.pL * (T(2) * v_r2) - dL * (v_tc / dd);
  v.direction = c.pL * (T(2) * c.tc * v_r2) - (oL + dL * (T(2) * c.tc)) * (v_tc / dd);
  return v;
}

// ---- Response G = exp(-(r^2)^p / 2p) (primal gaussianResponse in gaussian_kernel.h) (D7) ----

// dG/dr2 = -G (r^2)^(p-1) / 2; finite at r2 = 0 for p >= 1.
template <typename T>
GLINT_CPU_GPU T gaussianResponse_vjp(T r2, T power, T G, T v_G) {
  return -v_G * G * kernelPow(r2, power - T(1)) / T(2);
}

// The same, computing G.
template <typename T>
GLINT_CPU_GPU T gaussianResponse_vjp(T r2, T power, T v_G) {
  return gaussianResponse_vjp(r2, power, gaussianResponse(r2, power), v_G);
}

// ---- Alpha = kMaxAlpha * opacity * G (D8; primal hitAlpha) ----

template <typename T>
GLINT_CPU_GPU void hitAlpha_vjp(T opacity, T response, T v_alpha, T* v_opacity, T* v_response) {
  *v_opacity = v_alpha * T(kMaxAlpha) * response;
  *v_response = v_alpha * T(kMaxAlpha) * opacity;
}

// ---- Sort key / depth: tPeak clamped into [max(tEnter, tMin), tExit] (D9; primal hitKey) ----

// tEnter <= tPeak <= tExit always (they are tPeak -/+ a non-negative half-width), so the
// clamp only ever acts when tPeak < tMin, and then key = tMin, a constant of the ray:
// its gradient is 0. Otherwise key = tPeak and the adjoint passes through.
template <typename T>
GLINT_CPU_GPU T hitKey_vjp(T tPeak, T tMin, T v_key) {
  return tPeak < tMin ? T(0) : v_key;
}

// ---- The whole kernel (D10) ----

// Gradients of L through one accepted hit of evaluateGaussian (the hit must have been
// accepted: the proxy and alphaMin cut-offs are not differentiated, D10). v_alpha =
// dL/dalpha and v_key = dL/dkey, the adjoint of KernelHit::key (which the compositor
// accumulates as depth). Recomputes the forward intermediates in the precision T.
template <typename T>
GLINT_CPU_GPU KernelGrad<T> evaluateGaussian_vjp(const KernelParams<T>& params, const Vec3<T>& o, const Vec3<T>& d, T tMin,
                                   const TraceSettings& s, T v_alpha, T v_key) {
  // Forward, with the step functions evaluateGaussian is made of.
  T power = T(s.kernelPower);
  Mat3<T> W = worldToLocal(params.rotation, params.logScale);
  T opacity = opacityFromLogit(params.opacityLogit);
  T t0 = dot(params.mean - o, d);
  LocalRay<T> local = localRay(W, params.mean, o, d, t0);
  ClosestApproach<T> c = closestApproach(local);
  T response = gaussianResponse(c.r2, power);
  T tPeak = t0 + c.tc;

  // Backward, in reverse order.
  KernelGrad<T> grad;
  T v_opacity, v_response;
  hitAlpha_vjp(opacity, response, v_alpha, &v_opacity, &v_response);
  T v_r2 = gaussianResponse_vjp(c.r2, power, response, v_response);
  T v_tc = hitKey_vjp(tPeak, tMin, v_key);  // tPeak = t0 + tc with t0 held fixed (D5)
  LocalRay<T> v_local = closestApproach_vjp(local, c, v_tc, v_r2);
  Mat3<T> v_W = zeroMat3<T>();
  grad.v_mean = localRay_vjp(W, params.mean, o, d, t0, v_local, &v_W);
  worldToLocal_vjp(params.rotation, params.logScale, v_W, &grad.v_rotation, &grad.v_logScale);
  grad.v_opacityLogit = opacityFromLogit_vjp(opacity, v_opacity);
  return grad;
}

}  // namespace glint
