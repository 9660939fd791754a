// The paper's Disney subset BRDF: Lambert diffuse plus Cook-Torrance GGX specular.
//
// f(wo, wi) = f_d + f_s with f_d = diffuseAlbedo / pi and f_s the Cook-Torrance lobe
// (GGX D, height-correlated Smith G2, Schlick F; see cook_torrance.h). The two lobes are
// simply added: no (1 - F) factor couples the diffuse lobe to the specular one, because the
// paper defines f = f_d + f_s and its diffuse / specular buffers must sum to the render.
// Energy conservation is therefore the material's job: metals have zero diffuse albedo and
// dielectrics a small F0 (see SurfaceMaterial in synth/mesh_scene.h).
//
// Sampling picks one lobe with a probability that estimates its share of the reflected
// energy and weights the result by the full mixture density (one-sample MIS with the
// balance heuristic), so the estimator is unbiased whichever lobe was picked.
#pragma once

#include "bsdf/bsdf_sample.h"
#include "bsdf/cook_torrance.h"
#include "bsdf/lambert.h"
#include "math/vec.h"

namespace glint {

struct PrincipledBrdf {
  Rgb diffuseAlbedo{0.0f};  // Lambert albedo, (1 - metallic) baseColor
  Rgb F0{0.04f};            // specular reflectance at normal incidence
  float alpha = 0.25f;      // GGX alpha; clamped to kMinGgxAlpha by the specular lobe

  // Smallest probability given to a lobe that can reflect anything. The selection
  // probabilities are only estimates (they ignore masking and the Fresnel of each
  // microfacet), and a lobe starved of samples shows up as fireflies.
  static constexpr float kMinLobeProbability = 0.1f;

  // GGX alpha = perceptualRoughness^2 (Burley 2012, "Physically-Based Shading at Disney"),
  // roughness clamped to [0, 1] and alpha to at least kMinGgxAlpha.
  static float alphaFromRoughness(float perceptualRoughness);

  LambertLobe diffuseLobe() const { return LambertLobe{diffuseAlbedo}; }
  CookTorranceLobe specularLobe() const { return CookTorranceLobe(F0, alpha); }

  // Probability that sample() picks the specular lobe for this wo.
  float specularProbability(const Vec3f& wo) const;

  // (f_d + f_s)(wo, wi) cos(theta_i); wo and wi in the local frame (normal = +z).
  Rgb eval(const Vec3f& wo, const Vec3f& wi) const;
  // Mixture density p_s pdf_s + (1 - p_s) pdf_d of sample().
  float pdf(const Vec3f& wo, const Vec3f& wi) const;
  // u.x picks the lobe and is then rescaled to [0, 1) for that lobe's own sampling.
  BsdfSample sample(const Vec3f& wo, Vec2f u) const;
};

}  // namespace glint
