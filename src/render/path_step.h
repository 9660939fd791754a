// One step of a path through the Gaussians, for the CPU and the GPU: the path settings,
// the keys of a path's random numbers, and the GGX-sampled reflected segment that follows
// a traced one (paper sections 3.1-3.2).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "bsdf/cook_torrance.h"
#include "core/cpu_gpu.h"
#include "math/frame.h"
#include "math/owen_sobol.h"
#include "raytrace/gaussian_tracer.h"

namespace glint {

// The order in which a wavefront's reflected rays go to traceBatch: as their paths come
// (pixel order), or sorted by origin and direction octant (render_bench and train_bench
// measure both).
enum class ReflectedRayOrder { PathOrder, OriginAndOctant };

struct PathSettings {
  int bounces = 0;  // segments after the first; the paper's default is 2 (path length 3)
  // A blended normal shorter than this before normalisation is invalid and ends the path
  // (paper text 0.6, the authors' code 0.7).
  float invalidNormalLength = 0.7f;
  float minRoughness = 0.01f;  // alpha = max(roughness, this)^2
  float normalOffset = 1e-3f;  // reflection origins move this far along the normal
  // Reflection rays ignore back-facing Gaussians this close to their origin (appendix B).
  float backfaceSkip = 0.1f;
  // A path ends where the blended F0 it meets is below this in every channel (0: never).
  // Relighting ends its rays at dielectrics, which reflect a few percent.
  float minReflectance = 0.0f;
  size_t hitListCapacity = 512;  // of the hit lists recorded in PathSegment
  ReflectedRayOrder reflectedOrder = ReflectedRayOrder::OriginAndOctant;  // PathBatch only; no effect on results
  // PathBatch only, no effect on results: the first segments are camera rays of whole
  // images (Coherent), or pixels scattered over images (training's batches).
  RayCoherence primaryCoherence = RayCoherence::Coherent;
};

// The keys of a path's random numbers: the direction of segment k is drawn with sample
// `sample` of the stratified stream hashKeys({seed, view, pixel, k}) (math/owen_sobol.h),
// so any path can be re-run alone from its keys, and the samples of one pixel are
// stratified.
struct PathKey {
  uint64_t view = 0, pixel = 0, sample = 0;
};

// The GGX alpha of a blended roughness r: max(clamp(r, 0, 1), minRoughness)^2, at least
// kMinGgxAlpha (clampGgxAlpha, as CookTorranceLobe clamps), and d alpha / d r (0 where a
// clamp holds).
struct LobeAlpha {
  float alpha = kMinGgxAlpha;
  float dAlphaDRoughness = 0;
};

GLINT_CPU_GPU inline LobeAlpha lobeAlpha(float roughness, float minRoughness) {
  float rho = std::max(std::clamp(roughness, 0.0f, 1.0f), minRoughness);
  float squared = rho * rho;
  LobeAlpha a;
  a.alpha = clampGgxAlpha(squared);
  if (roughness > minRoughness && roughness < 1.0f && squared > kMinGgxAlpha) a.dAlphaDRoughness = 2.0f * roughness;
  return a;
}

// The shading normal of a reflection off `result` (traced along `ray`), or false where the
// blended normal is invalid and the path ends there. Blended normals may face away from
// the incoming ray (Gaussians seen from behind); the surface is then taken as seen from
// the ray's side.
GLINT_CPU_GPU inline bool reflectionNormal(const TraceRay& ray, const RayResult& result, const PathSettings& settings,
                                           Vec3f* n) {
  if (!(result.normalLength >= settings.invalidNormalLength)) return false;
  *n = result.normal / result.normalLength;
  if (dot(*n, ray.direction) > 0) *n = -*n;
  return true;
}

// The step from segment k - 1 (traced along `ray`, giving `result`) to segment k >= 1:
// false when the path ends there (an invalid blended normal or an invalid sample); else
// the next segment's ray and the factor its throughput gains.
GLINT_CPU_GPU inline bool continuePath(const TraceRay& ray, const RayResult& result, const PathSettings& settings, uint64_t seed,
                  const PathKey& key, int k, TraceRay* next, Rgb* weight) {
  Vec3f n;
  if (!reflectionNormal(ray, result, settings, &n)) return false;
  if (settings.minReflectance > 0 && std::max({result.f0.x, result.f0.y, result.f0.z}) < settings.minReflectance)
    return false;
  Frame<float> frame = Frame<float>::fromNormal(n);
  Vec3f wo = frame.toLocal(-ray.direction);
  CookTorranceLobe lobe(result.f0, lobeAlpha(result.roughness, settings.minRoughness).alpha);
  // Dimension k of the pixel's stratified stream: a pixel's samples spread their
  // directions of segment k evenly over the lobe, which at 64 samples leaves far less
  // noise on glossy surfaces than independent numbers.
  BsdfSample s =
      lobe.sample(wo, stratifiedSample2(hashKeys({seed, key.view, key.pixel, uint64_t(k)}), uint32_t(key.sample)));
  if (!s.valid) return false;
  *weight = s.weight;
  next->origin = ray.origin + ray.direction * result.depth + n * settings.normalOffset;
  next->direction = normalize(frame.toWorld(s.wi));
  next->tMin = 0.0f;
  next->backfaceSkip = settings.backfaceSkip;
  return true;
}

// How the weight w of a step (continuePath from segment k - 1, traced along `ray` and
// giving `result`, to the segment along `next`) changes with the material that chose it,
// its direction and density held fixed (docs/derivations.md D15): w = F G2 D / (4 wo.z p)
// with p detached, so d log w / d r = d log(D G2) / d alpha x d alpha / d r, and
// d log w_c / d F0_c = (1 - (1 - wo.wm)^5) / F_c per channel. Zero where the step could not
// have been taken.
struct StepMaterialDerivatives {
  float dLogWeightDRoughness = 0;
  Rgb dLogWeightDF0{0.0f};
};

GLINT_CPU_GPU inline StepMaterialDerivatives stepMaterialDerivatives(const TraceRay& ray, const RayResult& result,
                                                                     const PathSettings& settings, const Vec3f& next) {
  StepMaterialDerivatives d;
  Vec3f n, wm;
  if (!reflectionNormal(ray, result, settings, &n)) return d;
  Frame<float> frame = Frame<float>::fromNormal(n);
  const Vec3f wo = frame.toLocal(-ray.direction), wi = frame.toLocal(next);
  if (!reflectionHalfVector(wo, wi, &wm)) return d;
  const LobeAlpha a = lobeAlpha(result.roughness, settings.minRoughness);
  if (a.dAlphaDRoughness != 0) d.dLogWeightDRoughness = lobeLogAlphaDerivative(wo, wi, a.alpha) * a.dAlphaDRoughness;
  const float cosD = dot(wo, wm), dFdF0 = 1.0f - schlickWeight(cosD);
  const Rgb F = F_Schlick(result.f0, cosD);
  for (int c = 0; c < 3; ++c) d.dLogWeightDF0[c] = F[c] > 0 ? dFdF0 / F[c] : 0.0f;
  return d;
}

}  // namespace glint
