// The training split held in memory as per-pixel targets, and the drawing of each step's
// batch of rays from it.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "raytrace/gaussian_tracer.h"
#include "scene/camera.h"
#include "scene/dataset.h"
#include "train/depth_consistency.h"
#include "train/packed_target.h"
#include "train/ray_loss.h"

namespace glint {

// One ray of a batch: through the centre of `pixel` (row-major) of training view `view`.
struct BatchRay {
  TraceRay ray;
  uint32_t view;
  uint32_t pixel;
};

// What the first segment's colour is fitted to: the diffuse buffer (the method), or the
// render buffer (the RGB-only baseline, which bakes reflections into the colours, and
// datasets without a diffuse/specular split, whose paths' first diffuse plus specular is
// fitted to the final image).
enum class ColourTarget { Diffuse, Render };

// Which supervision a set of training views carries beside the colour.
struct SupervisedBuffers {
  bool specular = false, depth = false, normal = false, roughness = false, f0 = false;
  bool finalColour = false;  // the colour target is the render buffer (ColourTarget::Render or no diffuse)
  // F0 is a capture's predicted metalness (priors/metalness), grey by the white-base rule,
  // and only its metals' brightness is trained (PixelTarget::f0BrightnessOnly).
  bool f0BrightnessOnly = false;
  float f0TintPrior = 0;  // PixelTarget::f0TintPrior of those metals
  // Each view's photograph (render buffer) is held beside the diffuse prior for the
  // photograph term (LossWeights::photograph; PixelTarget::hasPhotograph).
  bool photograph = false;
  // The names ("specular, depth, ...") of the buffer kinds present, or of those missing.
  std::string list(bool present) const;
};

class TrainingViews {
 public:
  // Loads the colour (diffuse, or render), specular, depth, normal, roughness and F0
  // buffers of every view of the split in parallel, with a progress bar, into 18 bytes per
  // pixel (train/packed_target.h). A buffer kind the first view lacks is left out of
  // training (supervised() says which); a dataset without diffuse buffers trains on its
  // render images as final colours. Views may differ in size. Throws Error naming the file
  // for missing buffers of a kind the first view has, sizes that differ from the view's
  // camera, or non-finite values (Dataset::loadBuffer's checks).
  // metalnessTrainsBrightness: a capture's F0 given as metalness trains its brightness only
  // (TrainConfig::f0TintFromReflections), and every channel with the share tintPrior
  // (LossWeights::f0TintPrior). photograph: hold each view's render buffer too, as
  // PixelTarget::photograph (4 more bytes per pixel), where the colour target is the diffuse
  // buffer.
  static TrainingViews load(const Dataset& dataset, const DatasetSplit& split,
                            ColourTarget colour = ColourTarget::Diffuse, bool metalnessTrainsBrightness = false,
                            float tintPrior = LossWeights{}.f0TintPrior, bool photograph = false);

  size_t viewCount() const { return cameras_.size(); }
  const Camera& camera(size_t view) const { return cameras_[view]; }
  size_t pixelCount(size_t view) const { return firstPixel_[view + 1] - firstPixel_[view]; }
  double meanPixelsPerView() const { return double(targets_.size()) / double(std::max<size_t>(1, viewCount())); }
  // A pixel's targets, decoded (pixel is row-major within the view).
  PixelTarget target(size_t view, size_t pixel) const;
  // target(view, pixel).surface without decoding the rest.
  bool surfaceAt(size_t view, size_t pixel) const { return targets_[firstPixel_[view] + pixel].depth != 0; }
  const SupervisedBuffers& supervised() const { return supervised_; }

  // Leaves out of the depth term every pixel whose depth fewer than options.minAgreeing of
  // its view's neighbours confirm (train/depth_consistency.h): a predicted depth that the
  // other views' predictions contradict, or a camera whose pose puts its depth where the
  // others' is not; target() then says hasDepth = false there. Returns what was checked
  // (depthPixels - trustedPixels are left out).
  DepthConsistency keepConsistentDepth(const DepthConsistencyOptions& options);
  // target(view, pixel).hasDepth without decoding the rest: false without depth buffers and
  // where keepConsistentDepth left the pixel out.
  bool depthTrusted(size_t view, size_t pixel) const {
    return supervised_.depth && (depthTrusted_.empty() || depthTrusted_[firstPixel_[view] + pixel] != 0);
  }
  // Replaces a view's camera (its intrinsics must stay; train/camera_refinement.h moves
  // poses). With normalsFromCamera the view's normal targets came from camera-space priors
  // turned into the world by the camera as loaded, so they turn with the camera: target()
  // then rotates them by the new rotation times the loaded one's inverse. World-space
  // normals (a surface's own) do not turn. Checked depth (keepConsistentDepth) is not
  // checked again here.
  void setCamera(size_t view, const Camera& camera, bool normalsFromCamera);
  // Whether setCamera moved any view's camera since loading.
  bool camerasMoved() const { return !loadedCameras_.empty(); }
  // Bytes held for the targets and cameras.
  size_t memoryBytes() const;

  // The ray through a pixel's centre (the G-buffers' convention, docs/data-format.md).
  TraceRay pixelRay(size_t view, size_t pixel) const;

  // Draws the batch of a step: `views` distinct views at random (all of them when there
  // are fewer), an equal share of `rays` in each at uniformly random pixels, sorted by
  // pixel within a view so that neighbouring rays traverse similar nodes. Depends only
  // on (seed, step).
  void drawBatch(uint64_t seed, int64_t step, int rays, int views, std::vector<BatchRay>* batch) const;
  // Draws the batch of a step of whole images (TrainConfig::batchImages): every pixel of
  // `images` views (all of them when there are fewer), in row-major order. The views are
  // visited epoch by epoch, each epoch in its own seeded order, so every view is trained
  // once per epoch; step s takes positions [s * images, (s + 1) * images) of that sequence
  // (a step that straddles two epochs may take one view twice). Depends only on (seed, step).
  void drawWholeImages(uint64_t seed, int64_t step, int images, std::vector<BatchRay>* batch) const;
  // The view at `position` of the sequence of epochs drawWholeImages visits.
  uint32_t epochView(uint64_t seed, int64_t position) const;

 private:
  std::vector<Camera> cameras_;
  std::vector<size_t> firstPixel_;     // view v's targets are [firstPixel_[v], firstPixel_[v + 1])
  std::vector<PackedTarget> targets_;  // view-major, then row-major pixels
  std::vector<uint32_t> photographs_;  // per target, shared-exponent RGB (empty without the photograph term)
  SupervisedBuffers supervised_;
  std::vector<uint8_t> depthTrusted_;  // per target: 0 = out of the depth term (empty: all in)
  std::vector<Camera> loadedCameras_;   // the cameras as loaded, once setCamera moved one (else empty)
  std::vector<Mat3f> normalTurn_;       // per view: how its normal targets turn (empty: none do)
};

}  // namespace glint
