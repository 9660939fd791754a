// The isotropic GGX (Trowbridge-Reitz) microfacet distribution: normal distribution D,
// Smith masking-shadowing G1 / G2, and sampling of the distribution of visible normals.
#pragma once

#include <optional>

#include "math/vec.h"

namespace glint {

// Smallest GGX alpha we evaluate. A perfect mirror (alpha = 0) makes D a Dirac delta,
// which a float evaluation cannot represent; at alpha = 1e-3 the peak of D is
// 1 / (pi alpha^2) ~ 3.2e5, still comfortably finite in float, and the lobe is narrower
// than a pixel footprint at any resolution we render, so it looks like a mirror.
constexpr float kMinGgxAlpha = 1e-3f;

// All functions take unit vectors in the local shading frame (normal = +z) and an
// alpha >= kMinGgxAlpha (callers clamp; see PrincipledBrdf::alphaFromRoughness).

// GGX normal distribution D(wm); zero for wm below the horizon.
float D_GGX(const Vec3f& wm, float alpha);

// Smith's Lambda for GGX: the mean masked fraction term, G1 = 1 / (1 + Lambda).
float lambdaGGX(const Vec3f& w, float alpha);

// Smith masking G1(w) for GGX (the back-facing test on the microfacet is left to callers).
float smithG1(const Vec3f& w, float alpha);

// Height-correlated Smith masking-shadowing G2(wo, wi) for reflection (both above the horizon).
float smithG2(const Vec3f& wo, const Vec3f& wi, float alpha);

// Samples a microfacet normal wm from the distribution of normals visible from wo,
// D_wo(wm) = G1(wo) max(0, wo.wm) D(wm) / wo.z. Returns nothing when wo is not above the horizon.
std::optional<Vec3f> sampleVisibleNormalGGX(const Vec3f& wo, float alpha, Vec2f u);

// The density D_wo(wm) of sampleVisibleNormalGGX with respect to solid angle around wm.
float visibleNormalPdfGGX(const Vec3f& wo, const Vec3f& wm, float alpha);

}  // namespace glint
