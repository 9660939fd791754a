// Lambertian diffuse reflection.
#include "bsdf/lambert.h"

#include "math/sampling.h"

namespace glint {

Rgb LambertLobe::eval(const Vec3f& wo, const Vec3f& wi) const {
  // Lambert 1760: constant radiance in every direction, f = albedo / pi.
  if (!(wo.z > 0) || !(wi.z > 0)) return Rgb(0.0f);
  return albedo * (wi.z * kInvPi);
}

float LambertLobe::pdf(const Vec3f& wo, const Vec3f& wi) const {
  if (!(wo.z > 0) || !(wi.z > 0)) return 0.0f;
  return cosineHemispherePdf(wi.z);
}

BsdfSample LambertLobe::sample(const Vec3f& wo, Vec2f u) const {
  BsdfSample s;
  if (!(wo.z > 0)) return s;
  s.wi = sampleCosineHemisphere(u);
  // The disk boundary maps onto the horizon, where the density vanishes.
  if (!(s.wi.z > 0)) return s;
  s.pdf = cosineHemispherePdf(s.wi.z);
  s.weight = albedo;
  s.valid = true;
  return s;
}

}  // namespace glint
