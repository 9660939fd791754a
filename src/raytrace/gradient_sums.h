// The GPU's backward batch written for both devices (cuda/cuda_backward.cu runs it, the CPU
// emulates it): a job's run through backwardHits, per-Gaussian gradient sums in one flat
// float array (the layout, adding one hit's gradient, the reproducible sum of hit records
// sorted by Gaussian) and the copy into GaussianGradients. So the CPU suite tests what the
// GPU runs.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/cpu_gpu.h"
#include "raytrace/backward_batch.h"
#include "raytrace/gaussian_gradients.h"
#include "raytrace/ray_backward.h"
#include "scene/gaussians.h"

namespace glint {

// Floats per Gaussian: position 3, rotation 4, log-scale 3, opacity 1, diffuse 3, normal 3,
// roughness 1, F0 3, the blend weight and the split score.
constexpr size_t kSumFloatsPerGaussian = 3 + 4 + 3 + 1 + 3 + 3 + 1 + 3 + 1 + 1;

// The sums of n Gaussians in an array of kSumFloatsPerGaussian x n floats, one block per
// parameter in GaussianGradients' layout (Gaussian i's components at [i * components,
// (i + 1) * components), a quaternion's as w, x, y, z), then the weights and the scores.
struct GradientSums {
  float *position, *rotation, *logScale, *opacityLogit, *diffuse, *normal, *roughness, *f0, *weight, *score;
  const float* sigmaMax;  // each Gaussian's largest standard deviation; null: no scores

  static GradientSums in(float* base, size_t n, const float* sigmaMax) {
    GradientSums s;
    auto next = [&](size_t components) {
      float* p = base;
      base += components * n;
      return p;
    };
    s.position = next(3);
    s.rotation = next(4);
    s.logScale = next(3);
    s.opacityLogit = next(1);
    s.diffuse = next(3);
    s.normal = next(3);
    s.roughness = next(1);
    s.f0 = next(3);
    s.weight = next(1);
    s.score = next(1);
    s.sigmaMax = sigmaMax;
    return s;
  }
};

// Calls add(address, value) for every float of one hit's gradient, and its split score when
// the sums keep scores.
template <typename Add>
GLINT_CPU_GPU void forEachSum(const GradientSums& s, uint32_t id, const HitGradient<float>& g, float score, Add add) {
  const Vec3f* vectors[5] = {&g.v_position, &g.v_logScale, &g.v_diffuse, &g.v_normal, &g.v_f0};
  float* arrays[5] = {s.position, s.logScale, s.diffuse, s.normal, s.f0};
  GLINT_UNROLL
  for (int a = 0; a < 5; ++a) {
    add(arrays[a] + 3 * size_t(id) + 0, vectors[a]->x);
    add(arrays[a] + 3 * size_t(id) + 1, vectors[a]->y);
    add(arrays[a] + 3 * size_t(id) + 2, vectors[a]->z);
  }
  add(s.rotation + 4 * size_t(id) + 0, g.v_rotation.w);
  add(s.rotation + 4 * size_t(id) + 1, g.v_rotation.x);
  add(s.rotation + 4 * size_t(id) + 2, g.v_rotation.y);
  add(s.rotation + 4 * size_t(id) + 3, g.v_rotation.z);
  add(s.opacityLogit + id, g.v_opacityLogit);
  add(s.roughness + id, g.v_roughness);
  add(s.weight + id, g.weight);
  if (s.sigmaMax) add(s.score + id, score);
}

// The split score of a hit, or 0 when the sums keep none.
GLINT_CPU_GPU inline float hitScore(const GradientSums& s, uint32_t id, const HitGradient<float>& g) {
  return s.sigmaMax ? splitScore(g, s.sigmaMax[id]) : 0.0f;
}

// Records each hit's gradient and Gaussian at the job's next record: a job's k-th gradient
// goes to record firstHit + k (its hits' places in the batch).
struct RecordSink {
  HitGradient<float>* records;
  uint32_t* ids;
  uint32_t next;
  GLINT_CPU_GPU void operator()(uint32_t id, const HitGradient<float>& g) {
    records[next] = g;
    ids[next] = id;
    ++next;
  }
};

// Scratch of a batch's jobs: job j's transmittances at [firstHit + j, firstHit + j + hitCount
// + 1), its alphas and keys at [firstHit, firstHit + hitCount); so hitCount + jobs floats of
// transmittance and hitCount of each other.
struct JobScratch {
  float *transmittance, *alpha, *key;
};

// Job j of a batch through backwardHits, its gradients to `sink`: the body of the GPU's
// kernel (one thread per job), and of the CPU's emulation of it.
template <typename Sink>
GLINT_CPU_GPU void runBackwardJob(const BackwardScene& scene, const TraceSettings& settings, const BackwardJob& job,
                                  uint32_t j, const HitRecord* hits, const JobScratch& scratch, Sink& sink) {
  backwardHits<float>(scene, settings, job.ray, hits + job.firstHit, job.hitCount, job.truncated, job.transmittance,
                      job.v, scratch.transmittance + job.firstHit + j, scratch.alpha + job.firstHit,
                      scratch.key + job.firstHit, sink);
}

// With the records sorted by Gaussian, stably (sortedIds[r] the Gaussian of the r-th, and
// sortedRecord[r] its record): position r starts a run when its Gaussian differs from the
// one before, and then sums its run in order into the Gaussian's sums (one caller per run,
// so plain adds). Positions inside a run do nothing. The same bits on every run.
GLINT_CPU_GPU inline void sumSortedRun(const uint32_t* sortedIds, const uint32_t* sortedRecord,
                                       const HitGradient<float>* records, uint32_t count, uint32_t r,
                                       const GradientSums& sums) {
  const uint32_t id = sortedIds[r];
  if (r > 0 && sortedIds[r - 1] == id) return;
  HitGradient<float> total;
  float score = 0;
  for (uint32_t k = r; k < count && sortedIds[k] == id; ++k) {
    const HitGradient<float>& g = records[sortedRecord[k]];
    total.v_position += g.v_position;
    total.v_rotation = {total.v_rotation.w + g.v_rotation.w, total.v_rotation.x + g.v_rotation.x,
                        total.v_rotation.y + g.v_rotation.y, total.v_rotation.z + g.v_rotation.z};
    total.v_logScale += g.v_logScale;
    total.v_opacityLogit += g.v_opacityLogit;
    total.v_diffuse += g.v_diffuse;
    total.v_normal += g.v_normal;
    total.v_roughness += g.v_roughness;
    total.v_f0 += g.v_f0;
    total.weight += g.weight;
    score += hitScore(sums, id, g);
  }
  forEachSum(sums, id, total, score, [](float* at, float value) { *at += value; });
}

// The sums of n Gaussians (host memory, GradientSums' layout) into `gradient` (resized) and,
// when given, `splitScore` (resized; zeros when the sums kept no scores).
inline void copySums(const std::vector<float>& sums, size_t n, bool scored, GaussianGradients* gradient,
                     std::vector<float>* splitScore) {
  gradient->reset(n);
  size_t offset = 0;
  auto take = [&](std::span<float> to) {
    std::copy(sums.begin() + ptrdiff_t(offset), sums.begin() + ptrdiff_t(offset + to.size()), to.begin());
    offset += to.size();
  };
  // The order of GradientSums::in.
  take(gradient->of(&GaussianScene::position));
  take(gradient->of(&GaussianScene::rotation));
  take(gradient->of(&GaussianScene::logScale));
  take(gradient->of(&GaussianScene::opacityLogit));
  take(gradient->of(&GaussianScene::diffuse));
  take(gradient->of(&GaussianScene::normal));
  take(gradient->of(&GaussianScene::roughness));
  take(gradient->of(&GaussianScene::f0));
  take(gradient->weight);
  if (!splitScore) return;
  splitScore->assign(n, 0.0f);
  if (scored) take(*splitScore);
}

}  // namespace glint
