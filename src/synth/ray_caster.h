// Closest-hit and occlusion queries against a MeshScene's geometry, through Embree 3.
#pragma once

#include <memory>

#include "math/vec.h"
#include "synth/mesh_scene.h"

namespace glint {

// A ray-surface intersection with everything shading needs.
struct SurfaceHit {
  float t = 0;          // distance along the (unit) ray direction
  Vec3f position;
  Vec3f geometricNormal;  // unit, facing the side the ray came from
  Vec3f shadingNormal;    // unit, interpolated, on the same side as geometricNormal
  Vec2f uv;
  int material = 0;
  // Emitter identification for MIS: index into the caster's emissive-triangle list or -1.
  int mesh = -1;        // -1 for spheres
  int triangle = -1;
  bool frontFacing = true;  // the ray hit the side the surface's own normal points to
};

class RayCaster {
 public:
  explicit RayCaster(const MeshScene& scene);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  // Closest hit along origin + t dir for t in (tMin, tMax); false if none. dir is unit length.
  bool intersect(const Vec3f& origin, const Vec3f& dir, float tMin, float tMax, SurfaceHit* hit) const;
  // True if anything blocks the segment (tMin, tMax).
  bool occluded(const Vec3f& origin, const Vec3f& dir, float tMin, float tMax) const;

  // Rays traced so far (closest-hit and occlusion), summed over threads; for benchmarks.
  uint64_t rayCount() const;
  void resetRayCount();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Offset for a ray leaving a surface point: far enough to escape self-intersection given
// float error at that magnitude, small enough not to skip thin features.
inline Vec3f offsetRayOrigin(const Vec3f& p, const Vec3f& geometricNormal, const Vec3f& dir) {
  float scale = 1e-4f * (1.0f + maxComponent(Vec3f(std::abs(p.x), std::abs(p.y), std::abs(p.z))));
  return p + geometricNormal * (dot(dir, geometricNormal) >= 0 ? scale : -scale);
}

}  // namespace glint
