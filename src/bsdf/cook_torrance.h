// The Cook-Torrance microfacet specular lobe: GGX D, height-correlated Smith G2, Schlick F.
#pragma once

#include "bsdf/bsdf_sample.h"
#include "math/vec.h"

namespace glint {

// f_s(wo, wi) = D(wm) G2(wo, wi) F(wo.wm) / (4 wo.z wi.z), wm = normalize(wo + wi)
// (Cook & Torrance 1982, with Walter et al. 2007's normalisation). Reflection only: both
// wo and wi must be above the surface. Directions are in the local frame (normal = +z).
//
// sample() draws wm from the GGX distribution of normals visible from wo and reflects wo
// about it. When the reflected direction falls below the horizon, the sample is invalid;
// that lost probability is why pdf() integrates to less than 1 over directions (by the
// fraction of invalid samples), exactly as the estimator that discards them needs.
struct CookTorranceLobe {
  Rgb F0;       // Fresnel reflectance at normal incidence
  float alpha;  // GGX roughness, at least kMinGgxAlpha

  CookTorranceLobe() : CookTorranceLobe(Rgb(0.04f), 0.25f) {}
  // Clamps alpha to kMinGgxAlpha so a perfect mirror stays finite.
  CookTorranceLobe(const Rgb& F0, float alpha);

  // f_s(wo, wi) cos(theta_i).
  Rgb eval(const Vec3f& wo, const Vec3f& wi) const;
  // Density of sample() over wi: D_wo(wm) / (4 wo.wm) = G1(wo) D(wm) / (4 wo.z).
  float pdf(const Vec3f& wo, const Vec3f& wi) const;
  BsdfSample sample(const Vec3f& wo, Vec2f u) const;
};

}  // namespace glint
