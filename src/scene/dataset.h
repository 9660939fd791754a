// Reading, writing and validating scene datasets in the layout of docs/data-format.md:
// transforms_{train,test}.json, {split}/{buffer}/{buffer}_####.{exr,tiff,png}, and the
// optional point_cloud_dense.ply; the NeRF-synthetic layout; and real captures
// (docs/capture-format.md).
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/image.h"
#include "math/mat4.h"
#include "scene/buffers.h"
#include "scene/camera.h"
#include "scene/capture_dataset.h"
#include "scene/nerf_synthetic.h"

namespace glint {

// One view: a frame of transforms_*.json.
struct DatasetView {
  std::string filePath;  // render image path relative to the root, without extension
  // Pose (OpenGL camera axes), image size and intrinsics. A split opened without buffers
  // whose images do not exist has no size: its cameras are 1x1 pixel with the right field
  // of view, to be Camera::resized() to the size the caller renders at.
  Camera camera;
  // Captures only: each buffer's file relative to the root, "" when the view has none. The
  // transforms layout finds its files by name from filePath instead.
  std::array<std::string, kBufferCount> files;
};

// The cameras of one split.
struct DatasetSplit {
  std::string name;  // "train" or "test"
  int width = 0;     // image size, taken from the first view's render buffer
  int height = 0;    // (0 when no buffers exist, e.g. camera-only splits)
  std::vector<DatasetView> views;  // ordered by filePath

  const Camera& camera(size_t index) const;  // camera of a view at its own resolution
};

struct DatasetReading;

// A dataset folder opened for reading. Opening reads the transforms files and the size
// of the first render image; buffers are read on demand.
class Dataset {
 public:
  // The every-N-th image of a capture that is a test view (LLFF's hold-out), when the
  // dataset has no split of its own.
  static constexpr int kDefaultHoldout = 8;

  // Opens the transforms layout (transforms_train.json and transforms_test.json, or one
  // of them: the other split is then empty), the NeRF-synthetic layout
  // (isNerfSyntheticFolder) or a capture (isCaptureFolder: a COLMAP model or a nerfstudio
  // transforms.json, split by holdout). Throws Error naming the file for a missing or
  // malformed camera file. When requireBuffers is false, the transforms layouts' images
  // need not exist (width/height stay 0).
  static Dataset open(const std::filesystem::path& root, bool requireBuffers = true, int holdout = kDefaultHoldout);
  static Dataset open(const std::filesystem::path& root, const DatasetReading& reading);

  const std::filesystem::path& root() const { return root_; }
  // Throws Error for an unknown split, and for one the dataset lacks (naming its file).
  const DatasetSplit& split(const std::string& name) const;
  const DatasetSplit& train() const { return train_; }  // empty when the dataset has no train split
  const DatasetSplit& test() const { return test_; }    // empty when the dataset has no test split

  // Path of a buffer's file for a view: tries .exr, then .tiff, then .png. Returns
  // nullopt when none exists.
  std::optional<std::filesystem::path> findBufferFile(const DatasetView& view, Buffer buffer) const;

  // Reads and decodes one buffer of a view to linear values (inverse tonemap for 8-bit
  // radiance, n*2-1 for 8-bit normals), downscaled when the dataset was opened so. Checks
  // size, channels and finiteness; throws Error naming the file.
  Image loadBuffer(const DatasetSplit& split, size_t index, Buffer buffer) const;
  ViewBuffers loadView(const DatasetSplit& split, size_t index) const;

  // point_cloud_dense.ply, if present.
  std::optional<std::filesystem::path> pointCloudPath() const;
  // A capture's sparse points, decoding and depth fits (and the NeRF-synthetic layout's
  // background); null for the paper's transforms layout.
  const CaptureSource* capture() const { return capture_.get(); }
  // The --downscale factor the views were opened at (1: full resolution).
  int downscale() const { return downscale_; }

 private:
  // The layout's splits at full resolution.
  void openLayout(const DatasetReading& reading);
  // Shrinks every camera of a split by downscale_, keeping the full-resolution ones for loading.
  void downscaleSplits();
  Image loadFullResolution(const DatasetSplit& split, size_t index, Buffer buffer) const;

  std::filesystem::path root_;
  std::shared_ptr<const CaptureSource> capture_;
  DatasetSplit train_;
  DatasetSplit test_;
  int downscale_ = 1;
  DatasetSplit fullTrain_, fullTest_;  // the splits at full resolution, when downscale_ > 1
};

// How a dataset is read: besides requireBuffers, the settings a training run keeps in its
// config.json, so that eval, render and report read the dataset as training did.
struct DatasetReading {
  // false: the transforms layouts' images need not exist (cameras only; no size).
  bool requireBuffers = true;
  int holdout = Dataset::kDefaultHoldout;  // a capture's every N-th image is a test view
  // Behind the NeRF-synthetic layout's transparent pixels.
  AlphaBackground background = AlphaBackground::White;
  // Every view at 1/N resolution (scene/downscale.h), in [1, kMaxDownscale].
  int downscale = 1;
};

// A problem found by validation: the file it concerns and what is wrong.
struct DatasetProblem {
  std::string file;
  std::string message;
};

// Checks a whole dataset: transforms files parse (one of train and test may be absent),
// every frame's seven buffers exist with one size and the right channel count, values
// are finite, normals are unit length (within 0.1) where depth says there is a surface,
// roughness and f0 lie in [0,1].
// Returns every problem found (empty when clean); never throws for bad data.
std::vector<DatasetProblem> validateDataset(const std::filesystem::path& root);

// Writers used by `glint synth` and tests.
// Writes transforms_{split}.json atomically (frames in the given order). The layout stores one
// horizontal field of view per split, so every view's camera must have square pixels, the
// principal point at the centre and the first view's field of view (GLINT_CHECK).
void writeTransforms(const std::filesystem::path& root, const DatasetSplit& split);
// Writes the seven buffers of a view (linear values) in the given format: EXR and TIFF
// store linear values; PNG stores radiance tonemapped, normals as n/2+0.5, roughness and
// f0 as-is, and depth always as EXR (depth is never 8-bit).
void writeViewBuffers(const std::filesystem::path& root, const DatasetView& view, const ViewBuffers& buffers,
                      ImageFormat format);

// True when a frame's file_path names a render image the way docs/data-format.md lays them out
// (".../render/render<suffix>"), so that the other buffers can be found by name.
bool isRenderFilePath(const std::string& filePath);
// Relative path of a buffer for a view: "train/render/render_0007" -> "train/depth/depth_0007".
// Throws Error naming the path when !isRenderFilePath(renderFilePath).
std::string bufferFilePath(const std::string& renderFilePath, Buffer buffer);

}  // namespace glint
