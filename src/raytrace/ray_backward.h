// The backward half of the fused forward/backward pass (paper section 3.3): given a ray's
// composited hits (the HitList its trace left in memory) and dL/d of its blended outputs,
// replays the hits back to front and hands every hit its parameter gradients. The
// compositing adjoint is derived in docs/derivations.md D11, the truncation tail D12.
#pragma once

#include <type_traits>
#include <vector>

#include "core/cpu_gpu.h"
#include "raytrace/compositor.h"
#include "raytrace/gaussian_gradients.h"
#include "raytrace/gaussian_kernel_vjp.h"
#include "raytrace/gaussian_tracer.h"
#include "raytrace/ray_result.h"
#include "scene/gaussians.h"

namespace glint {

// dL/d of each blended output of a RayResult (the adjoint the loss produces).
struct RayResultAdjoint {
  Rgb v_diffuse;
  float v_depth = 0;
  Vec3f v_normal;
  float v_roughness = 0;
  Rgb v_f0;
  // dL/d the blended roughness and F0 with the compositing weights held fixed: each hit's
  // own roughness and F0 receive their share w_i, its opacity, position and shape nothing.
  // How L_r's material gradient (D15) reaches a surface: it is to set the material of the
  // surface a path leaves, not to move or fade it (docs/derivations.md D15).
  float v_roughnessWeightsHeld = 0;
  Rgb v_f0WeightsHeld;

  GLINT_CPU_GPU bool isZero() const {
    return v_diffuse == Rgb(0.0f) && v_depth == 0.0f && v_normal == Vec3f(0.0f) && v_roughness == 0.0f &&
           v_f0 == Rgb(0.0f) && v_roughnessWeightsHeld == 0.0f && v_f0WeightsHeld == Rgb(0.0f);
  }
};

// The values a hit blends, as one vector a_i = (c_i, t_i, n_i, rho_i, F0_i) (D11).
template <typename T>
struct BlendedValues {
  Vec3<T> diffuse;
  T depth = 0;
  Vec3<T> normal;
  T roughness = 0;
  Vec3<T> f0;

  GLINT_CPU_GPU T dot(const RayResultAdjoint& g) const {
    return glint::dot(diffuse, Vec3<T>(g.v_diffuse)) + depth * T(g.v_depth) + glint::dot(normal, Vec3<T>(g.v_normal)) +
           roughness * T(g.v_roughness) + glint::dot(f0, Vec3<T>(g.v_f0));
  }
  GLINT_CPU_GPU void addScaled(const BlendedValues& a, T w) {
    diffuse += a.diffuse * w;
    depth += a.depth * w;
    normal += a.normal * w;
    roughness += a.roughness * w;
    f0 += a.f0 * w;
  }
};

// What the backward pass reads of the scene, as arrays in CPU or GPU memory: the kernel's
// parameters and the attributes compositing blends.
struct BackwardScene {
  KernelParamArrays kernel;
  GaussianAttributes attributes;

  static BackwardScene of(const GaussianScene& scene) {
    return {KernelParamArrays::of(scene), GaussianAttributes::of(scene)};
  }
};

template <typename T>
GLINT_CPU_GPU BlendedValues<T> blendedValues(const GaussianAttributes& a, const HitRecord& hit) {
  uint32_t i = hit.id;
  return {Vec3<T>(a.diffuse[i]), T(hit.t), Vec3<T>(a.normal[i]), T(a.roughness[i]), Vec3<T>(a.f0[i])};
}

// Scratch memory of one thread, reused from ray to ray (no allocation on the hot path).
template <typename T>
struct RayBackwardScratch {
  std::vector<T> transmittance;  // T_i before hit i
  std::vector<T> alpha;          // alpha_i
  std::vector<T> key;            // t_i
};

// The smallest hit-list capacity that can never overflow: every composited hit has alpha
// >= alphaMin, so after n hits T <= (1 - alphaMin)^n, and compositing stops below
// minTransmittance.
size_t hitCapacityWithoutOverflow(const TraceSettings& settings);

// Back-propagates v (dL/d result) through the compositing of the n composited hits
// (front to back) and through each hit's kernel, calling sink(id, HitGradient<T>) once per
// hit (back to front). `truncated` and `finalTransmittance` are what the trace returned
// for the same ray (RayResult::truncated, ::transmittance); the list must be whole (not
// overflowed). For a truncated ray, the tail estimate's colour is detached and its
// final-transmittance ratio T_f / tau_n is held fixed (D12; 0 for the opaque tail).
// trans (n + 1 entries), alphas and keys (n each) are scratch. The one source of the CPU's
// backward pass (backwardRay) and the GPU's.
template <typename T, typename Sink>
GLINT_CPU_GPU void backwardHits(const BackwardScene& scene, const TraceSettings& settings, const TraceRay& ray,
                                const HitRecord* hits, size_t n, bool truncated, float finalTransmittance,
                                const RayResultAdjoint& v, T* trans, T* alphas, T* keys, Sink& sink) {
  if (n == 0) return;
  Vec3<T> o(ray.origin), d(ray.direction);
  T tMin = T(ray.tMin);
  // Forward replay: each hit's alpha and key, the transmittance before it, and the
  // composited values C. In float the trace's records are used as they are; in double
  // (the finite-difference oracle's precision) the kernel is re-evaluated, so that the
  // gradient is not limited by the records' float rounding.
  trans[0] = T(1);
  BlendedValues<T> composited;
  for (size_t i = 0; i < n; ++i) {
    const HitRecord& h = hits[i];
    alphas[i] = T(h.alpha);
    keys[i] = T(h.t);
    if constexpr (std::is_same_v<T, double>) {
      KernelHit<double> exact;
      if (evaluateGaussian(gaussianFrame(kernelParams<double>(scene.kernel, h.id), settings), o, d, tMin, settings,
                           &exact)) {
        alphas[i] = exact.alpha;
        keys[i] = exact.key;
      }
    }
    BlendedValues<T> a = blendedValues<T>(scene.attributes, h);
    a.depth = keys[i];
    composited.addScaled(a, trans[i] * alphas[i]);
    trans[i + 1] = trans[i] * (T(1) - alphas[i]);
  }
  const T tauN = trans[n];

  // Truncation tail (D12): out = C + tau_n * b with the background b = (1 - T_f / tau_n)
  // C / (1 - tau_n) detached, so that alpha gradients see the tail as a background.
  T behind = 0;  // S = sum_{j > i} w_j (g . a_j) + tau_n (g . b), built back to front
  if (truncated && tauN < T(1)) {
    T remaining = T(finalTransmittance) / tauN;  // product of (1 - alpha) over the tail
    T scale = (T(1) - remaining) / (T(1) - tauN);
    behind = tauN * scale * composited.dot(v);
  }

  for (size_t k = n; k-- > 0;) {
    const HitRecord& h = hits[k];
    T alpha = alphas[k];
    T w = trans[k] * alpha;
    BlendedValues<T> a = blendedValues<T>(scene.attributes, h);
    a.depth = keys[k];
    T ga = a.dot(v);
    // dL/dalpha_k = T_k (g . a_k) - S / (1 - alpha_k) (D11).
    T v_alpha = trans[k] * ga - behind / (T(1) - alpha);
    behind += w * ga;
    T v_key = w * T(v.v_depth);

    KernelGrad<T> kg = evaluateGaussian_vjp(kernelParams<T>(scene.kernel, h.id), o, d, tMin, settings, v_alpha, v_key);
    HitGradient<T> g;
    g.v_position = kg.v_mean;
    g.v_rotation = kg.v_rotation;
    g.v_logScale = kg.v_logScale;
    g.v_opacityLogit = kg.v_opacityLogit;
    g.v_diffuse = Vec3<T>(v.v_diffuse) * w;
    g.v_normal = Vec3<T>(v.v_normal) * w;
    g.v_roughness = (T(v.v_roughness) + T(v.v_roughnessWeightsHeld)) * w;
    g.v_f0 = (Vec3<T>(v.v_f0) + Vec3<T>(v.v_f0WeightsHeld)) * w;
    g.weight = w;
    sink(h.id, g);
  }
}

// backwardHits on the CPU, for a ray's HitList and RayResult, with a thread's scratch.
template <typename T, typename Sink>
void backwardRay(const GaussianScene& scene, const TraceSettings& settings, const TraceRay& ray, const HitList& hits,
                 const RayResult& result, const RayResultAdjoint& v, RayBackwardScratch<T>& scratch, Sink&& sink) {
  const size_t n = hits.hits.size();
  if (n == 0) return;
  scratch.transmittance.resize(n + 1);
  scratch.alpha.resize(n);
  scratch.key.resize(n);
  backwardHits<T>(BackwardScene::of(scene), settings, ray, hits.hits.data(), n, result.truncated,
                  result.transmittance, v, scratch.transmittance.data(), scratch.alpha.data(), scratch.key.data(),
                  sink);
}

}  // namespace glint
