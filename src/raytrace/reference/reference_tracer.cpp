// Brute-force Gaussian tracing in double precision.
#include "raytrace/reference/reference_tracer.h"

#include <algorithm>

#include "core/error.h"
#include "core/parallel.h"
#include "raytrace/compositor.h"

namespace glint {

void ReferenceTracer::build(const GaussianScene& scene, const TraceSettings& settings) {
  GLINT_CHECK(scene.consistent(), "the Gaussian scene's arrays differ in length");
  scene_ = &scene;
  settings_ = settings;
  refit();
}

void ReferenceTracer::refit() {
  GLINT_CHECK(scene_ != nullptr, "refit before build");
  frames_.resize(scene_->size());
  parallelFor(int64_t(frames_.size()), 1024,
              [&](int64_t i) { frames_[i] = makeGaussianFrame<double>(*scene_, size_t(i), settings_); });
}

RayResult ReferenceTracer::trace(const TraceRay& ray, HitList* hits) const {
  GLINT_CHECK(scene_ != nullptr, "trace before build");
  struct Entry {
    uint32_t id;
    KernelHit<double> hit;
  };
  std::vector<Entry> entries;
  Vec3d o(ray.origin), d(ray.direction);
  d = normalize(d);
  for (size_t i = 0; i < frames_.size(); ++i) {
    KernelHit<double> h;
    if (evaluateGaussian(frames_[i], o, d, double(ray.tMin), settings_, &h)) entries.push_back({uint32_t(i), h});
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.hit.key != b.hit.key ? a.hit.key < b.hit.key : a.id < b.id;
  });
  Compositor<double> compositor(*scene_, settings_, hits);
  if (ray.backfaceSkip > 0) compositor.skipBackfacing(ray.direction, ray.backfaceSkip);
  for (const Entry& e : entries) {
    if (!compositor.add(e.id, e.hit) && !settings_.exactTail) break;
  }
  return compositor.finish();
}

size_t ReferenceTracer::memoryBytes() const { return frames_.capacity() * sizeof(GaussianFrame<double>); }

}  // namespace glint
