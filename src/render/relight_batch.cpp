// Differential relighting's ratios traced receiver batch by receiver batch: the change rays
// in both scenes, a first look at E_before, the rest of it, and the refinement, each a
// wavefront over every receiver still in play.
#include "render/relight_batch.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "math/owen_sobol.h"
#include "math/rng.h"
#include "render/gaussian_path.h"
#include "render/radiance_batch.h"
#include "render/relight_cones.h"

namespace glint {

namespace {

// Receivers traced together. Their change rays (up to refineFactor x rays each, in both
// scenes) bound the batch's memory, and a step's rays (about 65k at 512 receivers of 64 rays,
// some 0.05 s on 2 threads) how long a cancelled relighting (RelightSettings::cancel) runs
// on: the viewer's edit that cancels it waits for that. At 2048 an undo sent during the
// full relighting of relight_bench at 100k Gaussians was shown after 0.14-0.16 s, against
// 0.06 s when each receiver checked the flag.
constexpr size_t kBatchReceivers = 512;

// One receiver through the steps.
struct Receiver {
  uint32_t slot = 0;  // index into `receivers` and the ratios
  uint32_t g = 0;     // index into the edited scene
  Vec3f p, n;
  RelightCone cones[kMaxRegions];
  int coneCount = 0;
  RelightCone lightCones[kMaxLights];
  int lightCount = 0;
  float solidAngle = 0;
  int count = 0;          // change rays before any refinement
  uint64_t changeStream = 0, hemisphereStream = 0;
  Rgb changeSum{0.0f};    // sum of (L_after - L_before) cos / pdf over the change rays
  Rgb sum{0.0f};          // sum of L_before over the cosine-distributed rays
  Rgb change{0.0f};
  Rgb ratio{1.0f};
  bool clamped = false;
  bool active = true;     // still in play
  uint64_t rays = 0;
};

// E_after / E_before per channel from E_before and the change, clamped.
Rgb irradianceRatio(const Rgb& before, const Rgb& change, float maxRatio, bool* clamped) {
  const float tiny = 1e-6f;
  float lumBefore = luminance(before);
  float lumRatio = lumBefore > tiny ? (lumBefore + luminance(change)) / lumBefore : 1.0f;
  Rgb ratio;
  for (int c = 0; c < 3; ++c) {
    // A channel that received almost no light follows the luminance rather than a ratio of
    // two noisy near-zero numbers.
    float r = before[c] > tiny ? (before[c] + change[c]) / before[c] : lumRatio;
    if (!std::isfinite(r)) r = 1.0f;
    float kept = std::clamp(r, 1.0f / maxRatio, maxRatio);
    *clamped = *clamped || kept != r;
    ratio[c] = kept;
  }
  return ratio;
}

// Change rays begin..end-1 of receiver r: by one-sample MIS over its cones (a changed
// region's cone picked uniformly, or, where a light region shares its directions, half of
// the rays aimed at the lights); directions below the horizon or outside every changed
// region (whose radiance the edit cannot change) are left out.
void makeChangeRays(const Receiver& r, int begin, int end, const PathSettings& path, std::vector<PendingRay>* out) {
  for (int k = begin; k < end; ++k) {
    Vec2f u = stratifiedSample2(r.changeStream, uint32_t(k));
    const bool towardLight = r.lightCount > 0 && u.x >= 0.5f;
    if (r.lightCount > 0) u.x = towardLight ? 2.0f * u.x - 1.0f : 2.0f * u.x;
    const Vec3f w = towardLight ? sampleConeMixture(r.lightCones, r.lightCount, u)
                                : sampleConeMixture(r.cones, r.coneCount, u);
    float cosine = dot(r.n, w);
    if (cosine <= 0) continue;
    const float regionPdf = coneMixturePdf(r.cones, r.coneCount, w);
    if (!(regionPdf > 0)) continue;
    const float pdf =
        r.lightCount > 0 ? 0.5f * (regionPdf + coneMixturePdf(r.lightCones, r.lightCount, w)) : regionPdf;
    out->push_back({radianceRay(r.p, r.n, w, path), PathKey{r.g, 0, uint64_t(k)}, cosine / pdf});
  }
}

// Cosine-distributed rays begin..end-1 of receiver r's hemisphere stream (E_before's).
void makeHemisphereRays(const Receiver& r, int begin, int end, const PathSettings& path,
                        std::vector<PendingRay>* out) {
  const Framef frame = Framef::fromNormal(r.n);
  for (int k = begin; k < end; ++k)
    out->push_back({radianceRay(r.p, r.n, cosineDirection(frame, r.hemisphereStream, k), path),
                    PathKey{r.g, 1, uint64_t(k)}, 1.0f});
}

// The steps of one batch of receivers, in the order tracing one receiver at a time takes
// them, each over every receiver still in play.
class RatioSteps {
 public:
  RatioSteps(const GaussianTracer& before, const GaussianTracer& after, const RelightSettings& settings)
      : before_(before), after_(after), settings_(settings) {
    path_ = settings.path;
    path_.minReflectance = settings.minReflectance;
    path_.primaryCoherence = RayCoherence::Scattered;  // rays from surfaces, not bundles of pixels
  }

  // dE over change rays begin..end-1 (or up to each receiver's count x factor).
  void addChange(std::vector<Receiver>& receivers, int factorBegin, int factorEnd) {
    batch_.gather(receivers.size(), [&](size_t k, std::vector<PendingRay>* out) {
      const Receiver& r = receivers[k];
      if (r.active) makeChangeRays(r, r.count * factorBegin, r.count * factorEnd, path_, out);
    });
    batch_.trace(after_, settings_.seed, path_, 0);
    batch_.trace(before_, settings_.seed, path_, 1);
    parallelFor(int64_t(receivers.size()), 64, [&](int64_t i) {
      Receiver& r = receivers[size_t(i)];
      for (size_t j = batch_.begin(size_t(i)); j < batch_.end(size_t(i)); ++j) {
        Rgb difference = batch_.radiance(j, 0) - batch_.radiance(j, 1);
        r.changeSum += difference * batch_.weight(j);
        r.rays += uint64_t(batch_.segments(j, 0) + batch_.segments(j, 1));
      }
    });
  }

  // E_before's cosine-weighted sum over hemisphere rays begin..end-1.
  void addHemisphere(std::vector<Receiver>& receivers, int begin, int end) {
    batch_.gather(receivers.size(), [&](size_t k, std::vector<PendingRay>* out) {
      if (receivers[k].active) makeHemisphereRays(receivers[k], begin, end, path_, out);
    });
    batch_.trace(before_, settings_.seed, path_, 1);
    parallelFor(int64_t(receivers.size()), 64, [&](int64_t i) {
      Receiver& r = receivers[size_t(i)];
      for (size_t j = batch_.begin(size_t(i)); j < batch_.end(size_t(i)); ++j) {
        r.sum += batch_.radiance(j, 1);
        r.rays += uint64_t(batch_.segments(j, 1));
      }
    });
  }

  const RelightSettings& settings() const { return settings_; }

 private:
  const GaussianTracer& before_;
  const GaussianTracer& after_;
  const RelightSettings& settings_;
  PathSettings path_;
  RadianceBatch batch_;
};

// Each receiver's place, cones, light cones, ray count and random streams.
std::vector<Receiver> setUpReceivers(const GaussianScene& scene, std::span<const uint32_t> receivers,
                                     std::span<const uint32_t> slots, std::span<const ChangedRegion> regions,
                                     std::span<const LightRegion> lights, const RelightSettings& settings) {
  std::vector<Receiver> batch(slots.size());
  parallelFor(int64_t(slots.size()), 64, [&](int64_t k) {
    Receiver& r = batch[size_t(k)];
    r.slot = slots[size_t(k)];
    r.g = receivers[r.slot];
    r.coneCount = receiverCones(scene, r.g, regions, settings, &r.p, &r.n, r.cones, &r.solidAngle);
    r.lightCount = lightConesToward(r.p, r.n, lights, std::span<const RelightCone>(r.cones, size_t(r.coneCount)),
                                    r.lightCones, kMaxLights);
    r.count = std::clamp(int(std::ceil(float(settings.rays) * r.solidAngle / kFullRaysSolidAngle)), settings.minRays,
                         settings.rays);
    r.changeStream = hashKeys({settings.seed, r.g, 0});
    r.hemisphereStream = hashKeys({settings.seed, r.g, 1});
  });
  return batch;
}

// The ratios of one batch of receivers, step by step as relightRatios describes: each
// receiver leaves play (keeping the ratio 1, or its ratio) where tracing it alone would stop.
template <typename Cancelled>
void estimateRatios(RatioSteps& steps, std::vector<Receiver>& batch, Cancelled&& cancelled) {
  const RelightSettings& s = steps.settings();
  steps.addChange(batch, 0, 1);
  for (Receiver& r : batch) {
    r.change = r.changeSum * (1.0f / float(r.count));
    r.active = r.change != Rgb(0.0f);  // else every ray met the same radiance in both scenes
  }
  if (cancelled()) return;
  // E_before: a first estimate, then the rest of the sequence where the change matters.
  const int quick = std::min(s.quickRays, s.hemisphereRays);
  steps.addHemisphere(batch, 0, quick);
  for (Receiver& r : batch) {
    if (!r.active) continue;
    const float quickLuminance = luminance(r.sum * (kPi / float(quick)));
    const float largestChange = std::max({std::abs(r.change.x), std::abs(r.change.y), std::abs(r.change.z)});
    r.active = !(largestChange < s.minRelativeChange * quickLuminance);
  }
  if (cancelled()) return;
  steps.addHemisphere(batch, quick, s.hemisphereRays);
  bool refining = false;
  for (Receiver& r : batch) {
    if (!r.active) continue;
    r.ratio = irradianceRatio(r.sum * (kPi / float(s.hemisphereRays)), r.change, s.maxRatio, &r.clamped);
    // A ratio far from 1 multiplies E_before's relative error (and divides dE's by a small
    // E_before): both estimates go on along their sequences.
    const float lumRatio = luminance(r.ratio);
    r.active = s.refineFactor > 1 && (lumRatio > s.refineBeyond || lumRatio * s.refineBeyond < 1);
    refining = refining || r.active;
  }
  if (!refining || cancelled()) return;
  steps.addChange(batch, 1, s.refineFactor);
  steps.addHemisphere(batch, s.hemisphereRays, s.hemisphereRays * s.refineFactor);
  for (Receiver& r : batch) {
    if (!r.active) continue;
    r.change = r.changeSum * (1.0f / float(r.count * s.refineFactor));
    r.clamped = false;
    r.ratio = irradianceRatio(r.sum * (kPi / float(s.hemisphereRays * s.refineFactor)), r.change, s.maxRatio,
                              &r.clamped);
  }
}

}  // namespace

RatioCounts traceIrradianceRatios(const GaussianTracer& before, const GaussianTracer& after,
                                  const GaussianScene& afterScene, std::span<const uint32_t> receivers,
                                  std::span<const uint32_t> traced, std::span<const ChangedRegion> regions,
                                  std::span<const LightRegion> lights, const RelightSettings& settings,
                                  std::vector<Rgb>* ratios, ProgressBar* progress) {
  auto cancelled = [&] { return settings.cancel && settings.cancel->load(std::memory_order_relaxed); };
  RatioSteps steps(before, after, settings);
  RatioCounts counts;
  for (size_t first = 0; first < traced.size() && !cancelled(); first += kBatchReceivers) {
    std::span<const uint32_t> slots = traced.subspan(first, std::min(kBatchReceivers, traced.size() - first));
    std::vector<Receiver> batch = setUpReceivers(afterScene, receivers, slots, regions, lights, settings);
    estimateRatios(steps, batch, cancelled);
    for (const Receiver& r : batch) {
      (*ratios)[r.slot] = r.ratio;
      counts.rays += r.rays;
      counts.changed += r.ratio != Rgb(1.0f);
      counts.clamped += r.clamped;
    }
    progress->advance(int64_t(slots.size()));
  }
  return counts;
}

}  // namespace glint
