// Dataset generation: camera paths, per-view rendering in parallel, buffers and point cloud.
#include "synth/dataset_generator.h"

#include <cmath>
#include <cstdio>

#include "core/cluster.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "scene/dataset.h"
#include "scene/view_sharing.h"
#include "synth/camera_paths.h"
#include "synth/light_sampler.h"
#include "synth/ray_caster.h"

namespace glint {

namespace {

std::string frameName(const std::string& split, int index) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%s/render/render_%04d", split.c_str(), index);
  return buffer;
}

}  // namespace

ViewBuffers renderView(const PathTracer& tracer, const Camera& camera, const SynthSettings& settings, uint64_t viewKey,
                       ProgressBar* progress) {
  const int spp = settings.spp;
  const int width = camera.width, height = camera.height;
  ViewBuffers out = ViewBuffers::allocate(width, height);
  const float invSpp = 1.0f / float(spp);
  parallelForChunks(height, 1, [&](int64_t rowBegin, int64_t rowEnd) {
    for (int64_t y = rowBegin; y < rowEnd; ++y) {
      for (int x = 0; x < width; ++x) {
        Rng rng = Rng::forKeys({settings.seed, viewKey, uint64_t(y) * width + x});
        Rgb diffuse(0.0f), specular(0.0f);
        for (int s = 0; s < spp; ++s) {
          Vec2f jitter = rng.uniform2();
          Ray ray = camera.generateRay(x + jitter.x, y + jitter.y);
          RadianceSample sample = tracer.trace(Vec3f(ray.origin), Vec3f(ray.direction), rng);
          // A NaN or infinite sample would poison the pixel; such a sample is a bug, but
          // the dataset must stay finite, so it is dropped (counted as black).
          if (isFinite(sample.diffuse)) diffuse += sample.diffuse;
          if (isFinite(sample.specular)) specular += sample.specular;
        }
        diffuse *= invSpp * settings.exposure;
        specular *= invSpp * settings.exposure;
        out[Buffer::Diffuse].setRgb(x, int(y), diffuse);
        out[Buffer::Specular].setRgb(x, int(y), specular);
        out[Buffer::Render].setRgb(x, int(y), diffuse + specular);

        Ray centre = camera.generateRay(x + 0.5, y + 0.5);
        FirstHit first = tracer.firstHit(Vec3f(centre.origin), Vec3f(centre.direction));
        out[Buffer::Depth].at(x, int(y)) = first.depth;
        out[Buffer::Normal].setRgb(x, int(y), first.normal);
        out[Buffer::Roughness].at(x, int(y)) = first.roughness;
        out[Buffer::F0].setRgb(x, int(y), first.F0);
      }
      if (progress) progress->advance(int64_t(width) * spp);
    }
  });
  return out;
}

void generateDataset(const MeshScene& scene, const SynthSettings& settings, const std::filesystem::path& outDir) {
  RayCaster caster(scene);
  LightSampler lights(scene);
  PathTracer tracer(scene, caster, lights, PathTracerSettings{settings.bounces, 3});

  CameraRig rig = sceneCameraRig(scene);

  struct SplitPlan {
    std::string name;
    int count;
    const OrbitPath* path;
    uint64_t key;
    int spp;
  };
  const int testSpp = settings.testSamplesPerPixel();
  const SplitPlan plans[] = {{"train", settings.trainViews, &rig.train, 1, settings.spp},
                             {"test", settings.testViews, &rig.test, 2, testSpp}};

  // View i of the training split is view i of the job's list, test view i is view
  // trainViews + i; whole views only, since a dataset has more views than a job has ranks.
  const ViewShare share(size_t(settings.trainViews) + size_t(settings.testViews), /*allowBands=*/false);
  auto listIndex = [&](const SplitPlan& plan, int i) {
    return size_t(i) + (plan.key == 1 ? 0 : size_t(settings.trainViews));
  };
  // Rank 0 makes the folders of every buffer before any rank writes into them.
  if (cluster::isRoot())
    for (const SplitPlan& plan : plans)
      for (Buffer b : kAllBuffers)
        std::filesystem::create_directories((outDir / bufferFilePath(frameName(plan.name, 0), b)).parent_path());
  cluster::barrier();

  // Progress counts path samples, so that the ETA holds when the splits' spp differ.
  const int64_t pixelsPerView = int64_t(settings.width) * settings.height;
  int64_t mySamples = 0;
  for (const SplitPlan& plan : plans)
    for (int i = 0; i < plan.count; ++i) mySamples += share.mine(listIndex(plan, i)) ? plan.spp : 0;
  ProgressBar progress(share.progressLabel("synth"), pixelsPerView * mySamples, "samples");
  std::vector<DepthView> depthViews;  // training views only: the point cloud must not see test views
  std::vector<size_t> depthViewIndex;
  std::vector<DatasetSplit> splits;
  for (const SplitPlan& plan : plans) {
    DatasetSplit split;
    split.name = plan.name;
    split.width = settings.width;
    split.height = settings.height;
    SynthSettings splitSettings = settings;
    splitSettings.spp = plan.spp;
    std::vector<Mat4> poses = orbitCameras(*plan.path, plan.count);
    for (int i = 0; i < plan.count; ++i) {
      Camera camera = Camera::fromFieldOfView(poses[i], rig.fovX, settings.width, settings.height);
      DatasetView view;
      view.filePath = frameName(plan.name, i);
      view.camera = camera;
      split.views.push_back(view);
      if (!share.mine(listIndex(plan, i))) continue;
      ViewBuffers buffers = renderView(tracer, camera, splitSettings, (plan.key << 32) | uint64_t(i), &progress);
      writeViewBuffers(outDir, view, buffers, settings.format);
      if (plan.name == "train") {
        depthViews.push_back({std::move(buffers[Buffer::Depth]), std::move(buffers[Buffer::Diffuse]), camera});
        depthViewIndex.push_back(size_t(i));
      }
    }
    splits.push_back(std::move(split));
  }
  progress.finish();
  PointCloud cloud = pointCloudFromDepthOverRanks(depthViews, depthViewIndex, size_t(settings.trainViews),
                                                  settings.pointCloudMaxPoints);
  if (!cluster::isRoot()) return;
  for (const DatasetSplit& split : splits) writeTransforms(outDir, split);
  writePointCloud(outDir / "point_cloud_dense.ply", cloud);
}

}  // namespace glint
