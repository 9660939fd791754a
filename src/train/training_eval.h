// The quick test-view score logged during training: diffuse PSNR on the paper's tonemapped
// 8-bit images and the mean normal error, from pixel-centre renders of the test views.
#pragma once

#include <vector>

#include "raytrace/gaussian_tracer.h"
#include "scene/buffers.h"
#include "scene/camera.h"
#include "scene/dataset.h"

namespace glint {

struct TestScore {
  double diffusePsnr = 0;     // dB, tonemapped 8-bit, mean over views
  double normalDegrees = 0;   // mean angular error, mean over views
};

class TestViews {
 public:
  // Loads the diffuse, depth and normal buffers of up to maxViews views of the split,
  // evenly spaced. Empty when the split has no buffers.
  static TestViews load(const Dataset& dataset, const DatasetSplit& split, int maxViews);
  bool empty() const { return cameras_.empty(); }
  size_t size() const { return cameras_.size(); }
  // Diffuse from spp jittered samples per pixel (the ground truth averages the pixel),
  // normals from the pixel-centre ray (like the ground truth's G-buffers).
  TestScore score(const GaussianTracer& tracer, int spp) const;

 private:
  std::vector<Camera> cameras_;
  std::vector<Image> diffuse_, depth_, normal_;
};

}  // namespace glint
