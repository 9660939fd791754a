// The irradiance ratios of differential relighting: cone sampling of the changed regions for
// the change, cosine sampling for the irradiance before.
#include "render/differential_relight.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "math/frame.h"
#include "math/owen_sobol.h"
#include "math/rng.h"
#include "math/sampling.h"
#include "render/light_regions.h"
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

Rgb incomingRadiance(const GaussianTracer& tracer, const Vec3f& p, const Vec3f& n, const Vec3f& w,
                     const PathSettings& path, const RadianceKeys& keys, uint64_t* segments) {
  const TraceRay ray{p + n * path.normalOffset, w, 0.0f, path.backfaceSkip};
  const PathResult light = tracePath(tracer, ray, path, keys.seed, keys.receiver, keys.sequence, keys.sample);
  *segments += uint64_t(light.segments);
  return light.first.diffuse + light.specular;
}

void addCosineRadiance(const GaussianTracer& tracer, const Vec3f& p, const Vec3f& n, const PathSettings& path,
                       uint64_t stream, RadianceKeys keys, int begin, int end, Rgb* sum, uint64_t* segments) {
  const Framef frame = Framef::fromNormal(n);
  for (int k = begin; k < end; ++k) {
    keys.sample = uint32_t(k);
    const Vec3f w = normalize(frame.toWorld(sampleCosineHemisphere(stratifiedSample2(stream, uint32_t(k)))));
    *sum += incomingRadiance(tracer, p, n, w, path, keys, segments);
  }
}

namespace {

// The cone of directions from a receiver toward one changed region or light region.
struct Cone {
  Framef frame;          // around the direction to the region's centre
  float cosThetaMax = 1;  // -1: the receiver is inside the region (every direction)
  float solidAngle = 0;
  float weight = 1;       // the probability a mixture of cones picks this one

  bool contains(const Vec3f& w) const { return dot(w, frame.n) >= cosThetaMax; }
  float pdf() const { return uniformConePdf(cosThetaMax); }
};

// The cone from p toward a sphere, if it rises above the horizon of normal n; a receiver
// inside the sphere gets every direction (cosThetaMax -1, framed on n).
bool coneToward(const Vec3f& p, const Vec3f& n, const Vec3f& centre, float radius, Cone* cone) {
  if (!(radius > 0)) return false;
  Vec3f toCentre = centre - p;
  float d = length(toCentre);
  if (d <= radius) {
    cone->frame = Framef::fromNormal(n);
    cone->cosThetaMax = -1.0f;
  } else {
    Vec3f axis = toCentre / d;
    float sinThetaMax = radius / d;
    // The whole cone lies below the horizon when its axis is more than 90 degrees plus its
    // half-angle away from the normal.
    if (dot(axis, n) < -sinThetaMax) return false;
    cone->frame = Framef::fromNormal(axis);
    cone->cosThetaMax = std::sqrt(std::max(0.0f, 1.0f - sinThetaMax * sinThetaMax));
  }
  cone->solidAngle = 2.0f * kPi * (1.0f - cone->cosThetaMax);
  return true;
}

// Cones toward the regions that rise above the receiver's horizon, picked uniformly.
int conesToward(const Vec3f& p, const Vec3f& n, std::span<const ChangedRegion> regions, Cone* cones) {
  int count = 0;
  for (const ChangedRegion& region : regions)
    if (coneToward(p, n, region.centre, region.radius, &cones[count])) ++count;
  for (int c = 0; c < count; ++c) cones[c].weight = 1.0f / float(count);
  return count;
}

// Whether two cones share a direction: their axes are closer than the sum of half-angles.
bool conesOverlap(const Cone& a, const Cone& b) {
  if (a.cosThetaMax <= -1.0f || b.cosThetaMax <= -1.0f) return true;
  const float between = std::acos(std::clamp(dot(a.frame.n, b.frame.n), -1.0f, 1.0f));
  return between <= std::acos(a.cosThetaMax) + std::acos(b.cosThetaMax);
}

// Cones toward the light regions above the receiver's horizon, outside them (a receiver
// inside a light's sphere gains nothing from aiming at it) and sharing directions with one
// of the `within` cones (a light behind or beside a changed region). Each is picked in proportion to the
// irradiance its light could bring, power x cosine / distance^2, and only the maxCones
// likeliest are kept.
int lightConesToward(const Vec3f& p, const Vec3f& n, std::span<const LightRegion> lights, std::span<const Cone> within,
                     Cone* cones, int maxCones) {
  int count = 0;
  for (const LightRegion& light : lights) {
    Cone cone;
    if (!coneToward(p, n, light.centre, light.radius, &cone) || cone.cosThetaMax <= -1.0f) continue;
    if (std::none_of(within.begin(), within.end(), [&](const Cone& c) { return conesOverlap(cone, c); })) continue;
    const Vec3f toLight = light.centre - p;
    // A light whose centre sits below the horizon can still rise above it: a floor of 5%.
    cone.weight = light.power * std::max(dot(cone.frame.n, n), 0.05f) /
                  std::max(dot(toLight, toLight), light.radius * light.radius);
    if (!(cone.weight > 0)) continue;
    if (count < maxCones) {
      cones[count++] = cone;
    } else {  // replace the unlikeliest kept
      Cone* weakest = std::min_element(cones, cones + count, [](const Cone& a, const Cone& b) { return a.weight < b.weight; });
      if (weakest->weight < cone.weight) *weakest = cone;
    }
  }
  float total = 0;
  for (int c = 0; c < count; ++c) total += cones[c].weight;
  for (int c = 0; c < count; ++c) cones[c].weight /= total;
  return count;
}

// The density, at w, of the mixture that picks cone c with probability cones[c].weight and
// then a direction uniformly within it.
float coneMixturePdf(const Cone* cones, int count, const Vec3f& w) {
  float pdf = 0;
  for (int c = 0; c < count; ++c)
    if (cones[c].contains(w)) pdf += cones[c].weight * cones[c].pdf();
  return pdf;
}

// A direction from that mixture; u.x picks the cone and is stretched back to [0, 1) for the
// direction.
Vec3f sampleConeMixture(const Cone* cones, int count, Vec2f u) {
  int pick = 0;
  float below = 0;  // the weights of the cones before `pick`
  while (pick < count - 1 && u.x >= below + cones[pick].weight) below += cones[pick++].weight;
  u.x = std::clamp((u.x - below) / cones[pick].weight, 0.0f, 0x1.fffffep-1f);
  return normalize(cones[pick].frame.toWorld(sampleUniformCone(u, cones[pick].cosThetaMax)));
}

constexpr int kMaxRegions = 8;
constexpr int kMaxLights = 8;  // light cones per receiver

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

std::vector<Rgb> relightRatios(const GaussianTracer& before, const GaussianTracer& after,
                               const GaussianScene& afterScene, std::span<const uint32_t> receivers,
                               std::span<const ChangedRegion> regions, const RelightSettings& settings,
                               RelightReport* report) {
  GLINT_CHECK(regions.size() <= size_t(kMaxRegions), "relightRatios: too many changed regions");
  GLINT_CHECK(settings.rays >= 1 && settings.minRays >= 1 && settings.hemisphereRays >= 1 && settings.quickRays >= 1 &&
                  settings.maxRatio >= 1 && settings.minRelativeChange >= 0,
              "relightRatios: bad settings");
  std::vector<Rgb> ratios(receivers.size(), Rgb(1.0f));
  // Which receivers the edit can reach: those with a normal that see a changed region above
  // their horizon under minSolidAngle or more.
  std::vector<uint8_t> inReach(receivers.size(), 0);
  auto receiverFrame = [&](size_t i, Vec3f* p, Vec3f* n, Cone* cones, float* solidAngle) {
    const uint32_t g = receivers[i];
    const float normalLength = length(afterScene.normal[g]);
    if (!(normalLength >= settings.minNormalLength)) return 0;
    *n = afterScene.normal[g] / normalLength, *p = afterScene.position[g];
    const int coneCount = conesToward(*p, *n, regions, cones);
    float largest = 0;
    *solidAngle = 0;
    for (int c = 0; c < coneCount; ++c) *solidAngle += cones[c].solidAngle, largest = std::max(largest, cones[c].solidAngle);
    return largest < settings.minSolidAngle ? 0 : coneCount;
  };
  parallelFor(int64_t(receivers.size()), 256, [&](int64_t i) {
    Vec3f p, n;
    Cone cones[kMaxRegions];
    float solidAngle = 0;
    inReach[size_t(i)] = receiverFrame(size_t(i), &p, &n, cones, &solidAngle) > 0;
  });
  std::vector<uint32_t> reached;  // indices into receivers
  for (size_t i = 0; i < receivers.size(); ++i)
    if (inReach[i]) reached.push_back(uint32_t(i));
  const std::vector<Vec3f> normals = unitNormals(afterScene, receivers, reached);
  float spacing = 0;
  const std::vector<uint32_t> traced = tracedReceivers(afterScene, receivers, reached, normals, settings, &spacing);
  const std::vector<LightRegion> lights = lightRegionsOf(afterScene, settings.lights);

  std::atomic<size_t> changed = 0, clampedCount = 0;
  std::atomic<uint64_t> rays = 0;
  ProgressBar progress("relight", int64_t(traced.size()), "Gaussians");
  // The radiance arriving at p from direction w: what the ray meets, and its reflected
  // light. Keys (receiver, sequence, sample) give both scenes the same reflected directions.
  PathSettings path = settings.path;
  path.minReflectance = settings.minReflectance;
  auto radiance = [&](const GaussianTracer& tracer, const Vec3f& p, const Vec3f& n, const Vec3f& w, uint32_t g,
                      uint64_t sequence, uint32_t k, uint64_t* raysTraced) {
    return incomingRadiance(tracer, p, n, w, path, {settings.seed, g, sequence, k}, raysTraced);
  };
  auto cancelled = [&] { return settings.cancel && settings.cancel->load(std::memory_order_relaxed); };
  parallelFor(int64_t(traced.size()), 16, [&](int64_t t) {
    if (cancelled()) return;
    const size_t i = traced[size_t(t)];
    const uint32_t g = receivers[i];
    Vec3f p, n;
    Cone cones[kMaxRegions];
    float solidAngle = 0;
    const int coneCount = receiverFrame(i, &p, &n, cones, &solidAngle);

    // dE by one-sample MIS over the cones: pick a changed region's cone uniformly, a direction in it, and
    // divide by the mean of the densities of every cone that holds the direction. Where a
    // light region shares directions with the changed regions, half the rays aim at the
    // lights instead: the light an object blocks or uncovers is most of the change, and a
    // small bright emitter is rarely met by rays spread over a large object.
    Cone lightCones[kMaxLights];
    const int lightCount =
        lightConesToward(p, n, lights, std::span<const Cone>(cones, size_t(coneCount)), lightCones, kMaxLights);
    int count = std::clamp(int(std::ceil(float(settings.rays) * solidAngle / kFullRaysSolidAngle)), settings.minRays,
                           settings.rays);
    const uint64_t stream = hashKeys({settings.seed, g, 0});
    uint64_t raysTraced = 0;
    Rgb changeSum(0.0f);
    auto addChangeRays = [&](int begin, int end) {
      for (int k = begin; k < end; ++k) {
        Vec2f u = stratifiedSample2(stream, uint32_t(k));
        const bool towardLight = lightCount > 0 && u.x >= 0.5f;
        if (lightCount > 0) u.x = towardLight ? 2.0f * u.x - 1.0f : 2.0f * u.x;
        const Vec3f w =
            towardLight ? sampleConeMixture(lightCones, lightCount, u) : sampleConeMixture(cones, coneCount, u);
        float cosine = dot(n, w);
        if (cosine <= 0) continue;
        // Outside every changed region the radiance is the same before and after.
        const float regionPdf = coneMixturePdf(cones, coneCount, w);
        if (!(regionPdf > 0)) continue;
        const float pdf = lightCount > 0 ? 0.5f * (regionPdf + coneMixturePdf(lightCones, lightCount, w)) : regionPdf;
        Rgb difference = radiance(after, p, n, w, g, 0, uint32_t(k), &raysTraced) -
                         radiance(before, p, n, w, g, 0, uint32_t(k), &raysTraced);
        changeSum += difference * (cosine / pdf);
      }
    };
    addChangeRays(0, count);
    Rgb change = changeSum * (1.0f / float(count));
    if (change == Rgb(0.0f)) {  // every ray met the same radiance in both scenes
      rays.fetch_add(raysTraced, std::memory_order_relaxed);
      return progress.advance();
    }

    // E_before = pi x mean radiance over cosine-distributed directions: a first estimate,
    // then the rest of the stratified sequence where the change is large enough to matter.
    // (Aiming half of these rays at the lights too measured worse on the Blender
    // spheres_room: the cosine rays left for the light bounced off walls grew noisier; README,
    // "Edits that move shadows".)
    const uint64_t hemisphere = hashKeys({settings.seed, g, 1});
    Rgb sum(0.0f);
    auto addRays = [&](int begin, int end) {
      addCosineRadiance(before, p, n, path, hemisphere, {settings.seed, g, 1, 0}, begin, end, &sum, &raysTraced);
    };
    const int quick = std::min(settings.quickRays, settings.hemisphereRays);
    addRays(0, quick);
    const float quickLuminance = luminance(sum * (kPi / float(quick)));
    const float largestChange = std::max({std::abs(change.x), std::abs(change.y), std::abs(change.z)});
    if (largestChange < settings.minRelativeChange * quickLuminance) {
      rays.fetch_add(raysTraced, std::memory_order_relaxed);
      return progress.advance();
    }
    addRays(quick, settings.hemisphereRays);
    Rgb irradiance = sum * (kPi / float(settings.hemisphereRays));

    bool clamped = false;
    ratios[size_t(i)] = irradianceRatio(irradiance, change, settings.maxRatio, &clamped);
    // A ratio far from 1 multiplies the relative error of E_before (and divides dE's by a
    // small E_before): where it leaves [1 / refineBeyond, refineBeyond], both estimates go
    // on along their sequences to refineFactor times their rays.
    const float lumRatio = luminance(ratios[size_t(i)]);
    if (settings.refineFactor > 1 && (lumRatio > settings.refineBeyond || lumRatio * settings.refineBeyond < 1)) {
      const int refinedCount = count * settings.refineFactor, refinedHemisphere = settings.hemisphereRays * settings.refineFactor;
      addChangeRays(count, refinedCount);
      change = changeSum * (1.0f / float(refinedCount));
      addRays(settings.hemisphereRays, refinedHemisphere);
      irradiance = sum * (kPi / float(refinedHemisphere));
      clamped = false;
      ratios[size_t(i)] = irradianceRatio(irradiance, change, settings.maxRatio, &clamped);
    }
    if (ratios[size_t(i)] != Rgb(1.0f)) changed.fetch_add(1, std::memory_order_relaxed);
    if (clamped) clampedCount.fetch_add(1, std::memory_order_relaxed);
    rays.fetch_add(raysTraced, std::memory_order_relaxed);
    progress.advance();
  });
  if (cancelled()) {
    progress.setStatus("cancelled");  // the bar ends short of 100%: say why
    throw RelightCancelled();
  }
  if (settings.filterRadius > 0 || spacing > 0) {
    ratios = filteredRatios(afterScene, receivers, reached, traced, normals, ratios, settings, spacing);
    changed = size_t(std::count_if(ratios.begin(), ratios.end(), [](const Rgb& r) { return r != Rgb(1.0f); }));
  }
  if (report) {
    report->receivers = receivers.size();
    report->reached = reached.size();
    report->traced = traced.size();
    report->changed = changed;
    report->clamped = clampedCount;
    report->rays = rays;
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
