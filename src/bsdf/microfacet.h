// The isotropic GGX (Trowbridge-Reitz) microfacet distribution: normal distribution D,
// Smith masking-shadowing G1 / G2, and sampling of the distribution of visible normals.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/cpu_gpu.h"
#include "math/sampling.h"
#include "math/vec.h"

namespace glint {

// Smallest GGX alpha we evaluate. A perfect mirror (alpha = 0) makes D a Dirac delta,
// which a float evaluation cannot represent; at alpha = 1e-3 the peak of D is
// 1 / (pi alpha^2) ~ 3.2e5, still comfortably finite in float, and the lobe is narrower
// than a pixel footprint at any resolution we render, so it looks like a mirror.
constexpr float kMinGgxAlpha = 1e-3f;

// Alpha as every lobe evaluates it: at least kMinGgxAlpha (NaN becomes kMinGgxAlpha).
GLINT_CPU_GPU inline float clampGgxAlpha(float alpha) { return alpha > kMinGgxAlpha ? alpha : kMinGgxAlpha; }

// All functions take unit vectors in the local shading frame (normal = +z) and an
// alpha >= kMinGgxAlpha (callers clamp; see PrincipledBrdf::alphaFromRoughness).

// GGX normal distribution D(wm); zero for wm below the horizon.
GLINT_CPU_GPU inline float D_GGX(const Vec3f& wm, float alpha) {
  // Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces" (GGX D),
  // in the form 1 / (pi a^2 (x^2 / a^2 + y^2 / a^2 + z^2)^2) used by Heitz 2018: reading
  // sin^2 as x^2 + y^2 avoids the cancellation in 1 - cos^2 near the normal.
  if (wm.z <= 0) return 0.0f;
  float a2 = alpha * alpha;
  float t = (wm.x * wm.x + wm.y * wm.y) / a2 + wm.z * wm.z;
  return 1.0f / (kPi * a2 * t * t);
}

// Smith's Lambda for GGX: the mean masked fraction term, G1 = 1 / (1 + Lambda).
// T = float, or double in the finite-difference tests.
template <typename T>
GLINT_CPU_GPU T lambdaGGX(const Vec3<T>& w, T alpha) {
  // Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs",
  // JCGT 3(2), GGX case: Lambda = (-1 + sqrt(1 + a^2 tan^2)) / 2, rewritten as
  // a^2 tan^2 / (2 (1 + sqrt(1 + a^2 tan^2))) so it stays accurate when a^2 tan^2 is tiny.
  T cos2 = w.z * w.z;
  if (cos2 == 0) return std::numeric_limits<T>::infinity();
  T a2tan2 = alpha * alpha * (w.x * w.x + w.y * w.y) / cos2;
  return a2tan2 / (T(2) * (T(1) + std::sqrt(T(1) + a2tan2)));
}

// Smith masking G1(w) for GGX (the back-facing test on the microfacet is left to callers).
GLINT_CPU_GPU inline float smithG1(const Vec3f& w, float alpha) {
  // Heitz 2014, Smith masking function: G1 = 1 / (1 + Lambda) for directions in front of the surface.
  if (w.z <= 0) return 0.0f;
  return 1.0f / (1.0f + lambdaGGX(w, alpha));
}

// Height-correlated Smith masking-shadowing G2(wo, wi) for reflection (both above the horizon).
GLINT_CPU_GPU inline float smithG2(const Vec3f& wo, const Vec3f& wi, float alpha) {
  // Heitz 2014, height-correlated Smith masking-shadowing, for reflection:
  // G2 = 1 / (1 + Lambda(wo) + Lambda(wi)).
  if (wo.z <= 0 || wi.z <= 0) return 0.0f;
  return 1.0f / (1.0f + lambdaGGX(wo, alpha) + lambdaGGX(wi, alpha));
}

// d Lambda / d alpha for GGX: Lambda = (sqrt(1 + a^2 tan^2) - 1) / 2 (lambdaGGX), so
// dLambda / da = a tan^2 / (2 sqrt(1 + a^2 tan^2)). w above the surface.
template <typename T>
GLINT_CPU_GPU T lambdaGGXAlphaDerivative(const Vec3<T>& w, T alpha) {
  const T tan2 = (w.x * w.x + w.y * w.y) / (w.z * w.z);
  return alpha * tan2 / (T(2) * std::sqrt(T(1) + alpha * alpha * tan2));
}

// d/d alpha of log(D(wm) G2(wo, wi)) at fixed directions, wm = normalize(wo + wi): the
// relative change of the Cook-Torrance lobe f_s(wo, wi) with alpha (F does not depend on
// it). A sampled direction's weight f cos / p, with the direction and its density held
// fixed, changes by this factor (docs/derivations.md D15). wo and wi above the surface;
// T = float in training, double in the finite-difference tests.
template <typename T>
GLINT_CPU_GPU T lobeLogAlphaDerivative(const Vec3<T>& wo, const Vec3<T>& wi, T alpha) {
  const Vec3<T> wm = normalize(wo + wi);
  // D = 1 / (pi a^2 (q + z^2)^2), q = (x^2 + y^2) / a^2 over wm: dq/da = -2 q / a, so
  // d log D / da = -2 / a + 4 q / (a (q + z^2)) = 2 (q - z^2) / (a (q + z^2)).
  const T q = (wm.x * wm.x + wm.y * wm.y) / (alpha * alpha), z2 = wm.z * wm.z;
  const T dLogD = T(2) * (q - z2) / (alpha * (q + z2));
  // G2 = 1 / (1 + Lambda(wo) + Lambda(wi)).
  const T dLambda = lambdaGGXAlphaDerivative(wo, alpha) + lambdaGGXAlphaDerivative(wi, alpha);
  return dLogD - dLambda / (T(1) + lambdaGGX(wo, alpha) + lambdaGGX(wi, alpha));
}

// Samples a microfacet normal wm from the distribution of normals visible from wo,
// D_wo(wm) = G1(wo) max(0, wo.wm) D(wm) / wo.z, into *wmOut. Returns false when wo is not
// above the horizon.
GLINT_CPU_GPU inline bool sampleVisibleNormalGGX(const Vec3f& wo, float alpha, Vec2f u, Vec3f* wmOut) {
  // Dupuy & Benyoub 2023, "Sampling Visible GGX Normals with Spherical Caps", CGF 42(8),
  // which is exact and equivalent to Heitz 2018, "Sampling the GGX Distribution of Visible
  // Normals", JCGT 7(4): in the configuration stretched to alpha = 1 the visible normals
  // of wo are wo plus a uniform point on the spherical cap of directions with z >= -wo.z.
  if (!(wo.z > 0)) return false;
  Vec3f woStd = normalize(Vec3f(wo.x * alpha, wo.y * alpha, wo.z));
  float phi = 2.0f * kPi * u.x;
  float z = (1.0f - u.y) * (1.0f + woStd.z) - woStd.z;
  float sinTheta = std::sqrt(std::clamp(1.0f - z * z, 0.0f, 1.0f));
  Vec3f cap(sinTheta * std::cos(phi), sinTheta * std::sin(phi), z);
  Vec3f wmStd = cap + woStd;
  // Unstretch back to the surface's alpha; the normal transforms with the inverse stretch.
  Vec3f wm = normalize(Vec3f(wmStd.x * alpha, wmStd.y * alpha, std::max(wmStd.z, 0.0f)));
  if (!(wm.z > 0)) return false;  // u.y = 1 maps to the horizon, a set of measure zero
  *wmOut = wm;
  return true;
}

// The same, as an optional (host code and the tests).
inline std::optional<Vec3f> sampleVisibleNormalGGX(const Vec3f& wo, float alpha, Vec2f u) {
  Vec3f wm;
  if (!sampleVisibleNormalGGX(wo, alpha, u, &wm)) return std::nullopt;
  return wm;
}

// The density D_wo(wm) of sampleVisibleNormalGGX with respect to solid angle around wm.
GLINT_CPU_GPU inline float visibleNormalPdfGGX(const Vec3f& wo, const Vec3f& wm, float alpha) {
  // Heitz 2018, JCGT 7(4), definition of the VNDF: D_wo(wm) = G1(wo) max(0, wo.wm) D(wm) / wo.z.
  if (!(wo.z > 0)) return 0.0f;
  float cosOm = dot(wo, wm);
  if (cosOm <= 0) return 0.0f;
  return smithG1(wo, alpha) * cosOm * D_GGX(wm, alpha) / wo.z;
}

}  // namespace glint
