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

// The step from segment k - 1 (traced along `ray`, giving `result`) to segment k >= 1:
// false when the path ends there (an invalid blended normal or an invalid sample); else
// the next segment's ray and the factor its throughput gains.
GLINT_CPU_GPU inline bool continuePath(const TraceRay& ray, const RayResult& result, const PathSettings& settings, uint64_t seed,
                  const PathKey& key, int k, TraceRay* next, Rgb* weight) {
  if (!(result.normalLength >= settings.invalidNormalLength)) return false;
  if (settings.minReflectance > 0 && std::max({result.f0.x, result.f0.y, result.f0.z}) < settings.minReflectance)
    return false;
  Vec3f n = result.normal / result.normalLength;
  // Blended normals may face away from the incoming ray (Gaussians seen from behind);
  // the surface is then taken as seen from the ray's side.
  if (dot(n, ray.direction) > 0) n = -n;
  Frame<float> frame = Frame<float>::fromNormal(n);
  Vec3f wo = frame.toLocal(-ray.direction);
  float rho = std::max(std::clamp(result.roughness, 0.0f, 1.0f), settings.minRoughness);
  CookTorranceLobe lobe(result.f0, rho * rho);
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

}  // namespace glint
