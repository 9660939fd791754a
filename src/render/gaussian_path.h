// Paths through the Gaussians (paper sections 3.1-3.2): the first segment gives the blended
// diffuse colour and G-buffers; each later segment leaves the expected termination point
// of the previous one in a direction drawn from the GGX distribution of visible normals
// for the blended roughness, and returns the blended diffuse colour of what it hits (the
// cached irradiance of equation 3), weighted by the Cook-Torrance throughput.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "raytrace/gaussian_tracer.h"

namespace glint {

struct PathSettings {
  int bounces = 0;  // segments after the first; the paper's default is 2 (path length 3)
  // A blended normal shorter than this before normalisation is invalid and ends the path
  // (paper text 0.6, the authors' code 0.7).
  float invalidNormalLength = 0.7f;
  float minRoughness = 0.01f;  // alpha = max(roughness, this)^2
  float normalOffset = 1e-3f;  // reflection origins move this far along the normal
  // Reflection rays ignore back-facing Gaussians this close to their origin (appendix B).
  float backfaceSkip = 0.1f;
  size_t hitListCapacity = 512;  // of the hit lists recorded in PathSegment
};

// Reflected segments whose light PathResult also keeps one by one (the viewer's per-bounce
// modes); the light of later segments is only in the sum.
constexpr int kSeparateBounces = 8;

// One path's outputs: the first segment's result and the specular light of the later ones.
struct PathResult {
  RayResult first;
  Rgb specular;      // sum over segments k >= 1 of throughput_k x blended diffuse_k
  // bounceLight[k - 1] = throughput_k x blended diffuse_k of segment k (zero where the path
  // ended earlier): the terms of `specular`, for k <= kSeparateBounces.
  std::array<Rgb, kSeparateBounces> bounceLight{};
  int segments = 1;  // segments traced
};

// One traced segment, recorded for inspection (glint render --debug-pixel).
struct PathSegment {
  TraceRay ray;
  Rgb throughput;  // weight of this segment's blended diffuse in the specular sum (1 for the first)
  RayResult result;
  HitList hits;    // its composited hits, front to back
};

// The direction of segment k is drawn with sample `sample` of the stratified stream
// hashKeys({seed, view, pixel, k}) (math/owen_sobol.h), so any path can be re-run alone
// from its keys (seed, view, pixel, sample), and the samples of one pixel are stratified.
// With `segments`, every segment is traced with its hit list and recorded in the first
// PathResult::segments entries (entries beyond them are left from earlier paths, so their
// memory is reused).
PathResult tracePath(const GaussianTracer& tracer, const TraceRay& primary, const PathSettings& settings,
                     uint64_t seed, uint64_t view, uint64_t pixel, uint64_t sample,
                     std::vector<PathSegment>* segments = nullptr);

}  // namespace glint
