// The losses of one ray (L1; the normal term optionally Huber) and their gradient.
#include "train/ray_loss.h"

#include <algorithm>
#include <cmath>

namespace glint {

namespace {

float sign(float x) { return x > 0 ? 1.0f : x < 0 ? -1.0f : 0.0f; }
Vec3f sign(const Vec3f& v) { return {sign(v.x), sign(v.y), sign(v.z)}; }
double absSum(const Vec3f& v) { return double(std::abs(v.x)) + std::abs(v.y) + std::abs(v.z); }

// The channel holding the largest value (the first of equals).
int brightestChannel(const Rgb& c) { return c.y > c.x ? (c.z > c.y ? 2 : 1) : (c.z > c.x ? 2 : 0); }

// The F0 term of one ray: the mean absolute error of its channels, or with
// target.f0BrightnessOnly that of the brightest channels alone (one value, so not divided
// by 3: a grey error scores the same either way), blended with the mean over every channel
// by target.f0TintPrior (kappa):
//   (1 - kappa) |F0_b - t_b| + kappa sum_c |F0_c - t_c| / 3.
double f0Error(const Rgb& f0, const PixelTarget& t) {
  const double all = absSum(f0 - t.f0) / 3;
  if (!t.f0BrightnessOnly) return all;
  const double brightness = std::abs(double(f0[brightestChannel(f0)]) - t.f0[brightestChannel(t.f0)]);
  return (1.0 - t.f0TintPrior) * brightness + t.f0TintPrior * all;
}

Rgb f0Error_vjp(const Rgb& f0, const PixelTarget& t) {
  const Rgb all = sign(f0 - t.f0) * (1.0f / 3.0f);
  if (!t.f0BrightnessOnly) return all;
  Rgb v = all * t.f0TintPrior;
  const int c = brightestChannel(f0);
  v[c] += (1.0f - t.f0TintPrior) * sign(f0[c] - t.f0[brightestChannel(t.f0)]);
  return v;
}

// The mean absolute error of one ray's colour against a target, per batch ray and channel
// (the colour, reflection and photograph terms), and its gradient times the term's weight.
double colourError(const Rgb& colour, const Rgb& target, const LossNormalisation& n) {
  return absSum(colour - target) / (3 * n.diffuseRays);
}
Rgb colourError_vjp(const Rgb& colour, const Rgb& target, const LossNormalisation& n, float weight) {
  return sign(colour - target) * float(weight / (3 * n.diffuseRays));
}

// The colour the colour term compares with its target: the first diffuse, or the final image.
Rgb fittedColour(const RayResult& r, const PixelTarget& t, const Rgb& pathSpecular) {
  return t.finalColour ? r.diffuse + pathSpecular : r.diffuse;
}

double normalError(const Vec3f& e, float width) {
  return normalPenalty(e.x, width) + normalPenalty(e.y, width) + normalPenalty(e.z, width);
}

}  // namespace

double normalPenalty(float x, float width) {
  const double a = std::abs(double(x));
  if (width <= 0) return a;
  return a >= width ? a - 0.5 * width : a * a / (2.0 * width);
}

float normalPenalty_vjp(float x, float width) {
  if (width <= 0) return sign(x);
  return std::clamp(x / width, -1.0f, 1.0f);
}

LossTerms rayLoss(const RayResult& r, const PixelTarget& t, const LossNormalisation& n, const Rgb& pathSpecular,
                  float normalHuber) {
  LossTerms terms;
  terms.diffuse = colourError(fittedColour(r, t, pathSpecular), t.diffuse, n);
  if (t.surface) {
    if (t.hasDepth) terms.depth = std::abs(double(r.depth) - t.depth) / n.surfaceRays;
    if (t.hasNormal) terms.normal = normalError(r.normal - t.normal, normalHuber) / (3 * n.surfaceRays);
    if (t.hasRoughness) terms.roughness = std::abs(double(r.roughness) - t.roughness) / n.surfaceRays;
    if (t.hasF0) terms.f0 = f0Error(r.f0, t) / n.surfaceRays;
  }
  return terms;
}

RayResultAdjoint rayLoss_vjp(const RayResult& r, const PixelTarget& t, const LossNormalisation& n,
                             const LossWeights& w, const Rgb& pathSpecular) {
  RayResultAdjoint v;
  v.v_diffuse = colourError_vjp(fittedColour(r, t, pathSpecular), t.diffuse, n, w.diffuse);
  if (t.surface) {
    if (t.hasDepth) v.v_depth = sign(r.depth - t.depth) * float(w.depth / n.surfaceRays);
    if (t.hasNormal) {
      const Vec3f e = r.normal - t.normal;
      const Vec3f slope(normalPenalty_vjp(e.x, w.normalHuber), normalPenalty_vjp(e.y, w.normalHuber),
                        normalPenalty_vjp(e.z, w.normalHuber));
      v.v_normal = slope * float(w.normal / (3 * n.surfaceRays));
    }
    if (t.hasRoughness) v.v_roughness = sign(r.roughness - t.roughness) * float(w.roughness / n.surfaceRays);
    if (t.hasF0) v.v_f0 = f0Error_vjp(r.f0, t) * float(w.f0 / n.surfaceRays);
  }
  return v;
}

double specularLoss(const Rgb& specular, const PixelTarget& t, const LossNormalisation& n) {
  return colourError(specular, t.specular, n);
}

Rgb specularLoss_vjp(const Rgb& specular, const PixelTarget& t, const LossNormalisation& n, const LossWeights& w) {
  return colourError_vjp(specular, t.specular, n, w.specular);
}

double photographLoss(const Rgb& diffusePlusSpecular, const PixelTarget& t, const LossNormalisation& n) {
  return colourError(diffusePlusSpecular, t.photograph, n);
}

Rgb photographLoss_vjp(const Rgb& diffusePlusSpecular, const PixelTarget& t, const LossNormalisation& n,
                       const LossWeights& w) {
  return colourError_vjp(diffusePlusSpecular, t.photograph, n, w.photograph);
}

}  // namespace glint
