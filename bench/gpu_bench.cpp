// Benchmark of rendering on the GPU against the CPU, through renderGaussianView (the path
// `glint render`, `eval` and `view` run): a generated scene of surface Gaussians (a floor and
// three reflective spheres), one view rendered by both at the same seeds, the speed-up and
// the per-pixel difference; then a GPU-only render of --spp samples. With --write DIR it
// also writes the scene (DIR/scene.ply) and a dataset of --views cameras around it
// (DIR/dataset, cameras only), for timing `glint render` and `glint view` on the same scene
// (scripts/device-check.sh does). Prints a table and writes JSON (--json FILE).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/parallel.h"
#include "io/transforms_json.h"
#include "math/mat4.h"
#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_renderer.h"
#include "scene/camera.h"
#include "scene/gaussian_ply.h"
#include "surface_scene.h"
#include "tracers/compute_device.h"

using namespace glint;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

constexpr double kFieldOfViewX = 0.9;  // radians

// Camera v of n on a ring around the spheres, looking at them from above the floor.
Mat4 ringCamera(int v, int n) {
  const double angle = 6.283185307179586 * (double(v) + 0.25) / double(n);
  const Vec3d eye(4.2 * std::sin(angle), 1.6 + 0.4 * std::sin(3.0 * angle), 4.2 * std::cos(angle));
  return Mat4::lookAt(eye, Vec3d(0.0, 0.5, -0.2), Vec3d(0.0, 1.0, 0.0));
}

// A NeRF-synthetic camera file of the ring's cameras (no images: glint reads it without).
TransformsFile ringCameras(int views) {
  TransformsFile file;
  file.cameraAngleX = kFieldOfViewX;
  for (int v = 0; v < views; ++v) file.frames.push_back({"views/r_" + std::to_string(v), ringCamera(v, views)});
  return file;
}

struct Timed {
  ViewBuffers buffers;
  double seconds = 0;
};

Timed render(const GaussianTracer& tracer, const Camera& camera, const RenderSettings& settings) {
  auto start = Clock::now();
  Timed t{renderGaussianView(tracer, camera, settings, 0), 0};
  t.seconds = secondsSince(start);
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Measures rendering on the GPU against the CPU through renderGaussianView, on a generated scene of "
               "surface Gaussians; optionally writes that scene and a camera dataset for timing glint's commands."};
  int gaussians = 500000, width = 1024, height = 768, bounces = 4, compareSpp = 2, gpuSpp = 64, threads = 0, views = 20;
  std::string jsonPath, writeDir;
  app.add_option("--gaussians", gaussians, "Size of the generated scene")->capture_default_str();
  app.add_option("--width", width, "Image width")->check(CLI::Range(16, 8192))->capture_default_str();
  app.add_option("--height", height, "Image height")->check(CLI::Range(16, 8192))->capture_default_str();
  app.add_option("--bounces", bounces, "Reflected segments")->check(CLI::Range(0, 8))->capture_default_str();
  app.add_option("--compare-spp", compareSpp, "Samples of the view both devices render")->check(CLI::Range(1, 4096))->capture_default_str();
  app.add_option("--gpu-spp", gpuSpp, "Samples of the GPU-only render")->check(CLI::Range(1, 65536))->capture_default_str();
  app.add_option("--threads", threads, "CPU threads (0 = all)")->check(CLI::Range(0, 1024))->capture_default_str();
  app.add_option("--write", writeDir, "Also write DIR/scene.ply and DIR/dataset (--views cameras) for glint's commands");
  app.add_option("--views", views, "Cameras of the written dataset")->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--json", jsonPath, "Also write the results to this JSON file");
  CLI11_PARSE(app, argc, argv);

  ThreadLimit limit(threads);
  auto start = Clock::now();
  GaussianScene scene = makeSurfaceScene(size_t(gaussians), 1);
  std::printf("gpu_bench: generated %d surface Gaussians in %.2f s\n", gaussians, secondsSince(start));
  if (!writeDir.empty()) {
    std::filesystem::create_directories(writeDir + "/dataset");
    writeGaussianPly(writeDir + "/scene.ply", scene);
    writeTransformsJson(writeDir + "/dataset/transforms_train.json", ringCameras(views));
    writeTransformsJson(writeDir + "/dataset/transforms_test.json", ringCameras(views));
    std::printf("gpu_bench: wrote %s/scene.ply and %s/dataset (%d cameras)\n", writeDir.c_str(), writeDir.c_str(),
                views);
  }
  std::string why;
  std::optional<GpuInfo> gpuInfo = findGpu(&why);
  if (!gpuInfo) {
    std::printf("gpu_bench: no GPU: %s\n", why.c_str());
    return writeDir.empty() ? 77 : 0;
  }

  TraceSettings trace;
  const Camera camera = Camera::fromFieldOfView(ringCamera(0, views), kFieldOfViewX, width, height);
  RenderSettings settings;
  settings.spp = compareSpp;
  settings.path.bounces = bounces;

  std::unique_ptr<GaussianTracer> cpu = makeGaussianTracer("fast"), perRay = makeGaussianTracer("cuda"),
                                  warp = makeGaussianTracer("cuda-warp");
  start = Clock::now();
  cpu->build(scene, trace);
  const double cpuBuild = secondsSince(start);
  start = Clock::now();
  perRay->build(scene, trace);
  const double gpuBuild = secondsSince(start);  // the CPU's build plus the upload
  warp->build(scene, trace);
  render(*perRay, camera, settings);  // warm-up: module load, allocations
  render(*warp, camera, settings);
  // The two walks of the GPU tracer (cuda/cuda_tracer.h); the faster one goes on.
  const Timed perRayView = render(*perRay, camera, settings), warpView = render(*warp, camera, settings);
  const bool warpFaster = warpView.seconds < perRayView.seconds;
  GaussianTracer* gpu = warpFaster ? warp.get() : perRay.get();
  const Timed& onGpu = warpFaster ? warpView : perRayView;
  Timed onCpu = render(*cpu, camera, settings);
  // The same view with the reflected rays traced in path order (unsorted): what sorting
  // them by origin and octant gains.
  RenderSettings unsorted = settings;
  unsorted.path.reflectedOrder = ReflectedRayOrder::PathOrder;
  Timed onGpuUnsorted = render(*gpu, camera, unsorted);
  double sum = 0, largest = 0;
  const Image &g = onGpu.buffers[Buffer::Render], &c = onCpu.buffers[Buffer::Render];
  for (size_t i = 0; i < g.pixels.size(); ++i) {
    const double d = std::abs(double(g.pixels[i]) - double(c.pixels[i]));
    sum += d, largest = std::max(largest, d);
  }
  const double meanDifference = sum / double(g.pixels.size());
  settings.spp = gpuSpp;
  Timed many = render(*gpu, camera, settings);
  const double pathsPerSecond = double(width) * height * gpuSpp / many.seconds;

  std::printf("gpu_bench: %s; %d CPU threads; %dx%d, %d bounces, %d Gaussians\n\n", gpuInfo->name.c_str(),
              maxThreads(), width, height, bounces, gaussians);
  std::printf("%-34s %12s\n", "measure", "value");
  std::printf("%-34s %12.3f\n", "CPU BVH build (s)", cpuBuild);
  std::printf("%-34s %12.3f\n", "GPU build: CPU BVH + upload (s)", gpuBuild);
  std::printf("%-34s %12.3f\n", ("CPU view, " + std::to_string(compareSpp) + " spp (s)").c_str(), onCpu.seconds);
  std::printf("%-34s %12.3f\n", ("GPU view, " + std::to_string(compareSpp) + " spp, per-ray walk (s)").c_str(),
              perRayView.seconds);
  std::printf("%-34s %12.3f\n", ("GPU view, " + std::to_string(compareSpp) + " spp, warp walk (s)").c_str(),
              warpView.seconds);
  std::printf("%-34s %12.3f\n", "GPU view, reflected rays unsorted", onGpuUnsorted.seconds);
  std::printf("%-34s %11.1fx (%s walk)\n", "GPU speed-up, same view", onCpu.seconds / onGpu.seconds,
              warpFaster ? "warp" : "per-ray");
  std::printf("%-34s %12.3g\n", "mean |GPU - CPU| (render buffer)", meanDifference);
  std::printf("%-34s %12.3g\n", "largest |GPU - CPU|", largest);
  std::printf("%-34s %12.3f\n", ("GPU view, " + std::to_string(gpuSpp) + " spp (s)").c_str(), many.seconds);
  std::printf("%-34s %12.1f\n", "GPU paths per second (M)", pathsPerSecond * 1e-6);
  if (!jsonPath.empty()) {
    nlohmann::json json = {{"gpu", gpuInfo->name},
                           {"cpu_threads", maxThreads()},
                           {"width", width},
                           {"height", height},
                           {"bounces", bounces},
                           {"gaussians", gaussians},
                           {"cpu_build_s", cpuBuild},
                           {"gpu_build_s", gpuBuild},
                           {"compare_spp", compareSpp},
                           {"cpu_view_s", onCpu.seconds},
                           {"gpu_view_s", onGpu.seconds},
                           {"gpu_view_per_ray_s", perRayView.seconds},
                           {"gpu_view_warp_s", warpView.seconds},
                           {"faster_walk", warpFaster ? "warp" : "per-ray"},
                           {"gpu_view_unsorted_s", onGpuUnsorted.seconds},
                           {"speedup", onCpu.seconds / onGpu.seconds},
                           {"mean_abs_difference", meanDifference},
                           {"largest_abs_difference", largest},
                           {"gpu_spp", gpuSpp},
                           {"gpu_many_spp_s", many.seconds},
                           {"gpu_mpaths_per_s", pathsPerSecond * 1e-6}};
    std::ofstream(jsonPath) << json.dump(2) << "\n";
    std::printf("\nwrote %s\n", jsonPath.c_str());
  }
  return 0;
}
