// Writing capture folders in the paper's priors/ layout with a COLMAP text model.
#include "scene/capture_writer.h"

#include <algorithm>
#include <cmath>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/colmap_model.h"
#include "io/image.h"
#include "io/transfer.h"
#include "scene/camera_conventions.h"
#include "scene/predicted_buffers.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

// World normals -> the paper's camera axes, stored as n/2 + 1/2 (0 stays mid-grey: no surface).
Image encodedCameraNormals(const Image& world, const Camera& camera) {
  Image normals = worldNormalsToCamera(world, CameraAxes::PaperPrior, camera.rotation());
  for (float& v : normals.pixels) v = v * 0.5f + 0.5f;
  return normals;
}

// Distance along the ray -> z-depth -> an affine map of the view's own into [0.05, 0.95];
// no surface is 0 (the loader reads 0 as "no depth").
Image relativeDepth(const Image& distance, const Camera& camera) {
  const RayIntrinsics k{camera.fx, camera.fy, camera.cx, camera.cy};
  Image z = distanceToZDepth(distance, k);
  float lo = INFINITY, hi = 0.0f;
  for (float v : z.pixels)
    if (hasSurface(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!(hi > lo)) hi = lo + 1.0f;
  for (float& v : z.pixels) v = hasSurface(v) ? 0.05f + 0.9f * (v - lo) / (hi - lo) : 0.0f;
  return z;
}

}  // namespace

void writeCapture(const fs::path& root, const std::vector<CaptureWriteView>& views, const std::vector<Vec3d>& points,
                  const std::vector<Rgb>& pointColours, const CaptureWriteSettings& settings,
                  const std::vector<std::vector<PointSighting>>& sightings) {
  GLINT_CHECK(points.size() == pointColours.size(), "one colour per point");
  GLINT_CHECK(sightings.empty() || sightings.size() == points.size(), "one list of sightings per point");
  ColmapModel model;
  model.format = ColmapFormat::Text;
  const ImageWriteOptions sixteenBits{16};
  for (size_t i = 0; i < views.size(); ++i) {
    const CaptureWriteView& v = views[i];
    ColmapView colmap = toColmap(toCaptureCamera(v.imageName, v.camera), uint32_t(i + 1), uint32_t(i + 1));
    model.cameras.push_back(colmap.camera);
    model.images.push_back(colmap.image);

    writeImage(root / "images" / v.imageName, toDisplay(Transfer::Filmic, v.buffers[Buffer::Render]));
    if (!settings.priors) continue;
    const std::string stem = fs::path(v.imageName).stem().string();
    auto prior = [&](const char* name) { return root / "priors" / name / (std::string(name) + "_" + stem + ".png"); };
    writeImage(prior("diffuse"), toDisplay(Transfer::Filmic, v.buffers[Buffer::Diffuse]));
    writeImage(prior("specular"), toDisplay(Transfer::Filmic, v.buffers[Buffer::Specular]));
    writeImage(prior("normal"), encodedCameraNormals(v.buffers[Buffer::Normal], v.camera));
    if (settings.relativeDepth)
      writeImage(prior("depth"), relativeDepth(v.buffers[Buffer::Depth], v.camera), sixteenBits);
    else  // metric distance along the ray, as float
      writeImage(root / "priors" / "depth" / ("depth_" + stem + ".exr"), v.buffers[Buffer::Depth]);
    writeImage(prior("roughness"), v.buffers[Buffer::Roughness], sixteenBits);
    if (settings.metalnessInsteadOfF0)
      writeImage(prior("metalness"), metalnessFromF0(v.buffers[Buffer::F0]), sixteenBits);
    else
      writeImage(prior("f0"), v.buffers[Buffer::F0]);
  }
  for (size_t i = 0; i < points.size(); ++i) {
    ColmapPoint p;
    p.id = i + 1;
    p.xyz = points[i];
    const Rgb& c = pointColours[i];
    for (int k = 0; k < 3; ++k)
      p.rgb[size_t(k)] = uint8_t(std::lround(std::clamp(toDisplay(Transfer::Srgb, c[k]), 0.0f, 1.0f) * 255.0f));
    p.error = 0.5;
    if (!sightings.empty())
      for (const PointSighting& seen : sightings[i]) {
        GLINT_CHECK(seen.view < views.size(), "a sighting names a view that is written");
        ColmapImage& image = model.images[seen.view];
        p.track.push_back({image.id, uint32_t(image.points2D.size())});
        image.points2D.push_back({seen.pixel, p.id});
      }
    model.points.push_back(p);
  }
  fs::create_directories(root / "sparse" / "0");
  writeColmapModelText(root / "sparse" / "0", model);
  writeTextAtomically(root / "capture.json",
                      std::string("{\n  \"photo_transfer\": \"filmic\",\n  \"prior_transfer\": \"filmic\",\n") +
                          "  \"normal_space\": \"camera\",\n  \"normal_axes\": \"paper\",\n  \"depth\": \"" +
                          (settings.relativeDepth ? "relative" : "distance") + "\",\n  \"priors\": \"" +
                          (settings.predictedPriors ? "predicted" : "exact") + "\"\n}\n");
}

}  // namespace glint
