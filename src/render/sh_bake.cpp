// Per-Gaussian radiance sampling through the path tracer and the SH fit of it.
#include "render/sh_bake.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "io/tonemap.h"
#include "math/mat4.h"
#include "math/owen_sobol.h"
#include "math/rng.h"
#include "math/sampling.h"
#include "math/sh_fit.h"

namespace glint {

namespace {

// Ray origins start this many standard deviations (the largest axis) before the mean: the
// generalised Gaussian's response is negligible there for every kernel power we use.
constexpr float kStartSigmas = 3.0f;
// Viewpoints are jittered within this fraction of the camera's distance, so that the few
// cameras that see a Gaussian still spread its samples over nearby directions.
constexpr double kViewpointJitter = 0.05;
// Rays whose blend covers less than this (1 - T_f) are too transparent to normalise by it.
constexpr float kMinCoverage = 1e-3f;

// The directions Gaussian i is sampled in, viewer towards the Gaussian.
std::vector<Vec3f> sampleDirections(const Vec3f& mean, uint64_t gaussian, const ShBakeSettings& s,
                                    const std::vector<Mat4>& worldToCamera) {
  std::vector<int> seenBy;
  for (size_t c = 0; c < s.cameras.size(); ++c) {
    Vec2d pixel;
    if (s.cameras[c].project(worldToCamera[c], Vec3d(mean), &pixel)) seenBy.push_back(int(c));
  }
  // The random streams of this Gaussian: viewpoint jitter, and sphere samples (their last
  // keys only tell the two apart).
  Rng rng = Rng::forKeys({s.seed, gaussian, 1});
  const uint64_t sphereStream = hashKeys({s.seed, gaussian, 2});
  const size_t count = size_t(s.directions);
  std::vector<Vec3f> directions(count);
  for (size_t k = 0; k < count; ++k) {
    if (seenBy.empty()) {
      // Stratified over the sphere (a (0,2)-net of sample indices).
      directions[k] = sampleUniformSphere(stratifiedSample2(sphereStream, uint32_t(k)));
      continue;
    }
    // The cameras that see the Gaussian in equal shares (every one when there are fewer
    // than the samples, evenly spaced ones otherwise), each from a jittered viewpoint.
    const Camera& camera = s.cameras[size_t(seenBy[k * seenBy.size() / count])];
    const Vec3d eye = camera.position();
    const double distance = length(Vec3d(mean) - eye);
    const Vec3f jitter = sampleUniformSphere(rng.uniform2()) * std::cbrt(rng.uniform());
    const Vec3d viewpoint = eye + Vec3d(jitter) * (kViewpointJitter * distance);
    directions[k] = Vec3f(normalize(Vec3d(mean) - viewpoint));
  }
  return directions;
}

// Gaussian i's blending weight T_i alpha_i on a traced ray (0 when not hit).
float blendingWeight(const HitList& hits, uint32_t i) {
  float T = 1.0f, w = 0.0f;
  for (const HitRecord& hit : hits.hits) {
    if (hit.id == i) w += T * hit.alpha;
    T *= 1.0f - hit.alpha;
  }
  return w;
}

}  // namespace

SplatColour bakeReflections(const GaussianScene& scene, const GaussianTracer& tracer, const ShBakeSettings& s) {
  GLINT_CHECK(s.degree >= 0 && s.degree <= kMaxShDegree && s.directions > 0, "bakeReflections: bad settings");
  const size_t n = scene.size();
  SplatColour colour;
  colour.shDegree = s.degree;
  colour.base.resize(n);
  colour.sh.assign(n * colour.restCount(), Rgb(0.0f));
  std::vector<Mat4> worldToCamera;
  for (const Camera& camera : s.cameras) worldToCamera.push_back(camera.cameraToWorld.inverse());

  ProgressBar progress("bake reflections", int64_t(n), "Gaussians");
  // The rays through a few hundred Gaussians at a time go through the renderer's wavefront
  // (so a GPU tracer receives them whole), with their first segment's hits recorded (a
  // Gaussian's blending weight on each): a bounded batch, since every recorded ray keeps its
  // hit list. The same SH, bit for bit, as tracing each Gaussian's paths one by one; on 2 CPU
  // threads 4-7% slower than that (12.1-12.5 s against 11.5-12.0 s on a 49k-Gaussian run,
  // 25 MB more; 1024 Gaussians a batch was no faster and took 120 MB more).
  constexpr size_t kBatchGaussians = 256;
  PathBatch batch;
  batch.setFirstSegmentHitsOnly(true);
  std::vector<TraceRay> rays;
  std::vector<PathKey> keys;
  std::vector<PathResult> results;
  std::vector<std::vector<Vec3f>> directions(kBatchGaussians);
  std::vector<size_t> begins(kBatchGaussians + 1);
  for (size_t first = 0; first < n; first += kBatchGaussians) {
    const size_t count = std::min(kBatchGaussians, n - first);
    parallelFor(int64_t(count), 1, [&](int64_t k) {
      directions[size_t(k)] = sampleDirections(scene.position[first + size_t(k)], first + size_t(k), s, worldToCamera);
    });
    rays.clear(), keys.clear();
    for (size_t k = 0; k < count; ++k) {
      const size_t i = first + k;
      const Vec3f sigma = scene.scale(i);
      const float start = kStartSigmas * std::max({sigma.x, sigma.y, sigma.z}) + 1e-4f;
      begins[k] = rays.size();
      for (size_t d = 0; d < directions[k].size(); ++d) {
        rays.push_back(TraceRay{scene.position[i] - directions[k][d] * start, directions[k][d]});
        keys.push_back(PathKey{i, d, 0});
      }
    }
    begins[count] = rays.size();
    results.resize(rays.size());
    batch.trace(tracer, rays, keys, s.seed, s.path, results, /*record=*/true);
    parallelFor(int64_t(count), 1, [&](int64_t kk) {
      const size_t k = size_t(kk), i = first + k;
      ShFit fit(s.degree);
      for (size_t j = begins[k]; j < begins[k + 1]; ++j) {
        const PathResult& path = results[j];
        const float coverage = 1.0f - path.first.transmittance;
        const float w = blendingWeight(batch.path(j)[0].hits, uint32_t(i));
        if (coverage < kMinCoverage || !(w > 0)) continue;
        const Rgb display = tonemapFilmic((path.first.diffuse + path.specular) * s.exposure) / coverage;
        fit.add(Vec3d(rays[j].direction), Vec3d(display), double(w));
      }
      thread_local std::vector<Vec3d> rest;  // per thread, not per Gaussian
      rest.resize(colour.restCount());
      Vec3d constant;
      if (!fit.solve(s.ridge, &constant, rest.data())) {
        colour.base[i] = tonemapFilmic(scene.diffuse[i] * s.exposure);  // never seen: no data to fit
        return;
      }
      colour.base[i] = Rgb(constant);
      for (size_t r = 0; r < rest.size(); ++r) colour.sh[i * colour.restCount() + r] = Rgb(rest[r]);
    });
    progress.advance(int64_t(count));
  }
  progress.finish();
  return colour;
}

}  // namespace glint
