// Seeds of far-field Gaussians along unexplained mirror reflections of the training views.
#include "train/reflection_seeds.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "bsdf/fresnel.h"
#include "io/tonemap.h"
#include "math/rng.h"
#include "train/training_views.h"

namespace glint {

namespace {

// Candidates drawn per seed asked for: most land in space some camera sees and are carved.
constexpr int kCandidatesPerSeed = 8;
// Pixels tried per candidate wanted before giving up (views with few mirror pixels).
constexpr int kPixelTriesPerCandidate = 16;

float luminance(const Rgb& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

struct Candidate {
  TraceRay ray;
  Rgb radiance;  // what the pixel's specular buffer says the reflected ray sees
};

}  // namespace

GaussianScene reflectionSeeds(const FarFieldSettings& s, const TrainingViews& views, const GaussianTracer& tracer,
                              const TraceSettings& trace, float backfaceSkip, float sceneRadius, uint64_t seed) {
  const SupervisedBuffers& has = views.supervised();
  if (s.reflectionSeeds <= 0 || views.viewCount() == 0 || !has.depth || !has.normal || !has.roughness ||
      !has.specular || has.finalColour)
    return {};
  Rng rng = Rng::forKeys({seed, 0x7265666c73656564ull});  // "reflseed"

  // 1. Near-mirror training pixels and the rays their mirrors reflect.
  const size_t wanted = size_t(s.reflectionSeeds) * kCandidatesPerSeed;
  std::vector<Candidate> candidates;
  candidates.reserve(wanted);
  for (size_t tries = 0; tries < wanted * kPixelTriesPerCandidate && candidates.size() < wanted; ++tries) {
    const size_t view = std::min(size_t(rng.uniform() * float(views.viewCount())), views.viewCount() - 1);
    const size_t pixel = std::min(size_t(rng.uniform() * float(views.pixelCount(view))), views.pixelCount(view) - 1);
    if (!views.surfaceAt(view, pixel)) continue;
    const PixelTarget t = views.target(view, pixel);
    if (!(t.roughness < s.reflectionSeedRoughness)) continue;
    const TraceRay eye = views.pixelRay(view, pixel);
    const Vec3f n = normalize(t.normal);
    const float cosTheta = -dot(eye.direction, n);
    if (!(cosTheta > 0.05f)) continue;  // back-facing or grazing: no reliable reflection
    const Rgb F = F_Schlick(t.hasF0 ? t.f0 : Rgb(0.04f), cosTheta);
    Candidate c;
    c.ray.origin = eye.origin + eye.direction * t.depth;
    c.ray.direction = normalize(reflect(-eye.direction, n));
    c.ray.tMin = 1e-3f * sceneRadius;
    c.ray.backfaceSkip = backfaceSkip;
    c.radiance = {std::min(t.specular.x / std::max(F.x, 0.02f), kMaxUntonemapped),
                  std::min(t.specular.y / std::max(F.y, 0.02f), kMaxUntonemapped),
                  std::min(t.specular.z / std::max(F.z, 0.02f), kMaxUntonemapped)};
    candidates.push_back(c);
  }

  // 2. What the scene shows along each reflected ray.
  std::vector<TraceRay> rays(candidates.size());
  for (size_t i = 0; i < candidates.size(); ++i) rays[i] = candidates[i].ray;
  std::vector<RayResult> results(rays.size());
  tracer.traceBatch(rays, results, {}, RayCoherence::Scattered);

  // 3. One point on the free segment of each reflection the scene does not explain.
  std::vector<Vec3f> points;
  std::vector<Rgb> radiance;
  const float tNear = 0.02f * sceneRadius, tFar = 3.0f * sceneRadius;
  for (size_t i = 0; i < candidates.size(); ++i) {
    const RayResult& r = results[i];
    const float opacity = 1.0f - r.transmittance;
    const float expected = luminance(candidates[i].radiance);
    const bool explained = opacity >= 0.5f && std::abs(luminance(r.diffuse) - expected) <= 0.2f * expected + 0.02f;
    if (explained) continue;
    const float tEnd = opacity >= 0.5f ? std::min(r.depth / opacity, tFar) : tFar;
    if (!(tEnd > tNear)) continue;
    const float t = tNear + rng.uniform() * (tEnd - tNear);
    points.push_back(candidates[i].ray.origin + candidates[i].ray.direction * t);
    radiance.push_back(candidates[i].radiance);
  }

  // 4. Only unobserved space keeps its seeds; then at most s.reflectionSeeds of them,
  //    sized by the spacing of those that stay.
  GaussianScene kept = farFieldAtPoints(points, s, sceneRadius);
  kept.diffuse = radiance;
  carveObservedFreeSpace(&kept, views, trace);
  std::vector<size_t> order(kept.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  for (size_t i = order.size(); i > 1; --i)  // Fisher-Yates, on the run's stream
    std::swap(order[i - 1], order[std::min(size_t(rng.uniform() * float(i)), i - 1)]);
  order.resize(std::min(order.size(), size_t(s.reflectionSeeds)));
  std::sort(order.begin(), order.end());
  std::vector<Vec3f> finalPoints;
  std::vector<Rgb> finalRadiance;
  for (size_t i : order) {
    finalPoints.push_back(kept.position[i]);
    finalRadiance.push_back(kept.diffuse[i]);
  }
  GaussianScene seeds = farFieldAtPoints(finalPoints, s, sceneRadius);
  seeds.diffuse = finalRadiance;
  carveObservedFreeSpace(&seeds, views, trace);  // removes none now; shrinks sizes to stay behind surfaces
  return seeds;
}

}  // namespace glint
