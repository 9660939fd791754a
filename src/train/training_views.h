// The training split held in memory as per-pixel targets, and the drawing of each step's
// batch of rays from it.
#pragma once

#include <cstdint>
#include <vector>

#include "raytrace/gaussian_tracer.h"
#include "scene/camera.h"
#include "scene/dataset.h"
#include "train/ray_loss.h"

namespace glint {

// One ray of a batch: through the centre of `pixel` (row-major) of training view `view`.
struct BatchRay {
  TraceRay ray;
  uint32_t view;
  uint32_t pixel;
};

// What the first segment's colour is fitted to: the diffuse buffer (the method), or the
// render buffer (the RGB-only baseline, which bakes reflections into the colours).
enum class ColourTarget { Diffuse, Render };

class TrainingViews {
 public:
  // Loads the diffuse, specular (when present), depth, normal, roughness and F0 buffers
  // of every view of the split, with a progress bar. Throws Error naming the file for
  // missing buffers, wrong sizes or non-finite values (Dataset::loadBuffer's checks).
  // With ColourTarget::Render, PixelTarget::diffuse holds the render buffer.
  static TrainingViews load(const Dataset& dataset, const DatasetSplit& split,
                            ColourTarget colour = ColourTarget::Diffuse);

  size_t viewCount() const { return cameras_.size(); }
  int width() const { return width_; }
  int height() const { return height_; }
  size_t pixelsPerView() const { return size_t(width_) * size_t(height_); }
  const Camera& camera(size_t view) const { return cameras_[view]; }
  const PixelTarget& target(size_t view, size_t pixel) const { return targets_[view * pixelsPerView() + pixel]; }

  // The ray through a pixel's centre (the G-buffers' convention, docs/data-format.md).
  TraceRay pixelRay(size_t view, size_t pixel) const;

  // Draws the batch of a step: `views` distinct views at random (all of them when there
  // are fewer), an equal share of `rays` in each at uniformly random pixels, sorted by
  // pixel within a view so that neighbouring rays traverse similar nodes. Depends only
  // on (seed, step).
  void drawBatch(uint64_t seed, int64_t step, int rays, int views, std::vector<BatchRay>* batch) const;

 private:
  int width_ = 0, height_ = 0;
  std::vector<Camera> cameras_;
  std::vector<PixelTarget> targets_;  // view-major, then row-major pixels
};

}  // namespace glint
