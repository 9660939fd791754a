// Seeds of far-field Gaussians along unexplained mirror reflections of the training views.
#include "train/reflection_seeds.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>
#include <vector>

#include "bsdf/fresnel.h"
#include "io/tonemap.h"
#include "math/rng.h"
#include "train/training_views.h"

namespace glint {

namespace {

// The most mirror pixels whose reflections vote (an even stride over all of them beyond
// this): the photo-consistency test needs many rays per cell whatever the number of seeds
// asked for, and marching them (a few hundred cells each) is the cost.
constexpr size_t kMaxRays = 262144;
// Photo-consistency (voxel colouring, Seitz and Dyer 1999): space is cut into cells of this
// fraction of the scene radius; the colours (c / (1 + c) per channel, which keeps HDR
// emitters comparable) of the reflected rays crossing a cell agree when their variance is
// below kMaxColourStd^2. A few rays agree by chance (two-colour texture: 2 / 2^n of n
// rays), so the variance is shrunk toward kPriorVariance (a cell of mixed colours) as if
// kPriorRays more rays had that spread: n rays of one colour pass at n >= about 15.
constexpr float kCellFraction = 1.0f / 48.0f;
constexpr int kMinViews = 3;
constexpr float kMaxColourStd = 0.07f;
constexpr float kPriorVariance = 0.0225f;
constexpr float kPriorRays = 4.0f;

struct Candidate {
  TraceRay ray;
  Rgb radiance;  // what the pixel's specular buffer says the reflected ray sees
  uint32_t view = 0;
  float tEnd = 0;          // end of the ray's free segment (the warm-up's scene, or 3 R)
  bool explained = false;  // the warm-up's scene already shows the right colour there
};

// What the reflected rays crossing one cell saw.
struct CellColours {
  Rgb sum{0.0f}, sumSquares{0.0f};
  int rays = 0, views = 0;
  int64_t lastView = -1;
  // The seed of the cell: the mean entry point and colour of the rays that stop in it.
  Vec3f pointSum{0.0f};
  Rgb radianceSum{0.0f};
  int stopped = 0;
  int8_t observed = -1;  // whether some view sees the cell's first stop point as empty (-1: not asked yet)

  // The largest variance of a channel, shrunk toward the prior; infinity when fewer than
  // kMinViews views crossed.
  float variance() const {
    if (views < kMinViews) return INFINITY;
    const Rgb mean = sum / float(rays);
    const Rgb v = sumSquares / float(rays) - mean * mean;
    return (float(rays) * std::max({v.x, v.y, v.z}) + kPriorRays * kPriorVariance) / (float(rays) + kPriorRays);
  }
};

Rgb compressed(const Rgb& c) { return {c.x / (1 + c.x), c.y / (1 + c.y), c.z / (1 + c.z)}; }

class CellGrid {
 public:
  explicit CellGrid(float cell) : cell_(cell) {}
  uint64_t key(const Vec3f& p) const {
    constexpr int64_t kOffset = int64_t(1) << 20;  // 21 bits per axis, centred on the origin
    auto axis = [&](float x) { return uint64_t(std::clamp<int64_t>(int64_t(std::floor(x / cell_)) + kOffset, 0, 2 * kOffset - 1)); };
    return axis(p.x) | axis(p.y) << 21 | axis(p.z) << 42;
  }
  // Calls f(key, t) once for each cell the segment [t0, t1] of the ray crosses, near to far,
  // at the first sample in it (samples every half cell).
  template <typename F>
  void march(const TraceRay& ray, float t0, float t1, F&& f) const {
    uint64_t last = ~uint64_t(0);
    for (float t = t0; t <= t1; t += 0.5f * cell_) {
      const uint64_t k = key(ray.origin + ray.direction * t);
      if (k == last) continue;
      last = k;
      if (!f(k, t)) return;
    }
  }

 private:
  float cell_;
};

// Near-mirror training pixels (about `wanted` of them, an even stride over every view) and
// the rays their mirrors reflect.
std::vector<Candidate> mirrorReflections(const FarFieldSettings& s, const TrainingViews& views, size_t wanted,
                                         float backfaceSkip, float sceneRadius) {
  size_t mirrorPixels = 0;
  auto isMirror = [&](size_t view, size_t pixel) {
    return views.surfaceAt(view, pixel) && views.target(view, pixel).roughness < s.reflectionSeedRoughness;
  };
  for (size_t v = 0; v < views.viewCount(); ++v)
    for (size_t p = 0; p < views.pixelCount(v); ++p) mirrorPixels += isMirror(v, p);
  const size_t stride = std::max<size_t>(1, mirrorPixels / std::max<size_t>(wanted, 1));
  std::vector<Candidate> candidates;
  size_t index = 0;
  for (size_t v = 0; v < views.viewCount(); ++v)
    for (size_t p = 0; p < views.pixelCount(v); ++p) {
      if (!isMirror(v, p) || index++ % stride != 0) continue;
      const PixelTarget t = views.target(v, p);
      const TraceRay eye = views.pixelRay(v, p);
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
      c.view = uint32_t(v);
      candidates.push_back(c);
    }
  return candidates;
}

}  // namespace

GaussianScene reflectionSeeds(const FarFieldSettings& s, const TrainingViews& views, const GaussianTracer& tracer,
                              const TraceSettings& trace, float backfaceSkip, float sceneRadius, uint64_t seed) {
  const SupervisedBuffers& has = views.supervised();
  if (s.reflectionSeeds <= 0 || views.viewCount() == 0 || !has.depth || !has.normal || !has.roughness ||
      !has.specular || has.finalColour)
    return {};
  Rng rng = Rng::forKeys({seed, 0x7265666c73656564ull});  // "reflseed"

  // 1. Near-mirror training pixels and the rays their mirrors reflect.
  std::vector<Candidate> candidates =
      mirrorReflections(s, views, kMaxRays, backfaceSkip, sceneRadius);

  // 2. What the warm-up's scene shows along each reflected ray: where its free segment ends,
  //    and whether it already explains the pixel.
  std::vector<TraceRay> rays(candidates.size());
  for (size_t i = 0; i < candidates.size(); ++i) rays[i] = candidates[i].ray;
  std::vector<RayResult> results(rays.size());
  tracer.traceBatch(rays, results, {}, RayCoherence::Scattered);
  const float tNear = 0.02f * sceneRadius, tFar = 3.0f * sceneRadius;
  for (size_t i = 0; i < candidates.size(); ++i) {
    const RayResult& r = results[i];
    const float opacity = 1.0f - r.transmittance;
    const float expected = luminance(candidates[i].radiance);
    candidates[i].explained =
        opacity >= 0.5f && std::abs(luminance(r.diffuse) - expected) <= 0.2f * expected + 0.02f;
    candidates[i].tEnd = opacity >= 0.5f ? std::min(r.depth / opacity, tFar) : tFar;
  }

  // 3. Voxel colouring along the free segments: every ray votes its colour into the cells it
  //    crosses. A cell on a surface gets the same colour from every view that sees it in a
  //    mirror; a cell of empty space gets whatever lies behind it, which differs by view.
  const CellGrid grid(kCellFraction * sceneRadius);
  std::unordered_map<uint64_t, CellColours> cells;
  for (const Candidate& c : candidates) {  // in view order, so that lastView counts views
    const Rgb colour = compressed(c.radiance);
    grid.march(c.ray, tNear, c.tEnd, [&](uint64_t k, float) {
      CellColours& cell = cells[k];
      cell.sum += colour;
      cell.sumSquares += colour * colour;
      ++cell.rays;
      if (cell.lastView != int64_t(c.view)) {
        ++cell.views;
        cell.lastView = int64_t(c.view);
      }
      return true;
    });
  }
  // Each reflection the scene does not explain stops in the most consistent cell on its way
  // (the lowest colour variance; the nearest of equals) that no view sees to be empty: on a
  // textured surface the views' reflections agree best where they meet it. (The uniform
  // sky over a mirror is consistent everywhere, also in the room the cameras see.)
  const std::vector<Mat4> worldToCamera = worldToCameras(views);
  for (const Candidate& c : candidates) {
    if (c.explained) continue;
    CellColours* best = nullptr;
    float bestVariance = kMaxColourStd * kMaxColourStd;
    Vec3f bestPoint;
    grid.march(c.ray, tNear, c.tEnd, [&](uint64_t k, float t) {
      CellColours& cell = cells.at(k);
      const float variance = cell.variance();
      if (!(variance < bestVariance)) return true;
      const Vec3f point = c.ray.origin + c.ray.direction * t;
      if (cell.observed < 0) cell.observed = gapBehindObservedSurfaces(Vec3d(point), views, worldToCamera) > 0.0 ? 0 : 1;
      if (cell.observed) return true;
      best = &cell;
      bestVariance = variance;
      bestPoint = point;
      return true;
    });
    if (!best) continue;
    best->pointSum += bestPoint;
    best->radianceSum += c.radiance;
    ++best->stopped;
  }
  std::vector<std::pair<uint64_t, const CellColours*>> stops;
  for (const auto& [k, cell] : cells)
    if (cell.stopped > 0) stops.emplace_back(k, &cell);
  std::sort(stops.begin(), stops.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Vec3f> points;
  std::vector<Rgb> radiance;
  for (const auto& [k, cell] : stops) {
    points.push_back(cell->pointSum / float(cell->stopped));
    radiance.push_back(cell->radianceSum / float(cell->stopped));
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
