// The irradiance ratios of differential relighting: cone sampling of the changed regions for
// the change, cosine sampling for the irradiance before.
#include "render/differential_relight.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>

#include "core/cluster.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "math/frame.h"
#include "math/owen_sobol.h"
#include "math/rng.h"
#include "math/sampling.h"
#include "render/light_regions.h"
#include "render/relight_batch.h"
#include "render/relight_cones.h"
#include "scene/gaussian_cell_grid.h"

namespace glint {

ChangedRegion changedRegionOf(const GaussianScene& scene, std::span<const uint32_t> indices) {
  if (indices.empty()) return {};
  Vec3d sum(0.0);
  for (uint32_t i : indices) sum += Vec3d(scene.position[i]);
  Vec3f centre(sum * (1.0 / double(indices.size())));
  float radius = 0;
  for (uint32_t i : indices) {
    Vec3f s = scene.scale(i);
    radius = std::max(radius, length(scene.position[i] - centre) + 3.0f * std::max({s.x, s.y, s.z}));
  }
  return {centre, radius};
}

Vec3f cosineDirection(const Framef& frame, uint64_t stream, int k) {
  return normalize(frame.toWorld(sampleCosineHemisphere(stratifiedSample2(stream, uint32_t(k)))));
}

Rgb incomingRadiance(const GaussianTracer& tracer, const Vec3f& p, const Vec3f& n, const Vec3f& w,
                     const PathSettings& path, const RadianceKeys& keys, uint64_t* segments) {
  const TraceRay ray = radianceRay(p, n, w, path);
  const PathResult light = tracePath(tracer, ray, path, keys.seed, keys.receiver, keys.sequence, keys.sample);
  *segments += uint64_t(light.segments);
  return light.first.diffuse + light.specular;
}

void addCosineRadiance(const GaussianTracer& tracer, const Vec3f& p, const Vec3f& n, const PathSettings& path,
                       uint64_t stream, RadianceKeys keys, int begin, int end, Rgb* sum, uint64_t* segments) {
  const Framef frame = Framef::fromNormal(n);
  for (int k = begin; k < end; ++k) {
    keys.sample = uint32_t(k);
    *sum += incomingRadiance(tracer, p, n, cosineDirection(frame, stream, k), path, keys, segments);
  }
}

namespace {

// Each receiver's unit normal (zero for receivers out of reach, which never use it).
std::vector<Vec3f> unitNormals(const GaussianScene& scene, std::span<const uint32_t> receivers,
                               std::span<const uint32_t> reached) {
  std::vector<Vec3f> normals(receivers.size(), Vec3f(0.0f));
  for (uint32_t i : reached) normals[i] = normalize(scene.normal[receivers[i]]);
  return normals;
}

// The receivers (indices into `receivers`) of a cover of those within reach: every one of
// them has a chosen receiver within `spacing` that faces the same way (normals within
// `cosine`). Greedy in an order hashed from the seed, so the cover is spread evenly and does
// not depend on the receivers' order or the thread count.
std::vector<uint32_t> coverOf(const GaussianScene& scene, std::span<const uint32_t> receivers,
                              const std::vector<uint32_t>& order, const std::vector<uint32_t>& receiverOf,
                              const std::vector<Vec3f>& normals, float spacing, float cosine) {
  CellGrid grid(scene, {}, spacing);  // the chosen receivers
  std::vector<uint32_t> chosen;
  for (uint32_t i : order) {
    bool covered = false;
    grid.near(scene.position[receivers[i]], spacing,
              [&](uint32_t g) { covered = covered || dot(normals[receiverOf[g]], normals[i]) >= cosine; });
    if (covered) continue;
    grid.add(receivers[i]);
    chosen.push_back(i);
  }
  return chosen;
}

// The receivers to trace under RelightSettings::tracedBudget: a cover of the receivers within
// reach with the smallest spacing (to 2%) that keeps it within the budget, and that spacing;
// every receiver within reach and spacing 0 when they fit the budget.
std::vector<uint32_t> tracedReceivers(const GaussianScene& scene, std::span<const uint32_t> receivers,
                                      std::vector<uint32_t> reached, const std::vector<Vec3f>& normals,
                                      const RelightSettings& settings, float* spacing) {
  *spacing = 0;
  if (settings.tracedBudget == 0 || reached.size() <= settings.tracedBudget) return reached;
  std::vector<uint64_t> rank(receivers.size());
  for (uint32_t i : reached) rank[i] = hashKeys({settings.seed, receivers[i], 2});
  std::sort(reached.begin(), reached.end(), [&](uint32_t a, uint32_t b) { return rank[a] < rank[b]; });
  std::vector<uint32_t> receiverOf(scene.size(), UINT32_MAX);
  for (uint32_t i : reached) receiverOf[receivers[i]] = i;
  Vec3f lo(INFINITY), hi(-INFINITY);
  for (uint32_t i : reached) lo = min(lo, scene.position[receivers[i]]), hi = max(hi, scene.position[receivers[i]]);
  // Bisection in log space: one cell spans the whole reach at `high`, the budget is exceeded
  // at `low` (a cover at spacing 0 holds every receiver).
  float low = 0, high = std::max(length(hi - lo), 1e-6f);
  std::vector<uint32_t> best = coverOf(scene, receivers, reached, receiverOf, normals, high, settings.filterCosine);
  for (int step = 0; step < 40 && (low == 0 || high > 1.02f * low); ++step) {
    const float middle = low == 0 ? 0.25f * high : std::sqrt(low * high);
    std::vector<uint32_t> cover = coverOf(scene, receivers, reached, receiverOf, normals, middle, settings.filterCosine);
    if (cover.size() <= settings.tracedBudget) {
      high = middle;
      best = std::move(cover);
    } else {
      low = middle;
    }
  }
  *spacing = high;
  std::sort(best.begin(), best.end());
  return best;
}

// The filter of RelightSettings::filterRadius over the receivers within reach: each takes the
// weighted mean of the ratios of the traced receivers near it that face the same way, within
// filterRadius of its largest standard deviations or `spacing`, whichever is wider, weighted
// by distance and by their trained luminance (RelightSettings::filterRadius). Without
// a budget every receiver within reach is traced and spacing is 0.
std::vector<Rgb> filteredRatios(const GaussianScene& scene, std::span<const uint32_t> receivers,
                                std::span<const uint32_t> reached, std::span<const uint32_t> traced,
                                const std::vector<Vec3f>& normals, const std::vector<Rgb>& ratios,
                                const RelightSettings& settings, float spacing) {
  std::vector<float> radii;  // per reached receiver
  float largest = 0;
  for (uint32_t i : reached) {
    const Vec3f s = scene.scale(receivers[i]);
    radii.push_back(std::max(settings.filterRadius * std::max({s.x, s.y, s.z}), spacing));
    largest = std::max(largest, radii.back());
  }
  if (reached.empty() || !(largest > 0)) return ratios;
  // Cells as wide as the largest radius any receiver asks for, over the traced receivers.
  std::vector<uint32_t> sceneIndices;
  std::vector<uint32_t> receiverOf(scene.size(), UINT32_MAX);
  for (uint32_t r : traced) sceneIndices.push_back(receivers[r]), receiverOf[receivers[r]] = r;
  const CellGrid grid(scene, sceneIndices, largest);
  std::vector<Rgb> filtered = ratios;
  parallelFor(int64_t(reached.size()), 64, [&](int64_t k) {
    const uint32_t r = reached[size_t(k)];
    const uint32_t g = receivers[r];
    const float radius = radii[size_t(k)];
    const float sigma2 = 0.25f * radius * radius;  // the weight falls to e^-2 at the radius
    const Vec3f n = normals[r];
    Rgb sum(0.0f);
    float weights = 0;
    grid.near(scene.position[g], radius, [&](uint32_t j) {
      if (dot(normals[receiverOf[j]], n) < settings.filterCosine) return;
      const Vec3f d = scene.position[j] - scene.position[g];
      // Weighted by the trained colour too: a receiver in deep shadow divides by a small,
      // noisy E_before, and the sum of colours relit over the sum trained (a ratio of sums)
      // lets it count for as little as its light.
      const float w = std::exp(-0.5f * dot(d, d) / sigma2) * std::max(luminance(scene.diffuse[j]), 1e-4f);
      sum += ratios[receiverOf[j]] * w;
      weights += w;
    });
    // A division, not a product with 1 / weights: ratios that are all 1 stay exactly 1.
    if (weights > 0) filtered[r] = Rgb(sum.x / weights, sum.y / weights, sum.z / weights);
  });
  return filtered;
}

}  // namespace

namespace {

// The receivers (indices into `receivers`) that the edit can reach: a normal, and a changed
// region above their horizon under minSolidAngle or more.
std::vector<uint32_t> receiversInReach(const GaussianScene& scene, std::span<const uint32_t> receivers,
                                       std::span<const ChangedRegion> regions, const RelightSettings& settings) {
  std::vector<uint8_t> inReach(receivers.size(), 0);
  parallelFor(int64_t(receivers.size()), 256, [&](int64_t i) {
    Vec3f p, n;
    RelightCone cones[kMaxRegions];
    float solidAngle = 0;
    inReach[size_t(i)] = receiverCones(scene, receivers[size_t(i)], regions, settings, &p, &n, cones, &solidAngle) > 0;
  });
  std::vector<uint32_t> reached;
  for (size_t i = 0; i < receivers.size(); ++i)
    if (inReach[i]) reached.push_back(uint32_t(i));
  return reached;
}

// Under MPI each rank traces its share of `traced` and every rank receives every ratio, so
// that all of them relight the same scene; the counts are summed.
RatioCounts shareRatios(std::span<const uint32_t> traced, cluster::Share share, RatioCounts mine,
                        std::vector<Rgb>* ratios) {
  if (!cluster::distributed()) return mine;
  std::vector<Rgb> slice(size_t(share.end - share.begin));
  for (size_t k = 0; k < slice.size(); ++k) slice[k] = (*ratios)[traced[size_t(share.begin) + k]];
  std::vector<std::vector<std::byte>> all = cluster::allGather(std::as_bytes(std::span<const Rgb>(slice)));
  for (int r = 0; r < cluster::size(); ++r) {
    const cluster::Share theirs = cluster::shareOf(int64_t(traced.size()), r, cluster::size());
    const size_t count = size_t(theirs.end - theirs.begin);
    GLINT_CHECK(all[size_t(r)].size() == count * sizeof(Rgb), "relightRatios: a rank's share");
    std::vector<Rgb> values(count);
    if (count > 0) std::memcpy(values.data(), all[size_t(r)].data(), count * sizeof(Rgb));
    for (size_t k = 0; k < count; ++k) (*ratios)[traced[size_t(theirs.begin) + k]] = values[k];
  }
  int64_t counts[3] = {int64_t(mine.changed), int64_t(mine.clamped), int64_t(mine.rays)};
  cluster::sumInRankOrder(std::span<int64_t>(counts));
  return {size_t(counts[0]), size_t(counts[1]), uint64_t(counts[2])};
}

}  // namespace

std::vector<Rgb> relightRatios(const GaussianTracer& before, const GaussianTracer& after,
                               const GaussianScene& afterScene, std::span<const uint32_t> receivers,
                               std::span<const ChangedRegion> regions, const RelightSettings& settings,
                               RelightReport* report) {
  GLINT_CHECK(regions.size() <= size_t(kMaxRegions), "relightRatios: too many changed regions");
  GLINT_CHECK(settings.rays >= 1 && settings.minRays >= 1 && settings.hemisphereRays >= 1 && settings.quickRays >= 1 &&
                  settings.maxRatio >= 1 && settings.minRelativeChange >= 0,
              "relightRatios: bad settings");
  std::vector<Rgb> ratios(receivers.size(), Rgb(1.0f));
  const std::vector<uint32_t> reached = receiversInReach(afterScene, receivers, regions, settings);
  const std::vector<Vec3f> normals = unitNormals(afterScene, receivers, reached);
  float spacing = 0;
  const std::vector<uint32_t> traced = tracedReceivers(afterScene, receivers, reached, normals, settings, &spacing);
  const std::vector<LightRegion> lights = lightRegionsOf(afterScene, settings.lights);

  const cluster::Share share = cluster::myShare(int64_t(traced.size()));
  const std::span<const uint32_t> mine =
      std::span<const uint32_t>(traced).subspan(size_t(share.begin), size_t(share.end - share.begin));
  ProgressBar progress("relight", int64_t(mine.size()), "Gaussians");
  RatioCounts counts =
      traceIrradianceRatios(before, after, afterScene, receivers, mine, regions, lights, settings, &ratios, &progress);
  if (settings.cancel && settings.cancel->load(std::memory_order_relaxed)) {
    progress.setStatus("cancelled");  // the bar ends short of 100%: say why
    throw RelightCancelled();
  }
  progress.finish();
  counts = shareRatios(traced, share, counts, &ratios);
  if (settings.filterRadius > 0 || spacing > 0) {
    ratios = filteredRatios(afterScene, receivers, reached, traced, normals, ratios, settings, spacing);
    counts.changed = size_t(std::count_if(ratios.begin(), ratios.end(), [](const Rgb& r) { return r != Rgb(1.0f); }));
  }
  if (report) {
    report->receivers = receivers.size();
    report->reached = reached.size();
    report->traced = traced.size();
    report->changed = counts.changed;
    report->clamped = counts.clamped;
    report->rays = counts.rays;
    report->lights = lights.size();
  }
  return ratios;
}

RelightReport relightDiffuse(const GaussianTracer& before, const GaussianTracer& after, GaussianScene& afterScene,
                             std::span<const uint32_t> receivers, std::span<const ChangedRegion> regions,
                             const RelightSettings& settings) {
  RelightReport report;
  std::vector<Rgb> ratios = relightRatios(before, after, afterScene, receivers, regions, settings, &report);
  for (size_t i = 0; i < receivers.size(); ++i) afterScene.diffuse[receivers[i]] *= ratios[i];
  return report;
}

}  // namespace glint
