// Progressive accumulation of a view's buffers: sums of single-sample renders, and the
// 8-bit-ready display image of one of them (tonemapped radiance, mapped G-buffers).
#pragma once

#include <span>
#include <vector>

#include "app/viewer/display_settings.h"
#include "io/image.h"
#include "scene/buffers.h"

namespace glint {

class FrameAccumulator {
 public:
  // Starts over; the samples to come carry the light of `bounces` reflected segments one by
  // one (at most kSeparateBounces of them are kept).
  void reset(int width, int height, int bounces = 0);
  // Adds one render of the view (all buffers, same size) and its per-bounce light
  // (renderGaussianView's bounceLight, one image per bounce given to reset).
  void add(const ViewBuffers& sample, std::span<const Image> bounceLight = {});
  int samples() const { return samples_; }
  int width() const { return sums_[Buffer::Render].width; }
  int height() const { return sums_[Buffer::Render].height; }
  // The mean of the chosen buffer as an RGB image with values in [0, 1]: radiance times
  // 2^exposure through the filmic tonemap (as 8-bit dataset images), normals as n/2 + 1/2,
  // depth as grey from near (white) to far (dark) over the frame's surfaces, roughness as
  // grey, F0 as is; a bounce mode as radiance. Zero samples, or a bounce not accumulated,
  // give a black image. With settings.denoise the final image goes through the a-trous
  // denoiser (render/denoise.h) first.
  Image display(const DisplaySettings& settings) const;
  // The mean of one buffer (linear values).
  Image mean(Buffer buffer) const;
  // The mean light of reflected segment `bounce` (1, 2, ...); black when not accumulated.
  Image meanBounce(int bounce) const;

 private:
  ViewBuffers sums_;
  std::vector<Image> bounceSums_;  // [k - 1]: the light of reflected segment k
  int samples_ = 0;
};

}  // namespace glint
