// Paths through the Gaussians (paper sections 3.1-3.2), forward and backward in one place:
// the first segment gives the blended diffuse colour and G-buffers; each later segment
// leaves the expected termination point of the previous one in a direction drawn from the
// GGX distribution of visible normals for the blended roughness, and returns the blended
// diffuse colour of what it hits (the cached irradiance of equation 3), weighted by the
// Cook-Torrance throughput. tracePaths traces a batch bounce by bounce (a wavefront),
// tracePath one path alone; both take each step with continuePath, so they agree exactly.
// tracePath_vjp is the gradient of a recorded path (docs/derivations.md D13).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "raytrace/backward_batch.h"
#include "raytrace/gaussian_tracer.h"
#include "raytrace/ray_backward.h"
#include "render/path_step.h"
#include "scene/predicted_buffers.h"

namespace glint {

// Reflected segments whose light PathResult also keeps one by one (the viewer's per-bounce
// modes); the light of later segments is only in the sum.
constexpr int kSeparateBounces = 8;

// One path's outputs: the first segment's result and the specular light of the later ones.
struct PathResult {
  RayResult first;
  Rgb specular;      // sum over segments k >= 1 of throughput_k x blended diffuse_k
  // bounceLight[k - 1] = throughput_k x blended diffuse_k of segment k (zero where the path
  // ended earlier): the terms of `specular`, for k <= kSeparateBounces.
  std::array<Rgb, kSeparateBounces> bounceLight{};
  int segments = 1;  // segments traced
};

// One traced segment, recorded for the backward pass and for inspection (--debug-pixel).
struct PathSegment {
  TraceRay ray;
  Rgb throughput;  // weight of this segment's blended diffuse in the specular sum (1 for the first)
  RayResult result;
  HitList hits;    // its composited hits, front to back
};

// Traces one path. With `segments`, every segment is traced with its hit list and recorded
// in the first PathResult::segments entries (entries beyond them are left from earlier
// paths, so their memory is reused).
PathResult tracePath(const GaussianTracer& tracer, const TraceRay& primary, const PathSettings& settings,
                     uint64_t seed, uint64_t view, uint64_t pixel, uint64_t sample,
                     std::vector<PathSegment>* segments = nullptr);

// Traces a batch of paths as a wavefront: all first segments through one traceBatch (so
// the camera rays of a view take the tracer's coherent bundles), then all second segments
// of the paths still alive, and so on. results[i] is what tracePath gives for primaries[i]
// and keys[i]. Holds its scratch memory between calls (a training step or a render tile
// allocates nothing once warm), and with `record` every segment of every path, hit lists
// included (capacity settings.hitListCapacity), for the backward pass.
class PathBatch {
 public:

  void trace(const GaussianTracer& tracer, std::span<const TraceRay> primaries, std::span<const PathKey> keys,
             uint64_t seed, const PathSettings& settings, std::span<PathResult> results, bool record);
  // With `record`, keep the hit lists of the first segments only (the later segments are
  // recorded with empty lists): what the SH bake needs, without the memory traffic of every
  // reflected segment's hits. Off by default (training replays every segment).
  void setFirstSegmentHitsOnly(bool only) { firstSegmentHitsOnly_ = only; }
  // The recorded segments of path i of the last trace with `record`.
  std::span<const PathSegment> path(size_t i) const { return {&segments_[i * stride_], counts_[i]}; }
  // Bytes held (scratch and records, hit lists included), for benchmarks.
  size_t memoryBytes() const;
  // Bytes of scratch per path when every path is alive (without hit lists), for benchmarks.
  static size_t bytesPerPath(bool record);

 private:
  // Reorders the current level's rays (and what goes with them) so that rays traced one
  // after the other start close together and point into the same octant: the key is the
  // direction's octant, then the Morton code of the origin in the level's bounding box.
  // Neighbouring rays then walk the same BVH nodes while those are in the cache. Ties keep
  // path order.
  void sortByOriginAndOctant();

  std::vector<std::pair<uint64_t, uint32_t>> sortKeys_;
  std::vector<uint32_t> sortedActive_;
  // The paths still alive at the current level, each with its last segment.
  std::vector<uint32_t> active_;
  std::vector<TraceRay> rays_;
  std::vector<RayResult> results_;
  std::vector<Rgb> throughput_;
  std::vector<HitList> hits_;
  // Candidates of the next level before compaction.
  std::vector<TraceRay> nextRays_;
  std::vector<Rgb> nextThroughput_;
  std::vector<uint8_t> continues_;
  // Records: segment k of path i at i * stride_ + k.
  size_t stride_ = 1;
  std::vector<PathSegment> segments_;
  std::vector<uint8_t> counts_;
  bool firstSegmentHitsOnly_ = false;
};

// Specular = sum over the reflected segments k >= 1 of throughput_k x blended diffuse_k
// (equation 3; the first segment carries the diffuse pass).
Rgb pathSpecular(std::span<const PathSegment> segments);

// The weight training gives segment k's gradient: (1 - rho)^3, rho the roughness of the
// surface the segment leaves (the previous segment's blended roughness, clamped to [0, 1]).
// It favours the low-variance gradients of sharp reflections (appendix B.5).
float reflectionGradientWeight(std::span<const PathSegment> segments, size_t k);

// How a recorded path's gradient reaches its segments (D13, D15).
struct PathGradientSettings {
  // Scale each reflected segment's gradient by reflectionGradientWeight (training does).
  bool weightReflections = true;
  // Weights of L_r's gradient into the roughness and the F0 of each surface a path reflects
  // off, through the step's weight with its direction and density held fixed (D15). 0, the
  // paper's choice: the throughputs are detached and nothing flows into those materials.
  float roughnessFromSpecular = 0;
  float f0FromSpecular = 0;
  // F0's gradient from L_r only where the surface left is a metal (its blended F0 reaches
  // greyF0IsMetal's 0.52): a dielectric's F0 is achromatic and set by its prior, and there
  // d log w / d F0 = 1 / F (about 25) makes L_r's noisy light loudest (docs/captures.md).
  bool f0FromSpecularMetalsOnly = false;
  // Whether those material gradients also reach the opacity, position and shape of the
  // Gaussians the segment hits (through the compositing weights that blend roughness and
  // F0): the whole derivative, which the finite-difference tests check. Off in training:
  // L_r's noisy light then moved and faded surfaces to change a blended material (on
  // builtin:room with f0_tint_from_reflections: depth RMSE 0.118 against 0.100 held, and
  // 0.93 dB of specular lost; docs/captures.md), so it sets only the Gaussians' own
  // roughness and F0 (RayResultAdjoint's *WeightsHeld).
  bool materialsMoveGeometry = false;
  PathSettings path;  // the settings the paths were traced with (continuePath's)
};

// dL/d segment k's blended outputs (D13): v_first for the first segment; for k >= 1,
// throughput_k x v_specular on its blended diffuse (times reflectionGradientWeight when
// weighted). With PathGradientSettings' material weights, a segment followed by another
// also gets, on its roughness and F0, the change of the later segments' light with the
// weight of the step it chose (D15).
inline RayResultAdjoint segmentAdjoint(std::span<const PathSegment> segments, size_t k,
                                       const RayResultAdjoint& v_first, const Rgb& v_specular,
                                       const PathGradientSettings& settings) {
  RayResultAdjoint v = k == 0 ? v_first : RayResultAdjoint{};
  if (k > 0)
    v.v_diffuse = segments[k].throughput * v_specular *
                  (settings.weightReflections ? reflectionGradientWeight(segments, k) : 1.0f);
  const bool materials = settings.roughnessFromSpecular != 0 || settings.f0FromSpecular != 0;
  if (!materials || k + 1 >= segments.size()) return v;
  // dL/d log w_{k+1}, per channel: the light of every later segment carries w_{k+1}.
  Rgb later(0.0f);
  for (size_t m = k + 1; m < segments.size(); ++m) later += v_specular * segments[m].throughput * segments[m].result.diffuse;
  const StepMaterialDerivatives d =
      stepMaterialDerivatives(segments[k].ray, segments[k].result, settings.path, segments[k + 1].ray.direction);
  const float v_roughness = settings.roughnessFromSpecular * (later.x + later.y + later.z) * d.dLogWeightDRoughness;
  Rgb v_f0(0.0f);
  if (!settings.f0FromSpecularMetalsOnly || greyF0IsMetal(segments[k].result.f0))
    v_f0 = settings.f0FromSpecular * later * d.dLogWeightDF0;
  (settings.materialsMoveGeometry ? v.v_roughness : v.v_roughnessWeightsHeld) += v_roughness;
  (settings.materialsMoveGeometry ? v.v_f0 : v.v_f0WeightsHeld) += v_f0;
  return v;
}

// Calls f(segment, adjoint) for each segment of a recorded path that gets a gradient: its
// adjoint is not zero (e.g. a loss of the specular term alone hands the first segment
// nothing) and its hit list did not overflow. Returns how many segments with a non-zero
// adjoint overflowed.
template <typename F>
int forEachSegmentAdjoint(std::span<const PathSegment> segments, const RayResultAdjoint& v_first,
                          const Rgb& v_specular, const PathGradientSettings& settings, F&& f) {
  int overflowed = 0;
  for (size_t k = 0; k < segments.size(); ++k) {
    const RayResultAdjoint v = segmentAdjoint(segments, k, v_first, v_specular, settings);
    if (v.isZero()) continue;
    if (segments[k].hits.overflowed) {
      ++overflowed;
      continue;
    }
    f(segments[k], v);
  }
  return overflowed;
}

// The vector-Jacobian product of a recorded path (D13): v_first = dL/d(the first segment's
// result) and v_specular = dL/d(specular). The first segment's adjoint flows through its
// compositing into every attribute of the Gaussians it hits; segment k >= 1 receives
// throughput_k x v_specular on its blended diffuse (times reflectionGradientWeight when
// weighted), so the colour, opacity, position and shape of the Gaussians it hits. The
// rays and sampled directions are detached (the paper's choice), and so are the
// throughputs unless the settings' material weights say otherwise (D15): by default
// nothing flows from the specular term into normals, roughness or F0. Segments whose hit
// list overflowed get no gradient; returns how many (of those with a non-zero adjoint)
// did. T = float in training, double for the finite-difference tests.
template <typename T, typename Sink>
int tracePath_vjp(const GaussianScene& scene, const TraceSettings& trace, std::span<const PathSegment> segments,
                  const RayResultAdjoint& v_first, const Rgb& v_specular, const PathGradientSettings& settings,
                  RayBackwardScratch<T>& scratch, Sink&& sink) {
  return forEachSegmentAdjoint(segments, v_first, v_specular, settings,
                               [&](const PathSegment& segment, const RayResultAdjoint& v) {
                                 backwardRay<T>(scene, trace, segment.ray, segment.hits, segment.result, v, scratch,
                                                sink);
                               });
}

// tracePath_vjp's segments as jobs for a BackwardBatch (raytrace/backward_batch.h): each
// segment with a non-zero adjoint and a whole hit list becomes a job, its hits appended to
// `hits`. Returns how many segments overflowed, as tracePath_vjp does.
int appendBackwardJobs(std::span<const PathSegment> segments, const RayResultAdjoint& v_first, const Rgb& v_specular,
                       const PathGradientSettings& settings, std::vector<BackwardJob>* jobs,
                       std::vector<HitRecord>* hits);

}  // namespace glint
