// The obviously-correct Gaussian tracer the fast ones are tested against: every ray is
// evaluated against every Gaussian in double precision, hits are fully sorted by
// (key, id), and composited with the shared Compositor. Slow by design: O(rays x Gaussians).
#pragma once

#include <vector>

#include "raytrace/gaussian_kernel.h"
#include "raytrace/gaussian_tracer.h"

namespace glint {

class ReferenceTracer final : public GaussianTracer {
 public:
  const char* name() const override { return "reference"; }
  void build(const GaussianScene& scene, const TraceSettings& settings) override;
  void refit() override;
  RayResult trace(const TraceRay& ray, HitList* hits = nullptr) const override;
  size_t memoryBytes() const override;

 private:
  const GaussianScene* scene_ = nullptr;
  TraceSettings settings_;
  std::vector<GaussianFrame<double>> frames_;
};

}  // namespace glint
