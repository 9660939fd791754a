// L1 losses of one ray and their gradient.
#include "train/ray_loss.h"

#include <cmath>

namespace glint {

namespace {

float sign(float x) { return x > 0 ? 1.0f : x < 0 ? -1.0f : 0.0f; }
Vec3f sign(const Vec3f& v) { return {sign(v.x), sign(v.y), sign(v.z)}; }
double absSum(const Vec3f& v) { return double(std::abs(v.x)) + std::abs(v.y) + std::abs(v.z); }

}  // namespace

LossTerms rayLoss(const RayResult& r, const PixelTarget& t, const LossNormalisation& n) {
  LossTerms terms;
  terms.diffuse = absSum(r.diffuse - t.diffuse) / (3 * n.diffuseRays);
  if (t.surface) {
    terms.depth = std::abs(double(r.depth) - t.depth) / n.surfaceRays;
    terms.normal = absSum(r.normal - t.normal) / (3 * n.surfaceRays);
    terms.roughness = std::abs(double(r.roughness) - t.roughness) / n.surfaceRays;
    terms.f0 = absSum(r.f0 - t.f0) / (3 * n.surfaceRays);
  }
  return terms;
}

RayResultAdjoint rayLoss_vjp(const RayResult& r, const PixelTarget& t, const LossNormalisation& n,
                             const LossWeights& w) {
  RayResultAdjoint v;
  v.v_diffuse = sign(r.diffuse - t.diffuse) * float(w.diffuse / (3 * n.diffuseRays));
  if (t.surface) {
    v.v_depth = sign(r.depth - t.depth) * float(w.depth / n.surfaceRays);
    v.v_normal = sign(r.normal - t.normal) * float(w.normal / (3 * n.surfaceRays));
    v.v_roughness = sign(r.roughness - t.roughness) * float(w.roughness / n.surfaceRays);
    v.v_f0 = sign(r.f0 - t.f0) * float(w.f0 / (3 * n.surfaceRays));
  }
  return v;
}

double specularLoss(const Rgb& specular, const PixelTarget& t, const LossNormalisation& n) {
  return absSum(specular - t.specular) / (3 * n.diffuseRays);
}

Rgb specularLoss_vjp(const Rgb& specular, const PixelTarget& t, const LossNormalisation& n, const LossWeights& w) {
  return sign(specular - t.specular) * float(w.specular / (3 * n.diffuseRays));
}

}  // namespace glint
