// Next-event estimation: picks a light (emissive triangles, punctual lights, environment)
// and a point on it, and gives the solid-angle densities that multiple importance
// sampling needs for BSDF-sampled rays that hit emitters.
#pragma once

#include <vector>

#include "math/sampling.h"
#include "math/vec.h"
#include "synth/mesh_scene.h"

namespace glint {

struct LightSample {
  Vec3f wi;            // unit direction from the shaded point towards the light
  float distance = 0;  // to the light point; infinity for the environment and directional lights
  Rgb radiance;        // arriving radiance (area, environment) or irradiance-like value (delta lights)
  float pdf = 0;       // solid-angle density including the light choice; 0 = no sample
  bool isDelta = false;  // punctual/directional: cannot be hit by BSDF sampling, no MIS
};

class LightSampler {
 public:
  explicit LightSampler(const MeshScene& scene);

  bool empty() const { return choice_.size() == 0; }
  // Samples light arriving at point p. u1 chooses the light, u2 the point on it.
  LightSample sample(const Vec3f& p, float u1, Vec2f u2) const;

  // Radiance of the environment seen along dir (unit).
  Rgb environmentRadiance(const Vec3f& dir) const;
  // Solid-angle density with which sample() produces direction dir escaping to the environment.
  float environmentPdf(const Vec3f& dir) const;
  // Solid-angle density with which sample() picks this point on an emissive triangle, seen
  // from p: for MIS when a BSDF-sampled ray hits it.
  float emitterPdf(const Vec3f& p, const Vec3f& hitPoint, const Vec3f& hitNormal, int mesh, int triangle) const;

 private:
  struct Emitter {
    int mesh;
    int triangle;
    float area;
  };
  enum class Kind { Emitters, Punctual, Environment };
  struct Choice {
    Kind kind;
    int index;  // punctual light index
  };

  const MeshScene& scene_;
  std::vector<Emitter> emitters_;
  std::vector<int> emitterLookup_;  // per mesh: offset of its first triangle in emitters_, or -1
  Distribution1D emitterDistribution_;
  std::vector<Choice> choices_;
  Distribution1D choice_;
  float emitterChoiceProbability_ = 0;
  float environmentChoiceProbability_ = 0;
  Distribution2D environmentDistribution_;
  float sceneRadius_ = 1;
};

// Equirectangular mapping of a direction (Y up) to [0,1)^2, and back.
Vec2f directionToEquirect(const Vec3f& dir, float rotationY);
Vec3f equirectToDirection(Vec2f uv, float rotationY);

}  // namespace glint
