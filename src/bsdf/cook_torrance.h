// The Cook-Torrance microfacet specular lobe: GGX D, height-correlated Smith G2, Schlick F;
// evaluation, density and visible-normal sampling, for the CPU and the GPU.
#pragma once

#include <algorithm>

#include "bsdf/bsdf_sample.h"
#include "bsdf/fresnel.h"
#include "bsdf/microfacet.h"
#include "core/cpu_gpu.h"
#include "math/vec.h"

namespace glint {

// The half vector of a reflection pair, or false for directions that do not both lie
// above the surface (where the lobe is zero).
GLINT_CPU_GPU inline bool reflectionHalfVector(const Vec3f& wo, const Vec3f& wi, Vec3f* wm) {
  if (!(wo.z > 0) || !(wi.z > 0)) return false;
  *wm = normalize(wo + wi);
  return wm->z > 0;
}

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

  GLINT_CPU_GPU CookTorranceLobe() : CookTorranceLobe(Rgb(0.04f), 0.25f) {}
  // Clamps alpha to kMinGgxAlpha so a perfect mirror stays finite.
  GLINT_CPU_GPU CookTorranceLobe(const Rgb& F0_, float alpha_) : F0(F0_), alpha(clampGgxAlpha(alpha_)) {}

  // f_s(wo, wi) cos(theta_i).
  GLINT_CPU_GPU Rgb eval(const Vec3f& wo, const Vec3f& wi) const {
    // Cook & Torrance 1982, in Walter et al. 2007's form D G F / (4 wo.z wi.z); multiplying
    // by cos(theta_i) = wi.z cancels it.
    Vec3f wm;
    if (!reflectionHalfVector(wo, wi, &wm)) return Rgb(0.0f);
    float D = D_GGX(wm, alpha);
    float G2 = smithG2(wo, wi, alpha);
    Rgb F = F_Schlick(F0, dot(wo, wm));
    return F * (D * G2 / (4.0f * wo.z));
  }

  // Density of sample() over wi: D_wo(wm) / (4 wo.wm) = G1(wo) D(wm) / (4 wo.z).
  GLINT_CPU_GPU float pdf(const Vec3f& wo, const Vec3f& wi) const {
    // Heitz 2018, JCGT 7(4): the reflection Jacobian dwm/dwi = 1 / (4 wo.wm) (Walter et al.
    // 2007) turns D_wo(wm) into a density over wi; the wo.wm factors cancel.
    Vec3f wm;
    if (!reflectionHalfVector(wo, wi, &wm)) return 0.0f;
    return smithG1(wo, alpha) * D_GGX(wm, alpha) / (4.0f * wo.z);
  }

  GLINT_CPU_GPU BsdfSample sample(const Vec3f& wo, Vec2f u) const {
    BsdfSample s;
    Vec3f sampled;
    if (!sampleVisibleNormalGGX(wo, alpha, u, &sampled)) return s;
    s.wi = normalize(reflect(wo, sampled));
    // Recompute the half vector from (wo, wi), as pdf() and eval() do since they only see
    // the pair: s.pdf then equals pdf(wo, wi) bit for bit, which MIS weights rely on.
    Vec3f wm;
    if (!reflectionHalfVector(wo, s.wi, &wm)) return s;  // reflected below the horizon
    s.pdf = smithG1(wo, alpha) * D_GGX(wm, alpha) / (4.0f * wo.z);
    if (!(s.pdf > 0)) return s;
    // f cos / pdf = F G2 / G1(wo): D and the Jacobian cancel, so the weight stays finite
    // even for near-mirror lobes where D and pdf are huge.
    s.weight = F_Schlick(F0, dot(wo, wm)) * (smithG2(wo, s.wi, alpha) / smithG1(wo, alpha));
    s.valid = true;
    return s;
  }
};

}  // namespace glint
