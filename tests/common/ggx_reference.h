// GGX's D and Smith's Lambda written out in double from their papers' closed forms: the
// references the microfacet tests compare with and the finite-difference tests of D15's
// gradients differentiate.
#pragma once

#include <cmath>
#include <numbers>

#include "math/vec.h"

namespace glint::test {

// D = alpha^2 / (pi cos^4 (alpha^2 + tan^2)^2) of the microfacet normal wm (Walter et al.
// 2007). tan^2 from wm's components, so a reference given a float direction sees the
// direction D_GGX sees.
inline double ggxDReference(const Vec3d& wm, double alpha) {
  double c = wm.z, tan2 = (wm.x * wm.x + wm.y * wm.y) / (c * c), a2 = alpha * alpha;
  return a2 / (std::numbers::pi * c * c * c * c * (a2 + tan2) * (a2 + tan2));
}

// Lambda = (-1 + sqrt(1 + alpha^2 tan^2)) / 2 (Heitz 2014).
inline double smithLambdaReference(const Vec3d& w, double alpha) {
  double tan2 = (w.x * w.x + w.y * w.y) / (w.z * w.z);
  return (-1 + std::sqrt(1 + alpha * alpha * tan2)) / 2;
}

// D(wm) G2(wo, wi), wm = normalize(wo + wi), with the height-correlated G2 = 1 / (1 + Lambda(wo) + Lambda(wi)).
inline double ggxLobeReference(const Vec3d& wo, const Vec3d& wi, double alpha) {
  return ggxDReference(normalize(wo + wi), alpha) /
         (1 + smithLambdaReference(wo, alpha) + smithLambdaReference(wi, alpha));
}

}  // namespace glint::test
