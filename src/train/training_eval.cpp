// Rendering views to score them, and scoring the test views during training.
#include "train/training_eval.h"

#include <cmath>

#include "eval/image_metrics.h"

namespace glint {

ViewBuffers renderScoredView(const GaussianTracer& tracer, const Camera& camera, const RenderSettings& settings,
                             uint64_t viewKey) {
  ViewBuffers rendered = renderGaussianView(tracer, camera, settings, viewKey);
  if (settings.jitter) {
    RenderSettings centre;
    centre.jitter = false;
    centre.rowBegin = settings.rowBegin;  // the same band of rows
    centre.rowEnd = settings.rowEnd;
    ViewBuffers gbuffers = renderGaussianView(tracer, camera, centre, viewKey);
    for (Buffer b : {Buffer::Depth, Buffer::Normal, Buffer::Roughness, Buffer::F0}) rendered[b] = gbuffers[b];
  }
  return rendered;
}

RenderSettings scoringSettings(int spp, const PathSettings& path, uint64_t seed) {
  RenderSettings settings;
  settings.spp = spp;
  settings.jitter = spp > 1;
  settings.seed = seed;
  settings.path = path;
  return settings;
}

TestViews TestViews::load(const Dataset& dataset, const DatasetSplit& split, int maxViews) {
  TestViews t;
  if (split.views.empty() || split.width <= 0 || maxViews <= 0) return t;
  size_t count = std::min(split.views.size(), size_t(maxViews));
  t.finalColour_ = !dataset.findBufferFile(split.views[0], Buffer::Diffuse);
  for (size_t k = 0; k < count; ++k) {
    size_t v = k * split.views.size() / count;
    auto load = [&](Buffer b) {
      return dataset.findBufferFile(split.views[v], b) ? dataset.loadBuffer(split, v, b) : Image();
    };
    t.cameras_.push_back(split.camera(v));
    t.diffuse_.push_back(dataset.loadBuffer(split, v, t.finalColour_ ? Buffer::Render : Buffer::Diffuse));
    t.depth_.push_back(load(Buffer::Depth));
    t.normal_.push_back(load(Buffer::Normal));
  }
  return t;
}

ViewBuffers TestViews::render(const GaussianTracer& tracer, size_t k, int spp, const PathSettings& path) const {
  return renderScoredView(tracer, cameras_[k], scoringSettings(spp, path), uint64_t(k));
}

TestScore TestViews::score(const GaussianTracer& tracer, int spp, const PathSettings& path) const {
  PathSettings firstSegment = path;
  if (!finalColour_) firstSegment.bounces = 0;
  TestScore s;
  for (size_t v = 0; v < cameras_.size(); ++v) {
    ViewBuffers rendered = render(tracer, v, spp, firstSegment);
    s.diffusePsnr += psnrTonemapped8Bit(rendered[finalColour_ ? Buffer::Render : Buffer::Diffuse], diffuse_[v]);
    if (normal_[v].empty()) continue;
    const Image& n = rendered[Buffer::Normal];
    double angle = normalAngleDegrees(n, normal_[v], depth_[v].empty() ? Image(n.width, n.height, 1, 1.0f) : depth_[v]);
    s.normalDegrees += std::isfinite(angle) ? angle : 0.0;
  }
  if (!cameras_.empty()) {
    s.diffusePsnr /= double(cameras_.size());
    s.normalDegrees /= double(cameras_.size());
  }
  return s;
}

}  // namespace glint
