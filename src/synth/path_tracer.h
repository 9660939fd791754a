// The reference Monte Carlo path tracer of the ground-truth generator. At the first
// surface it splits light transport as the paper's equation 2: the diffuse buffer is the
// light leaving through the Lambert lobe, the specular buffer the light leaving through
// the Cook-Torrance lobe; deeper vertices sample the full BRDF. Next-event estimation and
// BSDF sampling are combined with multiple importance sampling (power heuristic).
#pragma once

#include "math/rng.h"
#include "math/vec.h"
#include "synth/light_sampler.h"
#include "synth/mesh_scene.h"
#include "synth/ray_caster.h"

namespace glint {

struct PathTracerSettings {
  // Maximum number of surface interactions on a path (pbrt's maxdepth): 1 = direct light only.
  int maxBounces = 6;
  // Russian roulette starts after this many interactions.
  int rouletteStart = 3;
};

// Radiance estimates of one camera sample, split at the first surface.
struct RadianceSample {
  Rgb diffuse;   // light through the diffuse lobe at the first surface, + emission/environment seen directly
  Rgb specular;  // light through the specular lobe at the first surface
  Rgb render() const { return diffuse + specular; }
};

// Geometry and material of the first surface along a ray (the G-buffer of a pixel).
struct FirstHit {
  bool hit = false;
  float depth = 0;  // distance along the ray (0 when nothing is hit)
  Vec3f normal;     // world-space shading normal, facing the camera (0 when nothing is hit)
  float roughness = 0;
  Rgb F0;
};

class PathTracer {
 public:
  PathTracer(const MeshScene& scene, const RayCaster& caster, const LightSampler& lights, PathTracerSettings settings);

  RadianceSample trace(const Vec3f& origin, const Vec3f& dir, Rng& rng) const;
  FirstHit firstHit(const Vec3f& origin, const Vec3f& dir) const;

 private:
  struct Vertex;
  // Radiance arriving along a ray leaving a surface, the BSDF density that chose it given
  // for MIS with emitters it may hit; depth counts the interactions so far.
  Rgb continuePath(Vec3f origin, Vec3f dir, float bsdfPdf, int depth, Rng& rng) const;
  Vertex makeVertex(const SurfaceHit& hit, const Vec3f& dir) const;

  const MeshScene& scene_;
  const RayCaster& caster_;
  const LightSampler& lights_;
  PathTracerSettings settings_;
};

}  // namespace glint
