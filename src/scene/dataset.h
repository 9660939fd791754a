// Reading, writing and validating scene datasets in the layout of docs/data-format.md:
// transforms_{train,test}.json, {split}/{buffer}/{buffer}_####.{exr,tiff,png}, and the
// optional point_cloud_dense.ply.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/image.h"
#include "math/mat4.h"
#include "scene/buffers.h"
#include "scene/camera.h"

namespace glint {

// One frame of transforms_*.json.
struct DatasetView {
  std::string filePath;  // render image path relative to the root, without extension
  Mat4 cameraToWorld;    // OpenGL camera axes
};

// The cameras of one split.
struct DatasetSplit {
  std::string name;       // "train" or "test"
  double cameraAngleX = 0;  // horizontal field of view, radians
  int width = 0;          // image size, taken from the first view's render buffer
  int height = 0;         // (0 when no buffers exist, e.g. camera-only splits)
  std::vector<DatasetView> views;  // ordered by filePath

  Camera camera(size_t index) const;  // camera of a view at the split's resolution
};

// A dataset folder opened for reading. Opening reads both transforms files and the size
// of the first render image; buffers are read on demand.
class Dataset {
 public:
  // Throws Error naming the file for a missing or malformed transforms file. When
  // requireBuffers is false, the splits' images need not exist (width/height stay 0).
  static Dataset open(const std::filesystem::path& root, bool requireBuffers = true);

  const std::filesystem::path& root() const { return root_; }
  const DatasetSplit& split(const std::string& name) const;  // throws Error for an unknown split
  const DatasetSplit& train() const { return train_; }
  const DatasetSplit& test() const { return test_; }

  // Path of a buffer's file for a view: tries .exr, then .tiff, then .png. Returns
  // nullopt when none exists.
  std::optional<std::filesystem::path> findBufferFile(const DatasetView& view, Buffer buffer) const;

  // Reads and decodes one buffer of a view to linear values (inverse tonemap for 8-bit
  // radiance, n*2-1 for 8-bit normals). Checks size, channels and finiteness; throws
  // Error naming the file.
  Image loadBuffer(const DatasetSplit& split, size_t index, Buffer buffer) const;
  ViewBuffers loadView(const DatasetSplit& split, size_t index) const;

  // point_cloud_dense.ply, if present.
  std::optional<std::filesystem::path> pointCloudPath() const;

 private:
  std::filesystem::path root_;
  DatasetSplit train_;
  DatasetSplit test_;
};

// A problem found by validation: the file it concerns and what is wrong.
struct DatasetProblem {
  std::string file;
  std::string message;
};

// Checks a whole dataset: transforms files parse, every frame's seven buffers exist with
// one size and the right channel count, values are finite, normals are unit length
// (within 0.1) where depth says there is a surface, roughness and f0 lie in [0,1].
// Returns every problem found (empty when clean); never throws for bad data.
std::vector<DatasetProblem> validateDataset(const std::filesystem::path& root);

// Writers used by `glint synth` and tests.
// Writes transforms_{split}.json atomically (frames in the given order).
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
