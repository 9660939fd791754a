// How a trained scene is rendered to be scored against a dataset (training's quick test-view
// score and `glint eval`), and that quick score: diffuse PSNR on the paper's tonemapped
// 8-bit images and the mean normal error.
#pragma once

#include <vector>

#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_renderer.h"
#include "scene/buffers.h"
#include "scene/camera.h"
#include "scene/dataset.h"

namespace glint {

// A dataset's radiance buffers average the whole pixel and its G-buffers come from the
// pixel-centre ray (docs/data-format.md). So the radiance passes are rendered with
// `settings` (jittered samples when settings.jitter) and, when jittered, the G-buffers
// (depth, normal, roughness, F0) again from one pixel-centre ray.
ViewBuffers renderScoredView(const GaussianTracer& tracer, const Camera& camera, const RenderSettings& settings,
                             uint64_t viewKey);

// The render settings of scoring: spp samples per pixel, jittered when more than one (with
// one, through the centre only, which aliases edges), along paths of `path`.
RenderSettings scoringSettings(int spp, const PathSettings& path, uint64_t seed = 0);

struct TestScore {
  double diffusePsnr = 0;     // dB, tonemapped 8-bit, mean over views
  double normalDegrees = 0;   // mean angular error, mean over views
};

class TestViews {
 public:
  // Loads the diffuse, depth and normal buffers of up to maxViews views of the split,
  // evenly spaced. Empty when the split has no buffers. A capture without diffuse buffers
  // is scored on its final images (the photographs); without normals, on colour alone.
  static TestViews load(const Dataset& dataset, const DatasetSplit& split, int maxViews);
  bool empty() const { return cameras_.empty(); }
  size_t size() const { return cameras_.size(); }
  const Camera& camera(size_t k) const { return cameras_[k]; }
  // The buffers of test view k as training renders them (renderScoredView with
  // scoringSettings(spp, path)); `path` is the run's (TrainConfig::path()).
  ViewBuffers render(const GaussianTracer& tracer, size_t k, int spp, const PathSettings& path) const;
  // Diffuse PSNR and normal error of render(). They come from the first segment alone, so
  // the reflected segments of `path` are not traced: they would triple the cost for nothing
  // (unless the colour scored is the final image, which needs them).
  TestScore score(const GaussianTracer& tracer, int spp, const PathSettings& path = {}) const;

 private:
  std::vector<Camera> cameras_;
  std::vector<Image> diffuse_, depth_, normal_;  // depth_ and normal_ may be empty images
  bool finalColour_ = false;                      // diffuse_ holds the render buffer
};

}  // namespace glint
