// Path segments through the Gaussians with GGX importance sampling, one path alone or a
// batch bounce by bounce.
#include "render/gaussian_path.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "core/error.h"
#include "core/parallel.h"
#include "render/ray_order.h"

namespace glint {

namespace {

// Adds segment k's light to the path's sums.
void addLight(PathResult* path, int k, const Rgb& light) {
  path->specular += light;
  if (k <= kSeparateBounces) path->bounceLight[size_t(k - 1)] = light;
  ++path->segments;
}

}  // namespace

PathResult tracePath(const GaussianTracer& tracer, const TraceRay& primary, const PathSettings& settings,
                     uint64_t seed, uint64_t view, uint64_t pixel, uint64_t sample,
                     std::vector<PathSegment>* segments) {
  // Traces one segment, recording it when asked. Recorded segments reuse the entries (and
  // hit-list memory) of earlier paths.
  size_t recorded = 0;
  auto traceSegment = [&](const TraceRay& ray, const Rgb& throughput) {
    if (!segments) return tracer.trace(ray);
    if (recorded == segments->size()) segments->emplace_back();
    PathSegment& s = (*segments)[recorded++];
    s.ray = ray;
    s.throughput = throughput;
    s.hits.capacity = settings.hitListCapacity;
    s.result = tracer.trace(ray, &s.hits);
    return s.result;
  };
  const PathKey key{view, pixel, sample};
  PathResult path;
  path.first = traceSegment(primary, Rgb(1.0f));
  path.specular = Rgb(0.0f);
  RayResult current = path.first;
  TraceRay ray = primary;
  Rgb throughput(1.0f);
  for (int k = 1; k <= settings.bounces; ++k) {
    TraceRay next;
    Rgb weight;
    if (!continuePath(ray, current, settings, seed, key, k, &next, &weight)) break;
    throughput = throughput * weight;
    current = traceSegment(next, throughput);
    addLight(&path, k, throughput * current.diffuse);
    ray = next;
  }
  return path;
}

void PathBatch::trace(const GaussianTracer& tracer, std::span<const TraceRay> primaries, std::span<const PathKey> keys,
                      uint64_t seed, const PathSettings& settings, std::span<PathResult> results, bool record) {
  GLINT_CHECK(keys.size() == primaries.size() && results.size() == primaries.size(),
              "PathBatch::trace: one key and one result per path");
  const size_t n = primaries.size();
  const int bounces = std::max(settings.bounces, 0);
  if (record) {
    stride_ = size_t(bounces) + 1;
    if (segments_.size() < n * stride_) segments_.resize(n * stride_);
    counts_.assign(n, 1);
  }
  // Level 0: every path's first segment.
  active_.resize(n);
  rays_.assign(primaries.begin(), primaries.end());
  throughput_.assign(n, Rgb(1.0f));
  for (size_t i = 0; i < n; ++i) active_[i] = uint32_t(i);
  for (int k = 0;; ++k) {
    const size_t m = active_.size();
    results_.resize(m);
    const bool recordHits = record && (k == 0 || !firstSegmentHitsOnly_);
    if (recordHits) {
      if (hits_.size() < m) hits_.resize(m);
      for (size_t j = 0; j < m; ++j) hits_[j].capacity = settings.hitListCapacity;
    }
    tracer.traceBatch(rays_, results_, recordHits ? std::span<HitList>(hits_.data(), m) : std::span<HitList>(),
                      k == 0 ? settings.primaryCoherence : RayCoherence::Scattered);
    // Each path takes its segment's light (and record); then the ones that go on draw
    // their next segment. Paths are independent, so the loop is parallel.
    nextRays_.resize(m);
    nextThroughput_.resize(m);
    continues_.assign(m, 0);
    parallelForChunks(int64_t(m), 256, [&](int64_t begin, int64_t end) {
      for (int64_t j = begin; j < end; ++j) {
        const uint32_t i = active_[size_t(j)];
        PathResult& path = results[i];
        const RayResult& r = results_[size_t(j)];
        if (k == 0) {
          path = PathResult{};
          path.first = r;
          path.specular = Rgb(0.0f);
        } else {
          addLight(&path, k, throughput_[size_t(j)] * r.diffuse);
        }
        if (record) {
          PathSegment& s = segments_[i * stride_ + size_t(k)];
          s.ray = rays_[size_t(j)];
          s.throughput = throughput_[size_t(j)];
          s.result = r;
          if (recordHits)
            std::swap(s.hits, hits_[size_t(j)]);  // the segment's list; its old memory serves the next level
          else
            s.hits.clear();
          counts_[i] = uint8_t(k + 1);
        }
        if (k == bounces) continue;
        Rgb weight;
        if (continuePath(rays_[size_t(j)], r, settings, seed, keys[i], k + 1, &nextRays_[size_t(j)], &weight)) {
          nextThroughput_[size_t(j)] = throughput_[size_t(j)] * weight;
          continues_[size_t(j)] = 1;
        }
      }
    });
    if (k == bounces) break;
    // Compaction, in path order (the next level's rays follow their paths' order).
    size_t alive = 0;
    for (size_t j = 0; j < m; ++j) {
      if (!continues_[j]) continue;
      active_[alive] = active_[j];
      rays_[alive] = nextRays_[j];
      throughput_[alive] = nextThroughput_[j];
      ++alive;
    }
    if (alive == 0) break;
    active_.resize(alive);
    rays_.resize(alive);
    throughput_.resize(alive);
    if (settings.reflectedOrder == ReflectedRayOrder::OriginAndOctant) sortByOriginAndOctant();
  }
}

void PathBatch::sortByOriginAndOctant() {
  const size_t m = rays_.size();
  Vec3f lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
  for (const TraceRay& r : rays_) lo = min(lo, r.origin), hi = max(hi, r.origin);
  const Vec3f extent = max(hi - lo, Vec3f(1e-20f));
  sortKeys_.resize(m);
  for (size_t j = 0; j < m; ++j) sortKeys_[j] = {rayOrderKey(rays_[j].origin, rays_[j].direction, lo, extent), uint32_t(j)};
  std::sort(sortKeys_.begin(), sortKeys_.end());
  // Gathered into the next level's candidate arrays (unused until the next level is
  // drawn), then swapped in, so sorting allocates nothing once warm.
  nextRays_.resize(m);
  nextThroughput_.resize(m);
  sortedActive_.resize(m);
  for (size_t j = 0; j < m; ++j) {
    const uint32_t from = sortKeys_[j].second;
    sortedActive_[j] = active_[from], nextRays_[j] = rays_[from], nextThroughput_[j] = throughput_[from];
  }
  active_.swap(sortedActive_), rays_.swap(nextRays_), throughput_.swap(nextThroughput_);
}

size_t PathBatch::memoryBytes() const {
  size_t bytes = (active_.capacity() + sortedActive_.capacity()) * sizeof(uint32_t) +
                 sortKeys_.capacity() * sizeof(sortKeys_[0]) +
                 (rays_.capacity() + nextRays_.capacity()) * sizeof(TraceRay) + results_.capacity() * sizeof(RayResult) +
                 (throughput_.capacity() + nextThroughput_.capacity()) * sizeof(Rgb) + continues_.capacity() +
                 counts_.capacity() + segments_.capacity() * sizeof(PathSegment) + hits_.capacity() * sizeof(HitList);
  for (const HitList& h : hits_) bytes += h.hits.capacity() * sizeof(HitRecord);
  for (const PathSegment& s : segments_) bytes += s.hits.hits.capacity() * sizeof(HitRecord);
  return bytes;
}

size_t PathBatch::bytesPerPath(bool record) {
  return sizeof(uint32_t) + 2 * sizeof(TraceRay) + sizeof(RayResult) + 2 * sizeof(Rgb) + 1 +
         (record ? sizeof(HitList) + sizeof(PathSegment) + 1 : 0);
}

Rgb pathSpecular(std::span<const PathSegment> segments) {
  Rgb specular(0.0f);
  for (size_t k = 1; k < segments.size(); ++k) specular += segments[k].throughput * segments[k].result.diffuse;
  return specular;
}

float reflectionGradientWeight(std::span<const PathSegment> segments, size_t k) {
  float rho = std::clamp(segments[k - 1].result.roughness, 0.0f, 1.0f);
  return (1 - rho) * (1 - rho) * (1 - rho);
}

int appendBackwardJobs(std::span<const PathSegment> segments, const RayResultAdjoint& v_first, const Rgb& v_specular,
                       const PathGradientSettings& settings, std::vector<BackwardJob>* jobs,
                       std::vector<HitRecord>* hits) {
  return forEachSegmentAdjoint(segments, v_first, v_specular, settings,
                               [&](const PathSegment& segment, const RayResultAdjoint& v) {
                                 const std::vector<HitRecord>& h = segment.hits.hits;
                                 if (h.empty()) return;
                                 GLINT_CHECK(hits->size() + h.size() < size_t(UINT32_MAX),
                                             "a backward batch of more than 4 billion hits");
                                 BackwardJob job;
                                 job.ray = segment.ray;
                                 job.firstHit = uint32_t(hits->size());
                                 job.hitCount = uint32_t(h.size());
                                 job.truncated = segment.result.truncated;
                                 job.transmittance = segment.result.transmittance;
                                 job.v = v;
                                 jobs->push_back(job);
                                 hits->insert(hits->end(), h.begin(), h.end());
                               });
}

}  // namespace glint
