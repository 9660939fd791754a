// Lambert + Cook-Torrance mixture: evaluation, mixture density and lobe-selection sampling.
#include "bsdf/principled.h"

#include <algorithm>

#include "bsdf/fresnel.h"
#include "bsdf/microfacet.h"

namespace glint {

float PrincipledBrdf::alphaFromRoughness(float perceptualRoughness) {
  // Burley 2012, "Physically-Based Shading at Disney": alpha = roughness^2 makes the
  // roughness parameter perceptually linear.
  float r = std::clamp(perceptualRoughness, 0.0f, 1.0f);
  return std::max(r * r, kMinGgxAlpha);
}

float PrincipledBrdf::specularProbability(const Vec3f& wo) const {
  // Estimate each lobe's reflectance: the diffuse albedo, and Schlick's Fresnel at the
  // viewing angle for the specular lobe (its albedo is close to F for smooth surfaces).
  float diffuse = std::max(luminance(diffuseAlbedo), 0.0f);
  float specular = std::max(luminance(F_Schlick(F0, wo.z)), 0.0f);
  if (diffuse == 0) return 1.0f;  // a metal: never waste samples on a zero lobe
  if (specular == 0) return 0.0f;
  float p = specular / (specular + diffuse);
  return std::clamp(p, kMinLobeProbability, 1.0f - kMinLobeProbability);
}

Rgb PrincipledBrdf::eval(const Vec3f& wo, const Vec3f& wi) const {
  return diffuseLobe().eval(wo, wi) + specularLobe().eval(wo, wi);
}

float PrincipledBrdf::pdf(const Vec3f& wo, const Vec3f& wi) const {
  float pSpecular = specularProbability(wo);
  return pSpecular * specularLobe().pdf(wo, wi) + (1.0f - pSpecular) * diffuseLobe().pdf(wo, wi);
}

BsdfSample PrincipledBrdf::sample(const Vec3f& wo, Vec2f u) const {
  if (!(wo.z > 0)) return {};
  float pSpecular = specularProbability(wo);
  // Pick a lobe with u.x, then stretch the chosen interval of u.x back to [0, 1).
  constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;
  BsdfSample s;
  if (u.x < pSpecular) {
    u.x = std::min(u.x / pSpecular, kOneMinusEpsilon);
    s = specularLobe().sample(wo, u);
  } else {
    u.x = std::min((u.x - pSpecular) / (1.0f - pSpecular), kOneMinusEpsilon);
    s = diffuseLobe().sample(wo, u);
  }
  if (!s.valid) return s;
  // One-sample MIS (Veach 1997, section 9.2.4) with the balance heuristic: weight by the
  // full mixture density so the estimate is unbiased whichever lobe produced wi.
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0)) return {};
  s.weight = eval(wo, s.wi) / s.pdf;
  return s;
}

}  // namespace glint
