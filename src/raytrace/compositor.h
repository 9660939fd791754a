// Front-to-back alpha compositing of a ray's Gaussian hits, shared by every tracer so they
// agree to rounding: w_i = T_i alpha_i, T_{i+1} = T_i (1 - alpha_i), stop below
// minTransmittance, and the truncation tail of appendix A.2.
#pragma once

#include <type_traits>

#include "core/cpu_gpu.h"
#include "raytrace/gaussian_kernel.h"
#include "raytrace/ray_result.h"
#include "scene/gaussians.h"

namespace glint {

// The attributes compositing blends, one entry per Gaussian, as plain arrays: the
// GaussianScene's vectors on the CPU, their copies in GPU memory on the GPU.
struct GaussianAttributes {
  const Rgb* diffuse = nullptr;
  const Vec3f* normal = nullptr;
  const float* roughness = nullptr;
  const Rgb* f0 = nullptr;

  static GaussianAttributes of(const GaussianScene& scene) {
    return {scene.diffuse.data(), scene.normal.data(), scene.roughness.data(), scene.f0.data()};
  }
};

// Where a compositor records its hits: a HitList (CPU), or nowhere when the list is null.
class HitListRecorder {
 public:
  explicit HitListRecorder(HitList* hits) : hits_(hits) {
    if (hits_) hits_->clear();
  }
  void record(const HitRecord& hit) {
    if (!hits_) return;
    if (hits_->hits.size() < hits_->capacity)
      hits_->hits.push_back(hit);
    else
      hits_->overflowed = true;
  }

 private:
  HitList* hits_;
};

template <typename T, typename Recorder = HitListRecorder>
class Compositor {
 public:
  GLINT_CPU_GPU Compositor(const GaussianAttributes& attributes, const TraceSettings& settings, Recorder recorder)
      : attributes_(attributes), settings_(settings), recorder_(recorder) {}
  Compositor(const GaussianScene& scene, const TraceSettings& settings, HitList* hits)
    requires std::is_same_v<Recorder, HitListRecorder>
      : Compositor(GaussianAttributes::of(scene), settings, HitListRecorder(hits)) {}

  // Reflection rays ignore Gaussians whose attached normal points along the ray (their
  // back faces: the surface the ray leaves) closer than `until` to the origin, against
  // surface acne (paper appendix B).
  GLINT_CPU_GPU void skipBackfacing(const Vec3f& direction, float until) {
    skipDirection_ = direction;
    skipUntil_ = T(until);
  }

  // Adds the next hit in front-to-back order. Returns false once the ray has terminated
  // (transmittance below the threshold): later hits only count towards the exact tail.
  // Whether add() ignores a hit of Gaussian id at this key (a back face near the origin).
  GLINT_CPU_GPU bool skips(uint32_t id, T key) const {
    return key < skipUntil_ && dot(attributes_.normal[id], skipDirection_) > 0.0f;
  }

  GLINT_CPU_GPU bool add(uint32_t id, const KernelHit<T>& h) {
    if (skips(id, h.key)) return !terminated_;
    if (terminated_) {
      tailTransmittance_ *= T(1) - h.alpha;
      return false;
    }
    T w = transmittance_ * h.alpha;
    diffuse_ += Vec3<T>(attributes_.diffuse[id]) * w;
    depth_ += h.key * w;
    normal_ += Vec3<T>(attributes_.normal[id]) * w;
    roughness_ += T(attributes_.roughness[id]) * w;
    f0_ += Vec3<T>(attributes_.f0[id]) * w;
    transmittance_ *= T(1) - h.alpha;
    ++count_;
    recorder_.record({id, float(h.key), float(h.alpha)});
    if (transmittance_ < T(settings_.minTransmittance)) {
      terminated_ = true;
      tailTransmittance_ = transmittance_;
    }
    return !terminated_;
  }

  GLINT_CPU_GPU bool terminated() const { return terminated_; }
  GLINT_CPU_GPU T transmittance() const { return transmittance_; }

  // The ray's result. A truncated ray's light behind the termination point is estimated
  // as the mean of the composited part, (T_i - T_f) * c_front / (1 - T_i) (appendix A.2;
  // the estimate is detached in the backward pass). T_f, the final transmittance, is exact
  // with exactTail; otherwise the tail is taken as opaque (T_f = 0), its limit behind any
  // solid surface. Without an estimate, training fails as the paper warns: front Gaussians
  // grow to mask a background that truncation removed. The reported transmittance is T_f.
  GLINT_CPU_GPU RayResult finish() const {
    RayResult r;
    const T finalTransmittance = finalTransmittanceEstimate();
    T tailWeight = 0;
    if (terminated_ && transmittance_ < T(1))
      tailWeight = (transmittance_ - finalTransmittance) / (T(1) - transmittance_);
    T scale = T(1) + tailWeight;
    r.diffuse = Rgb(diffuse_ * scale);
    r.depth = float(depth_ * scale);
    r.normal = Vec3f(normal_ * scale);
    r.normalLength = length(r.normal);
    r.roughness = float(roughness_ * scale);
    r.f0 = Rgb(f0_ * scale);
    r.transmittance = float(finalTransmittance);
    r.hitCount = count_;
    r.truncated = terminated_;
    return r;
  }

 private:
  GLINT_CPU_GPU T finalTransmittanceEstimate() const {
    if (!terminated_) return transmittance_;
    return settings_.exactTail ? tailTransmittance_ : T(0);
  }

  GaussianAttributes attributes_;
  const TraceSettings& settings_;
  Recorder recorder_;
  Vec3<T> diffuse_{0}, normal_{0}, f0_{0};
  T depth_ = 0, roughness_ = 0;
  T transmittance_ = 1;
  T tailTransmittance_ = 1;
  int count_ = 0;
  bool terminated_ = false;
  Vec3f skipDirection_{0.0f};
  T skipUntil_ = 0;
};

}  // namespace glint
