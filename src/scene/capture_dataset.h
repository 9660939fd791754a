// Real captures as datasets (docs/capture-format.md): photographs with COLMAP or nerfstudio
// cameras, and any subset of a predictor's buffers in the paper's priors/ layout, decoded
// to the definitions of docs/data-format.md.
#pragma once

#include <filesystem>
#include <map>
#include <mutex>
#include <set>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "io/image.h"
#include "io/transfer.h"
#include "scene/buffers.h"
#include "scene/depth_alignment.h"
#include "scene/predicted_buffers.h"

namespace glint {

struct DatasetSplit;
struct DatasetView;

// How a capture's stored buffers become Glint's: capture.json at the dataset's root (every
// key optional), defaults as the paper's released layout stores its predictions.
struct CaptureDecoding {
  Transfer photoTransfer = Transfer::Srgb;         // images/*: 8/16-bit photographs ("photo_transfer")
  Transfer priorTransfer = Transfer::Filmic;       // priors/{render,diffuse,specular} when 8/16-bit ("prior_transfer")
  float clampMax = 0.0f;                           // cap on decoded radiance, 0 for none ("clamp_max")
  bool worldNormals = false;                       // "normal_space": "world" or "camera"
  CameraAxes normalAxes = CameraAxes::PaperPrior;  // "normal_axes": "opengl", "opencv" or "paper"
  enum class Depth { Distance, ZDepth, Relative, RelativeDisparity };
  Depth depth = Depth::Relative;                        // "depth": "distance", "z", "relative" or "relative_disparity"
  RoughnessKind roughness = RoughnessKind::Perceptual;  // "roughness": "perceptual" or "alpha"
  // "priors": "predicted" (a network's buffers, what the layout is for) or "exact"
  // (rendered, as `glint synth --layout capture --degrade none` writes them). Predicted
  // ones train with the real-capture setting unless a config is given (train_config.h).
  bool predictedPriors = true;
};
// capture.json's keys; throws Error naming the file and the key for an unknown key or value.
CaptureDecoding readCaptureDecoding(const std::filesystem::path& file);

// What a capture holds beside its views: the decoding, the sparse points (for the depth
// fit and the initialisation) and a description for `glint info`.
struct CaptureSource {
  CaptureDecoding decoding;
  std::vector<Vec3d> points;      // world space (the cameras' world)
  std::vector<Rgb> pointColours;  // linear, one per point
  // By a view's render file (DatasetView::files[Buffer::Render]): the indices into points of
  // those its COLMAP model's tracks say it observed. Empty for a model without tracks.
  std::unordered_map<std::string, std::vector<uint32_t>> observedPoints;
  std::string description;        // "COLMAP binary model sparse/0, 120 images, 8000 points"
  // The paper's layout for synthetic scenes with predicted buffers (transforms files and
  // SPLIT/<buffer>/<buffer>_ID.png beside a COLMAP model): its render images are priors too.
  bool priorTransforms = false;
  // The NeRF-synthetic layout (scene/nerf_synthetic.h): RGBA final images, composited over
  // this linear colour where their alpha leaves them uncovered.
  std::optional<Rgb> alphaBackground;
  // The transforms files that hold the splits, for `glint info` ("" when split by holdout).
  std::string splitFiles;

  // The per-view depth fits made while loading, for reports (thread-safe).
  void recordDepthFit(const std::string& view, const DepthFit& fit) const;
  std::map<std::string, DepthFit> depthFits() const;  // by depth file
  // One line per depth file whose alignment failed, its depth dropped (read as 0, no
  // surface): the file and why, for `glint info` and `glint train` to warn with.
  std::vector<std::string> droppedDepths() const;
  // The buffers whose files carried an alpha channel (read as coverage), for `glint info`.
  void recordAlpha(Buffer buffer) const;
  std::set<Buffer> buffersWithAlpha() const;

 private:
  mutable std::mutex fitsMutex_;
  mutable std::map<std::string, DepthFit> fits_;
  mutable std::set<Buffer> withAlpha_;
};

// A capture's F0 file that holds a predictor's metalness (priors/metalness/metalness_*).
bool isMetalnessPrior(const std::filesystem::path& path);
// Files of integer codes (PNG, JPEG), which readImage scales to [0, 1]: display-referred
// radiance and n/2 + 1/2 normals, unlike the stored values of EXR and TIFF.
bool isDisplayReferred(const std::filesystem::path& path);
// The photographs (display-referred images, isDisplayReferred) directly inside `folder`,
// sorted by name; none when it is not a folder.
std::vector<std::filesystem::path> photographsIn(const std::filesystem::path& folder);

// True when root holds a capture: a COLMAP model (sparse/0/ or sparse/) or a nerfstudio
// transforms.json, and no transforms_train.json.
bool isCaptureFolder(const std::filesystem::path& root);
// True when root holds transforms_train.json and a COLMAP model: the paper's layout for
// synthetic scenes with predicted buffers (docs/capture-format.md), whose buffers are
// decoded like a capture's priors.
bool isPriorTransformsFolder(const std::filesystem::path& root);
// For such a folder, whose splits were read from the transforms files: points each view's
// files at SPLIT/<buffer>/<buffer>_ID.{png,exr,tiff,tif,jpg} (F0 from metalness when
// there is no f0), and reads the decoding and the COLMAP model's points.
void attachPriorTransforms(const std::filesystem::path& root, DatasetSplit* train, DatasetSplit* test,
                           CaptureSource* source);

// Reads a capture's cameras and finds its files. Views are the images sorted by name; every
// holdout-th (the first, then holdout on: LLFF's convention) is a test view. Each view's
// filePath is "SPLIT/render/render_STEM" (where renders are written), and its files point
// at images/NAME (render, unless priors/render/render_STEM exists) and
// priors/<buffer>/<buffer>_STEM.{png,exr,tiff,tif,jpg} for the others (F0 from
// priors/metalness when there is no priors/f0). Throws Error naming the file for a missing
// or broken model, a missing image, a camera that is not a pinhole.
void openCapture(const std::filesystem::path& root, int holdout, DatasetSplit* train, DatasetSplit* test,
                 CaptureSource* source);

// Reads one buffer of a capture view and decodes it (transfer and clamp of radiance;
// normals decoded and turned to world space; depth aligned to the sparse points and turned
// into distance along the ray; roughness made perceptual; F0 from metalness). Checks that
// its size is the view camera's. Throws Error naming the file.
Image loadCaptureBuffer(const std::filesystem::path& root, const CaptureSource& source, const DatasetView& view,
                        Buffer buffer);

// A prior's alpha (PNG with alpha) is coverage: normal and depth pixels below this are read
// as "no surface" (0), radiance is composited over a NeRF-synthetic background, roughness
// and F0 drop it. `glint info` says which buffers had one.
constexpr float kMinPriorCoverage = 0.5f;

// A view's normal prior checked as loadCaptureBuffer checks it, decoded to unit vectors
// (0: no surface) but left in its file's own axes: what the normal-space guess tests.
Image readCameraNormalPrior(const std::filesystem::path& root, const CaptureSource& source, const DatasetView& view);

}  // namespace glint
