// The healed Gaussians' light factors: shared cosine-distributed directions from each healed
// Gaussian and each of its ring neighbours, traced through the edited scene.
#include "edit_effects/healed_lighting.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <unordered_map>

#include "core/parallel.h"
#include "math/rng.h"
#include "math/sampling.h"
#include "render/radiance_batch.h"

namespace glint {

std::vector<float> healedLightFactors(const GaussianTracer& after, const GaussianScene& afterScene,
                                      const HealReport& report, const RelightSettings& settings, uint64_t* rays) {
  std::vector<float> factors(report.healed.size(), 1.0f);
  if (report.healed.empty()) return factors;

  // The points to trace from: every healed Gaussian and every ring neighbour, once each.
  std::vector<uint32_t> points;
  std::unordered_map<uint32_t, size_t> slot;
  auto add = [&](uint32_t g) {
    if (slot.emplace(g, points.size()).second) points.push_back(g);
  };
  for (const HealedGaussian& h : report.healed) {
    add(h.index);
    for (uint32_t n : h.neighbours) add(n);
  }

  PathSettings path = settings.path;
  path.minReflectance = settings.minReflectance;
  path.bounces = std::max(path.bounces, 1);
  const int count = settings.hemisphereRays * std::max(1, settings.refineFactor);
  const uint64_t stream = hashKeys({settings.seed, 2});  // one stream for every point: shared directions
  constexpr float kNoNormal = -1.0f;
  std::vector<float> irradiance(points.size(), kNoNormal);
  uint64_t traced = 0;
  auto cancelled = [&] { return settings.cancel && settings.cancel->load(std::memory_order_relaxed); };
  // The points' rays traced as batches (a few hundred points' rays at once bound the memory).
  constexpr size_t kBatchPoints = 256;
  RadianceBatch batch;
  for (size_t first = 0; first < points.size() && !cancelled(); first += kBatchPoints) {
    const size_t pointCount = std::min(kBatchPoints, points.size() - first);
    batch.gather(pointCount, [&](size_t k, std::vector<PendingRay>* out) {
      const uint32_t g = points[first + k];
      const float normalLength = length(afterScene.normal[g]);
      if (!(normalLength >= settings.minNormalLength)) return;
      const Vec3f n = afterScene.normal[g] / normalLength, p = afterScene.position[g];
      const Framef frame = Framef::fromNormal(n);
      for (int j = 0; j < count; ++j)
        out->push_back({radianceRay(p, n, cosineDirection(frame, stream, j), path), PathKey{0, 2, uint64_t(j)}, 1.0f});
    });
    batch.trace(after, settings.seed, path, 0);
    for (size_t k = 0; k < pointCount; ++k) {
      if (batch.begin(k) == batch.end(k)) continue;  // no normal
      Rgb sum(0.0f);
      for (size_t j = batch.begin(k); j < batch.end(k); ++j) sum += batch.radiance(j, 0), traced += uint64_t(batch.segments(j, 0));
      irradiance[first + k] = luminance(sum) * (kPi / float(count));
    }
  }
  if (cancelled()) throw RelightCancelled();
  if (rays) *rays += traced;

  for (size_t k = 0; k < report.healed.size(); ++k) {
    const HealedGaussian& h = report.healed[k];
    const float own = irradiance[slot[h.index]];
    double ring = 0, weights = 0;
    for (size_t m = 0; m < h.neighbours.size(); ++m) {
      const float e = irradiance[slot[h.neighbours[m]]];
      if (e == kNoNormal) continue;
      ring += double(h.weights[m]) * e;
      weights += h.weights[m];
    }
    if (own == kNoNormal || !(weights > 0) || !(ring > 1e-6 * weights)) continue;
    const float factor = float(double(own) * weights / ring);
    if (std::isfinite(factor)) factors[k] = std::clamp(factor, 1.0f / settings.maxRatio, settings.maxRatio);
  }
  return factors;
}

}  // namespace glint
