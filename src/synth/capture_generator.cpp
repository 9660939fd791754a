// Capture generation: the training path rendered view by view, priors, points from depth.
#include "synth/capture_generator.h"

#include <algorithm>
#include <cstdio>

#include "core/cluster.h"
#include "core/error.h"
#include "core/progress.h"
#include "io/transfer.h"
#include "scene/capture_writer.h"
#include "scene/view_sharing.h"
#include "synth/camera_paths.h"
#include "synth/light_sampler.h"
#include "synth/monocular_degradation.h"
#include "synth/network_degradation.h"
#include "synth/path_tracer.h"
#include "synth/ray_caster.h"

namespace glint {

namespace {

std::string viewImageName(int index) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "view_%04d.jpg", index);
  return buffer;
}

// Whether prior b gets the capture's degradation (the photograph, Render, never does).
bool degrades(const CaptureSynthSettings& capture, Buffer b) {
  const auto& only = capture.degradedPriors;
  return b != Buffer::Render && (only.empty() || std::find(only.begin(), only.end(), b) != only.end());
}

// The views in which each point is in the image and nothing of the scene lies between it
// and the camera (kSightingTolerance): what COLMAP's tracks would say had it matched the
// point in every view that shows it.
std::vector<std::vector<PointSighting>> sightingsOf(const std::vector<Vec3d>& points,
                                                    const std::vector<Camera>& cameras, const RayCaster& caster) {
  std::vector<std::vector<PointSighting>> sightings(points.size());
  for (size_t v = 0; v < cameras.size(); ++v) {
    const Camera& camera = cameras[v];
    const Mat4 worldToCamera = camera.cameraToWorld.inverse();
    const Vec3d eye = camera.position();
    for (size_t i = 0; i < points.size(); ++i) {
      Vec2d pixel;
      if (!camera.project(worldToCamera, points[i], &pixel)) continue;
      const Vec3d toPoint = points[i] - eye;
      const double distance = length(toPoint);
      // Stop short of the point, so that its own surface does not hide it.
      const double shortOf = kSightingTolerance * distance;
      if (!caster.occluded(Vec3f(eye), Vec3f(toPoint / distance), 0.0f, float(distance - shortOf)))
        sightings[i].push_back({uint32_t(v), pixel});
    }
  }
  return sightings;
}

}  // namespace

void generateCapture(const MeshScene& scene, const SynthSettings& settings, const CaptureSynthSettings& capture,
                     const std::filesystem::path& outDir) {
  GLINT_CHECK(capture.holdout >= 1, "holdout is at least 1");
  RayCaster caster(scene);
  LightSampler lights(scene);
  PathTracer tracer(scene, caster, lights, PathTracerSettings{settings.bounces, 3});
  const CameraRig rig = sceneCameraRig(scene);
  const int count = settings.trainViews;
  const std::vector<Mat4> poses = orbitCameras(rig.train, count);
  auto isTest = [&](int i) { return capture.holdout > 1 && i % capture.holdout == 0; };

  // In an MPI job the views go round-robin to the ranks (scene/view_sharing.h), and rank 0,
  // which writes the whole capture, receives them one by one in order.
  const ViewShare share(size_t(count), /*allowBands=*/false);
  const int testSpp = settings.testSamplesPerPixel();
  int64_t samples = 0;
  for (int i = 0; i < count; ++i) samples += share.mine(size_t(i)) ? (isTest(i) ? testSpp : settings.spp) : 0;
  ProgressBar progress(share.progressLabel("synth"), samples * settings.width * settings.height, "samples");

  std::vector<Camera> cameras;
  std::vector<ViewBuffers> rendered(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    cameras.push_back(Camera::fromFieldOfView(poses[size_t(i)], rig.fovX, settings.width, settings.height));
    if (!share.mine(size_t(i))) continue;
    SynthSettings viewSettings = settings;
    viewSettings.spp = isTest(i) ? testSpp : settings.spp;
    // The same random streams as the transforms layout's training view i.
    rendered[size_t(i)] = renderView(tracer, cameras.back(), viewSettings, (uint64_t(1) << 32) | uint64_t(i), &progress);
  }
  progress.finish();

  std::vector<CaptureWriteView> views;
  std::vector<DepthView> depthViews;  // training views only: test views must not inform the points
  for (int i = 0; i < count; ++i) {
    ViewBuffers exact = sendViewToRoot(rendered[size_t(i)], share.owner(size_t(i)));
    rendered[size_t(i)] = ViewBuffers();
    if (!cluster::isRoot()) continue;
    const Camera& camera = cameras[size_t(i)];
    if (!isTest(i)) depthViews.push_back({exact[Buffer::Depth], exact[Buffer::Diffuse], camera});
    ViewBuffers priors = capture.priorErrors == PriorErrors::Network     ? networkLikePriors(exact, settings.seed, uint64_t(i))
                         : capture.priorErrors == PriorErrors::Monocular ? monocularPriors(exact, settings.seed, uint64_t(i))
                                                                         : exact;
    for (Buffer b : kAllBuffers)
      if (!degrades(capture, b)) priors[b] = exact[b];
    views.push_back({viewImageName(i), camera, std::move(priors)});
  }
  if (!cluster::isRoot()) return;

  // pointCloudFromDepth colours are sRGB-encoded; writeCapture takes linear colours.
  PointCloud cloud = pointCloudFromDepth(depthViews, capture.sparsePoints);
  std::vector<Vec3d> points;
  std::vector<Rgb> colours;
  for (size_t p = 0; p < cloud.positions.size(); ++p) {
    points.push_back(Vec3d(cloud.positions[p]));
    const Rgb& c = cloud.colors[p];
    colours.push_back({toLinear(Transfer::Srgb, c.x), toLinear(Transfer::Srgb, c.y), toLinear(Transfer::Srgb, c.z)});
  }
  CaptureWriteSettings write;
  write.metalnessInsteadOfF0 = capture.priorErrors == PriorErrors::Monocular && degrades(capture, Buffer::F0);
  write.predictedPriors = capture.priorErrors != PriorErrors::None;
  writeCapture(outDir, views, points, colours, write, sightingsOf(points, cameras, caster));
}

}  // namespace glint
