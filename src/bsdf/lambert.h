// The Lambertian diffuse lobe f_d = albedo / pi, sampled with a cosine-weighted hemisphere.
#pragma once

#include "bsdf/bsdf_sample.h"
#include "math/vec.h"

namespace glint {

// Reflection only: zero unless both wo and wi lie above the surface (local frame, normal = +z).
struct LambertLobe {
  Rgb albedo{0.0f};

  // f_d cos(theta_i) = albedo cos(theta_i) / pi.
  Rgb eval(const Vec3f& wo, const Vec3f& wi) const;
  // cos(theta_i) / pi.
  float pdf(const Vec3f& wo, const Vec3f& wi) const;
  // weight = albedo exactly, since the density is proportional to f cos.
  BsdfSample sample(const Vec3f& wo, Vec2f u) const;
};

}  // namespace glint
