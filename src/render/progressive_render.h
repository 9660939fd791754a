// Progressive offline rendering (`glint render --progressive`): a view's samples traced in
// passes of doubling size, with the running mean of every buffer handed out after each pass.
#pragma once

#include <functional>
#include <vector>

#include "render/gaussian_renderer.h"

namespace glint {

// Weighted running sums of a view's buffers.
class ViewAccumulator {
 public:
  ViewAccumulator(int width, int height);
  // Adds a render that averaged `samples` samples per pixel.
  void add(const ViewBuffers& render, int samples);
  int samples() const { return samples_; }
  // The mean over every sample added so far, with the normal buffer normalised: the renders
  // added should hold mean blended normals (RenderSettings::normalizeNormals false), so that
  // the result is the normal of one render of all their samples.
  ViewBuffers mean() const;

 private:
  ViewBuffers sums_;
  int samples_ = 0;
};

// Sample counts of the passes for spp samples: 1, 1, 2, 4, 8, ... so the total after pass k
// is 2^k, the last pass cut to end at spp exactly.
std::vector<int> progressivePassSizes(int spp);

// Called after each pass with the mean so far and the samples it holds.
using ProgressivePassCallback = std::function<void(const ViewBuffers& mean, int samples)>;

// Renders settings.spp samples (from settings.firstSample on) in the passes above. Pass
// samples are those of one render of settings.spp samples (RenderSettings::firstSample), so
// the result equals renderGaussianView of the same settings up to float rounding of the sums.
// Returns the final mean.
ViewBuffers renderProgressively(const GaussianTracer& tracer, const Camera& camera, const RenderSettings& settings,
                                uint64_t viewKey, const ProgressivePassCallback& onPass);

}  // namespace glint
