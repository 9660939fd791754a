// Rendering and scoring the test views during training.
#include "train/training_eval.h"

#include <cmath>

#include "eval/image_metrics.h"
#include "render/gaussian_renderer.h"

namespace glint {

TestViews TestViews::load(const Dataset& dataset, const DatasetSplit& split, int maxViews) {
  TestViews t;
  if (split.views.empty() || split.width <= 0 || maxViews <= 0) return t;
  size_t count = std::min(split.views.size(), size_t(maxViews));
  for (size_t k = 0; k < count; ++k) {
    size_t v = k * split.views.size() / count;
    t.cameras_.push_back(split.camera(v));
    t.diffuse_.push_back(dataset.loadBuffer(split, v, Buffer::Diffuse));
    t.depth_.push_back(dataset.loadBuffer(split, v, Buffer::Depth));
    t.normal_.push_back(dataset.loadBuffer(split, v, Buffer::Normal));
  }
  return t;
}

TestScore TestViews::score(const GaussianTracer& tracer, int spp) const {
  TestScore s;
  RenderSettings pixel, centre;
  pixel.spp = spp;
  pixel.jitter = spp > 1;
  centre.jitter = false;
  for (size_t v = 0; v < cameras_.size(); ++v) {
    ViewBuffers rendered = renderGaussianView(tracer, cameras_[v], pixel, uint64_t(v));
    s.diffusePsnr += psnrTonemapped8Bit(rendered[Buffer::Diffuse], diffuse_[v]);
    if (pixel.jitter) rendered = renderGaussianView(tracer, cameras_[v], centre, uint64_t(v));
    double angle = normalAngleDegrees(rendered[Buffer::Normal], normal_[v], depth_[v]);
    s.normalDegrees += std::isfinite(angle) ? angle : 0.0;
  }
  if (!cameras_.empty()) {
    s.diffusePsnr /= double(cameras_.size());
    s.normalDegrees /= double(cameras_.size());
  }
  return s;
}

}  // namespace glint
