// The per-ray L1 losses of the first segment (paper section 3.2): diffuse, and the G-buffer
// terms depth, normal (optionally Huber, LossWeights::normalHuber), roughness and F0,
// masked where the pixel has no surface; with the _vjp that starts the backward pass.
#pragma once

#include <cmath>

#include "math/vec.h"
#include "raytrace/ray_backward.h"
#include "raytrace/ray_result.h"
#include "train/train_config.h"

namespace glint {

// Ground truth of one training pixel (linear values, docs/data-format.md).
struct PixelTarget {
  Rgb diffuse;
  Rgb specular;
  float depth = 0;
  Vec3f normal;
  float roughness = 0;
  Rgb f0;
  bool surface = false;  // hasSurface(depth): the G-buffer terms apply
  // Which terms the dataset supervises (a predictor may give only some buffers).
  bool hasSpecular = true, hasDepth = true, hasNormal = true, hasRoughness = true, hasF0 = true;
  // `diffuse` holds the final image (the render buffer): the first segment's diffuse plus
  // the path's specular is fitted to it.
  bool finalColour = false;
  // F0 came from a predicted metalness (grey by the white-base rule) of a metal: only its
  // brightest channel is compared, so the metal's tint is left to the reflection loss L_r.
  bool f0BrightnessOnly = false;
  // With f0BrightnessOnly, the share of the F0 term that still compares every channel
  // (LossWeights::f0TintPrior): 0 leaves the tint to L_r alone, 1 is the plain term.
  float f0TintPrior = 0;
  // The view's photograph (its render buffer), fitted by diffuse + specular beside the
  // priors when LossWeights::photograph > 0 (photographLoss).
  Rgb photograph;
  bool hasPhotograph = false;
};

// Each term is the mean absolute error over the batch (and the term's channels); the
// G-buffer terms average over the batch's surface pixels only.
struct LossNormalisation {
  double diffuseRays = 1;  // rays in the batch
  double surfaceRays = 1;  // rays of the batch whose pixel has a surface
};

// Unweighted terms (sums over rays of per-ray contributions, already normalised), so that
// summing them over a batch gives the batch's mean errors.
struct LossTerms {
  double diffuse = 0, depth = 0, normal = 0, roughness = 0, f0 = 0;
  double specular = 0;    // L_r, once reflections are trained
  double photograph = 0;  // photographLoss, once reflections are trained (LossWeights::photograph)

  double weighted(const LossWeights& w) const {
    return w.diffuse * diffuse + w.depth * depth + w.normal * normal + w.roughness * roughness + w.f0 * f0 +
           w.specular * specular + w.photograph * photograph;
  }
  LossTerms& operator+=(const LossTerms& o) {
    diffuse += o.diffuse, depth += o.depth, normal += o.normal, roughness += o.roughness, f0 += o.f0;
    specular += o.specular, photograph += o.photograph;
    return *this;
  }
};

// Whether a pixel's rendered depth lies within `band` (a fraction) of its prior's, so that
// the depth term counts it (LossWeights::depthBand; always with band 0).
inline bool withinDepthBand(float rendered, float prior, float band) {
  return band <= 0.0f || std::abs(rendered - prior) <= band * prior;
}

// The normal term's per-component penalty: |x| with width 0, else Huber's, x^2 / (2 width)
// within the width and |x| - width / 2 beyond (the L1 slope, so that a weight means the same
// for large errors); and its derivative.
double normalPenalty(float x, float width);
float normalPenalty_vjp(float x, float width);

// One ray's contribution to each term. pathSpecular is the path's specular sum (0 before
// reflections are trained): with target.finalColour the colour term fits diffuse + specular.
// normalHuber is LossWeights::normalHuber (0: the L1 of every term).
LossTerms rayLoss(const RayResult& r, const PixelTarget& target, const LossNormalisation& n,
                  const Rgb& pathSpecular = Rgb(0.0f), float normalHuber = 0.0f);

// The reflection term L_r = mean |specular - target| over the batch's rays and channels,
// and its gradient with respect to the path's specular sum (weights.specular included).
double specularLoss(const Rgb& specular, const PixelTarget& target, const LossNormalisation& n);
Rgb specularLoss_vjp(const Rgb& specular, const PixelTarget& target, const LossNormalisation& n,
                     const LossWeights& weights);

// The photograph term = mean |diffuse + specular - photograph| over the batch's rays and
// channels (diffuse the first segment's, specular the path's sum), and its gradient with
// respect to that sum (weights.photograph included), which is both dL/d diffuse and dL/d
// specular. Meant for target.hasPhotograph only.
double photographLoss(const Rgb& diffusePlusSpecular, const PixelTarget& target, const LossNormalisation& n);
Rgb photographLoss_vjp(const Rgb& diffusePlusSpecular, const PixelTarget& target, const LossNormalisation& n,
                       const LossWeights& weights);

// dL/d result for L = rayLoss(...).weighted(weights); d|x|/dx = sign(x), 0 at 0. With
// target.finalColour the colour term's gradient with respect to the path's specular sum
// equals v_diffuse (the caller adds it to the specular adjoint).
RayResultAdjoint rayLoss_vjp(const RayResult& r, const PixelTarget& target, const LossNormalisation& n,
                             const LossWeights& weights, const Rgb& pathSpecular = Rgb(0.0f));

}  // namespace glint
