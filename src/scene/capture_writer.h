// Writing a capture folder (docs/capture-format.md) from exact buffers: photographs, the
// paper's priors/ encodings and a COLMAP text model, so that `glint synth` can make real-
// capture-like datasets with known answers and the tests can round-trip the loader.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scene/buffers.h"
#include "scene/camera.h"

namespace glint {

struct CaptureWriteView {
  std::string imageName;  // "view_0007.jpg": the photograph's file name under images/
  Camera camera;
  ViewBuffers buffers;  // linear values, docs/data-format.md
};

struct CaptureWriteSettings {
  bool jpegPhotos = true;  // images/ as JPEG (else 8-bit PNG), filmic-tonemapped like Glint's 8-bit images
  bool priors = true;      // write priors/{diffuse,specular,normal,depth,roughness,f0}
  // Relative depth as a predictor gives it: z-depth mapped to [0.05, 0.95] by an affine
  // map of the view's own (so only a per-view fit to the sparse points recovers metres).
  bool relativeDepth = true;
  // priors/metalness (metalnessFromF0) instead of priors/f0, as predictors that give
  // metalness write; the loader then reads F0 as grey (f0FromMetalness).
  bool metalnessInsteadOfF0 = false;
  // capture.json's "priors": "predicted" for degraded buffers, "exact" for rendered ones.
  bool predictedPriors = false;
};

// One view's sighting of a sparse point: the view (an index into the views written) and
// where the point lands in it, in pixels (Camera::project's: the top-left corner is (0, 0),
// as in COLMAP).
struct PointSighting {
  uint32_t view = 0;
  Vec2d pixel;
};

// Writes images/, priors/ (paper encodings: 8-bit filmic radiance, 8-bit normals in the
// paper's camera axes, 16-bit depth, roughness, 8-bit linear F0), sparse/0/ (COLMAP text:
// PINHOLE cameras, the poses, the points with their colours) and capture.json naming the
// encodings. sightings, when given, holds one list per point: the model's tracks and each
// image's 2D points, as COLMAP writes the observations it triangulated from. Every file is
// written atomically. Throws Error naming the file.
void writeCapture(const std::filesystem::path& root, const std::vector<CaptureWriteView>& views,
                  const std::vector<Vec3d>& points, const std::vector<Rgb>& pointColours,
                  const CaptureWriteSettings& settings = {},
                  const std::vector<std::vector<PointSighting>>& sightings = {});

}  // namespace glint
