// Capture generation: the training path rendered view by view, priors, points from depth.
#include "synth/capture_generator.h"

#include <cstdio>

#include "core/error.h"
#include "core/progress.h"
#include "io/transfer.h"
#include "scene/capture_writer.h"
#include "synth/camera_paths.h"
#include "synth/light_sampler.h"
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

  const int testSpp = settings.testSamplesPerPixel();
  int64_t samples = 0;
  for (int i = 0; i < count; ++i) samples += isTest(i) ? testSpp : settings.spp;
  ProgressBar progress("synth", samples * settings.width * settings.height, "samples");

  std::vector<CaptureWriteView> views;
  std::vector<DepthView> depthViews;  // training views only: test views must not inform the points
  for (int i = 0; i < count; ++i) {
    Camera camera = Camera::fromFieldOfView(poses[size_t(i)], rig.fovX, settings.width, settings.height);
    SynthSettings viewSettings = settings;
    viewSettings.spp = isTest(i) ? testSpp : settings.spp;
    // The same random streams as the transforms layout's training view i.
    ViewBuffers exact = renderView(tracer, camera, viewSettings, (uint64_t(1) << 32) | uint64_t(i), &progress);
    if (!isTest(i)) depthViews.push_back({exact[Buffer::Depth], exact[Buffer::Diffuse], camera});
    ViewBuffers priors = capture.networkLikePriors ? networkLikePriors(exact, settings.seed, uint64_t(i)) : exact;
    views.push_back({viewImageName(i), camera, std::move(priors)});
  }
  progress.finish();

  // pointCloudFromDepth colours are sRGB-encoded; writeCapture takes linear colours.
  PointCloud cloud = pointCloudFromDepth(depthViews, capture.sparsePoints);
  std::vector<Vec3d> points;
  std::vector<Rgb> colours;
  for (size_t p = 0; p < cloud.positions.size(); ++p) {
    points.push_back(Vec3d(cloud.positions[p]));
    const Rgb& c = cloud.colors[p];
    colours.push_back({toLinear(Transfer::Srgb, c.x), toLinear(Transfer::Srgb, c.y), toLinear(Transfer::Srgb, c.z)});
  }
  writeCapture(outDir, views, points, colours);
}

}  // namespace glint
