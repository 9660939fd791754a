// Rays that relighting and the healed colours' lighting trace from surface points, many
// points' at once through PathBatch (the renderer's wavefront): each ray's radiance as
// incomingRadiance counts it (the blended diffuse colour it meets plus its reflected light).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/parallel.h"
#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_path.h"

namespace glint {

// One ray of a batch: its path key and the weight its radiance takes in its owner's sum.
struct PendingRay {
  TraceRay ray;
  PathKey key;
  float weight = 1;
};

// The rays of one step from many owners (receivers, points), traced through one scene or two.
class RadianceBatch {
 public:
  // Gathers the rays of every owner for which make(owner, &rays) adds any, made in parallel
  // and kept in owner order; owner k's rays are then begin(k)..end(k)-1.
  template <typename Make>
  void gather(size_t owners, Make&& make) {
    std::vector<std::vector<PendingRay>> made(owners);
    parallelFor(int64_t(owners), 16, [&](int64_t k) { make(size_t(k), &made[size_t(k)]); });
    rays_.clear(), keys_.clear(), weights_.clear(), begins_.assign(owners + 1, 0);
    for (size_t k = 0; k < owners; ++k) {
      begins_[k] = rays_.size();
      for (const PendingRay& r : made[k]) rays_.push_back(r.ray), keys_.push_back(r.key), weights_.push_back(r.weight);
    }
    begins_[owners] = rays_.size();
  }
  size_t begin(size_t owner) const { return begins_[owner]; }
  size_t end(size_t owner) const { return begins_[owner + 1]; }
  // Traces the gathered rays through `tracer` into results set `which` (0 or 1).
  void trace(const GaussianTracer& tracer, uint64_t seed, const PathSettings& path, int which) {
    results_[which].resize(rays_.size());
    batch_.trace(tracer, rays_, keys_, seed, path, results_[which], /*record=*/false);
  }
  // The radiance ray i brought in results set `which`, as incomingRadiance counts it.
  Rgb radiance(size_t i, int which) const { return results_[which][i].first.diffuse + results_[which][i].specular; }
  int segments(size_t i, int which) const { return results_[which][i].segments; }
  float weight(size_t i) const { return weights_[i]; }

 private:
  std::vector<TraceRay> rays_;
  std::vector<PathKey> keys_;
  std::vector<float> weights_;
  std::vector<size_t> begins_;
  std::vector<PathResult> results_[2];
  PathBatch batch_;
};

}  // namespace glint
