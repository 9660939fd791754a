// L1 losses of one ray and their gradient.
#include "train/ray_loss.h"

#include <cmath>

namespace glint {

namespace {

float sign(float x) { return x > 0 ? 1.0f : x < 0 ? -1.0f : 0.0f; }
Vec3f sign(const Vec3f& v) { return {sign(v.x), sign(v.y), sign(v.z)}; }
double absSum(const Vec3f& v) { return double(std::abs(v.x)) + std::abs(v.y) + std::abs(v.z); }

// The colour the colour term compares with its target: the first diffuse, or the final image.
Rgb fittedColour(const RayResult& r, const PixelTarget& t, const Rgb& pathSpecular) {
  return t.finalColour ? r.diffuse + pathSpecular : r.diffuse;
}

}  // namespace

LossTerms rayLoss(const RayResult& r, const PixelTarget& t, const LossNormalisation& n, const Rgb& pathSpecular) {
  LossTerms terms;
  terms.diffuse = absSum(fittedColour(r, t, pathSpecular) - t.diffuse) / (3 * n.diffuseRays);
  if (t.surface) {
    if (t.hasDepth) terms.depth = std::abs(double(r.depth) - t.depth) / n.surfaceRays;
    if (t.hasNormal) terms.normal = absSum(r.normal - t.normal) / (3 * n.surfaceRays);
    if (t.hasRoughness) terms.roughness = std::abs(double(r.roughness) - t.roughness) / n.surfaceRays;
    if (t.hasF0) terms.f0 = absSum(r.f0 - t.f0) / (3 * n.surfaceRays);
  }
  return terms;
}

RayResultAdjoint rayLoss_vjp(const RayResult& r, const PixelTarget& t, const LossNormalisation& n,
                             const LossWeights& w, const Rgb& pathSpecular) {
  RayResultAdjoint v;
  v.v_diffuse = sign(fittedColour(r, t, pathSpecular) - t.diffuse) * float(w.diffuse / (3 * n.diffuseRays));
  if (t.surface) {
    if (t.hasDepth) v.v_depth = sign(r.depth - t.depth) * float(w.depth / n.surfaceRays);
    if (t.hasNormal) v.v_normal = sign(r.normal - t.normal) * float(w.normal / (3 * n.surfaceRays));
    if (t.hasRoughness) v.v_roughness = sign(r.roughness - t.roughness) * float(w.roughness / n.surfaceRays);
    if (t.hasF0) v.v_f0 = sign(r.f0 - t.f0) * float(w.f0 / (3 * n.surfaceRays));
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
