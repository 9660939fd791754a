// Dataset generation: camera paths, per-view rendering in parallel, buffers and point cloud.
#include "synth/dataset_generator.h"

#include <cmath>
#include <cstdio>

#include "core/parallel.h"
#include "core/progress.h"
#include "scene/dataset.h"
#include "synth/camera_paths.h"
#include "synth/light_sampler.h"
#include "synth/ray_caster.h"

namespace glint {

namespace {

float srgbEncode(float linear) {
  linear = std::clamp(linear, 0.0f, 1.0f);
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

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

PointCloud pointCloudFromDepth(const std::vector<DepthView>& views, int maxPoints) {
  PointCloud cloud;
  int64_t surfacePixels = 0;
  for (const DepthView& v : views) {
    for (float d : v.depth.pixels) surfacePixels += hasSurface(d) ? 1 : 0;
  }
  if (surfacePixels == 0) return cloud;
  // Keep every stride-th surface pixel (in scan order across views) to respect maxPoints.
  int64_t stride = std::max<int64_t>(1, (surfacePixels + maxPoints - 1) / std::max(1, maxPoints));
  int64_t counter = 0;
  for (const DepthView& v : views) {
    const Image& depth = v.depth;
    const Image& diffuse = v.diffuse;
    for (int y = 0; y < depth.height; ++y)
      for (int x = 0; x < depth.width; ++x) {
        float d = depth.at(x, y);
        if (!hasSurface(d) || (counter++ % stride) != 0) continue;
        Ray ray = v.camera.generateRay(x + 0.5, y + 0.5);
        cloud.positions.push_back(Vec3f(ray.origin + ray.direction * double(d)));
        Rgb c = diffuse.rgb(x, y);
        cloud.colors.push_back({srgbEncode(c.x), srgbEncode(c.y), srgbEncode(c.z)});
      }
  }
  return cloud;
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

  // Progress counts path samples, so that the ETA holds when the splits' spp differ.
  const int64_t pixelsPerView = int64_t(settings.width) * settings.height;
  const int64_t samplesOfAllViews = int64_t(settings.trainViews) * settings.spp + int64_t(settings.testViews) * testSpp;
  ProgressBar progress("synth", pixelsPerView * samplesOfAllViews, "samples");
  std::vector<DepthView> depthViews;  // training views only: the point cloud must not see test views
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
      DatasetView view{frameName(plan.name, i), camera};
      ViewBuffers buffers = renderView(tracer, camera, splitSettings, (plan.key << 32) | uint64_t(i), &progress);
      writeViewBuffers(outDir, view, buffers, settings.format);
      split.views.push_back(view);
      if (plan.name == "train")
        depthViews.push_back({std::move(buffers[Buffer::Depth]), std::move(buffers[Buffer::Diffuse]), camera});
    }
    writeTransforms(outDir, split);
  }
  progress.finish();
  writePointCloud(outDir / "point_cloud_dense.ply", pointCloudFromDepth(depthViews, settings.pointCloudMaxPoints));
}

}  // namespace glint
