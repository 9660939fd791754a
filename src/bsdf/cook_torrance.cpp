// Cook-Torrance GGX specular: evaluation, density and visible-normal sampling.
#include "bsdf/cook_torrance.h"

#include <algorithm>

#include "bsdf/fresnel.h"
#include "bsdf/microfacet.h"

namespace glint {

namespace {

// The half vector of a reflection pair, or nothing for directions that do not both lie
// above the surface (where the lobe is zero).
bool halfVector(const Vec3f& wo, const Vec3f& wi, Vec3f* wm) {
  if (!(wo.z > 0) || !(wi.z > 0)) return false;
  *wm = normalize(wo + wi);
  return wm->z > 0;
}

}  // namespace

CookTorranceLobe::CookTorranceLobe(const Rgb& F0_, float alpha_) : F0(F0_), alpha(std::max(alpha_, kMinGgxAlpha)) {}

Rgb CookTorranceLobe::eval(const Vec3f& wo, const Vec3f& wi) const {
  // Cook & Torrance 1982, in Walter et al. 2007's form D G F / (4 wo.z wi.z); multiplying
  // by cos(theta_i) = wi.z cancels it.
  Vec3f wm;
  if (!halfVector(wo, wi, &wm)) return Rgb(0.0f);
  float D = D_GGX(wm, alpha);
  float G2 = smithG2(wo, wi, alpha);
  Rgb F = F_Schlick(F0, dot(wo, wm));
  return F * (D * G2 / (4.0f * wo.z));
}

float CookTorranceLobe::pdf(const Vec3f& wo, const Vec3f& wi) const {
  // Heitz 2018, JCGT 7(4): the reflection Jacobian dwm/dwi = 1 / (4 wo.wm) (Walter et al.
  // 2007) turns D_wo(wm) into a density over wi; the wo.wm factors cancel.
  Vec3f wm;
  if (!halfVector(wo, wi, &wm)) return 0.0f;
  return smithG1(wo, alpha) * D_GGX(wm, alpha) / (4.0f * wo.z);
}

BsdfSample CookTorranceLobe::sample(const Vec3f& wo, Vec2f u) const {
  BsdfSample s;
  std::optional<Vec3f> sampled = sampleVisibleNormalGGX(wo, alpha, u);
  if (!sampled) return s;
  s.wi = normalize(reflect(wo, *sampled));
  // Recompute the half vector from (wo, wi), as pdf() and eval() do since they only see
  // the pair: s.pdf then equals pdf(wo, wi) bit for bit, which MIS weights rely on.
  Vec3f wm;
  if (!halfVector(wo, s.wi, &wm)) return s;  // reflected below the horizon
  s.pdf = smithG1(wo, alpha) * D_GGX(wm, alpha) / (4.0f * wo.z);
  if (!(s.pdf > 0)) return s;
  // f cos / pdf = F G2 / G1(wo): D and the Jacobian cancel, so the weight stays finite
  // even for near-mirror lobes where D and pdf are huge.
  s.weight = F_Schlick(F0, dot(wo, wm)) * (smithG2(wo, s.wi, alpha) / smithG1(wo, alpha));
  s.valid = true;
  return s;
}

}  // namespace glint
