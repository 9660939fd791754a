// The obviously correct irradiance estimator the relighting tests compare against: many
// independent cosine-distributed rays, each bringing the light the renderer's paths bring.
#pragma once

#include <memory>

#include "math/frame.h"
#include "math/rng.h"
#include "math/sampling.h"
#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_path.h"
#include "scene/gaussians.h"

namespace glint::test {

// Brute-force irradiance at Gaussian g: pi x the mean radiance of many independent
// cosine-distributed rays (with random numbers of their own): the blended diffuse colour
// each meets, plus `bounces` reflected segments from there as the renderer traces them.
inline Rgb bruteForceIrradiance(const GaussianTracer& tracer, const GaussianScene& scene, uint32_t g, int rays,
                                int bounces = 0) {
  Vec3f n = normalize(scene.normal[g]);
  Framef frame = Framef::fromNormal(n);
  Rng rng = Rng::forKeys({77, g});
  PathSettings path;
  path.bounces = bounces;
  Rgb sum(0.0f);
  for (int k = 0; k < rays; ++k) {
    Vec3f w = normalize(frame.toWorld(sampleCosineHemisphere({rng.uniform(), rng.uniform()})));
    const PathResult r = tracePath(tracer, {scene.position[g] + n * 1e-3f, w, 0.0f, 0.1f}, path, 79, g, 0, uint64_t(k));
    sum += r.first.diffuse + r.specular;
  }
  return sum * (kPi / float(rays));
}

// The fast tracer, built over the scene with the default settings.
inline std::unique_ptr<GaussianTracer> tracerOf(const GaussianScene& scene) {
  std::unique_ptr<GaussianTracer> tracer = makeGaussianTracer("fast");
  tracer->build(scene, TraceSettings());
  return tracer;
}

}  // namespace glint::test
