// Benchmark of the product's render path (renderGaussianView, what `glint render` and
// `glint eval` call per view, and the viewer per sample) with the fast tracer against the
// Embree k-buffer baseline, on the same scene, cameras and settings: the random rooms of
// 100k and 500k Gaussians that tracer_bench measures (bench/room_scene.h), seen by 4
// cameras inside the cloud and 4 outside it, primary rays only and 2-bounce paths. Prints
// a table of times and ratios, the memory of the tracers and of the render's wavefront
// buffers, and writes JSON (--json FILE).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/parallel.h"
#include "raytrace/fast/fast_tracer.h"
#include "render/gaussian_path.h"
#include "render/gaussian_renderer.h"
#include "room_scene.h"
#include "bench_timing.h"

using namespace glint;

namespace {

// 4 pinhole cameras (60 degrees): inside, at the room's centre looking along +-x and +-z;
// outside, on a circle of 9 m around the room looking at its centre (tracer_bench's
// inside and outside views, turned).
std::vector<Camera> roomCameras(bool inside, int width, int height) {
  std::vector<Camera> cameras;
  for (int v = 0; v < 4; ++v) {
    double a = 1.5707963 * v;
    Vec3d eye = inside ? Vec3d(0.0) : Vec3d(9.0 * std::sin(a), 0.5, 9.0 * std::cos(a));
    Vec3d target = inside ? Vec3d(std::sin(a), 0.0, -std::cos(a)) : Vec3d(0.0);
    cameras.push_back(Camera::fromFieldOfView(Mat4::lookAt(eye, target, {0, 1, 0}), 60.0 * 3.14159265 / 180.0, width,
                                              height));
  }
  return cameras;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"glint render's path (renderGaussianView) with the fast tracer vs the Embree k=16 baseline"};
  std::string jsonPath;
  int width = 320, height = 240, threads = 2, repeats = 1;
  const int views = 4;
  std::vector<int> counts{100000, 500000};
  app.add_option("--gaussians", counts, "Sizes of the random room")->capture_default_str();
  app.add_option("--width", width, "Image width")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--height", height, "Image height")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--repeats", repeats, "Renders of each view per measurement")->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--threads", threads, "Threads")->check(CLI::Range(1, 1024))->capture_default_str();
  app.add_option("--json", jsonPath, "Write the results as JSON here");
  CLI11_PARSE(app, argc, argv);
  ThreadLimit limit(threads);

  TraceSettings trace;  // the defaults glint render uses for a scene without a run
  std::printf("render_bench: renderGaussianView at %dx%d, 1 spp, %d views x %d repeats per measurement, %d threads\n",
              width, height, views, repeats, threads);
  std::printf("%-9s %-8s %-8s %10s %10s %10s %8s %16s %9s %10s\n", "gaussians", "cameras", "bounces", "refl/path",
              "fast s", "embree s", "ratio", "fast unsorted s", "fast MB", "embree MB");
  nlohmann::json json;
  json["width"] = width, json["height"] = height, json["views"] = views, json["threads"] = threads;
  const std::vector<Camera> inside = roomCameras(true, width, height), outside = roomCameras(false, width, height);
  for (int count : counts) {
    GaussianScene scene = makeRoom(size_t(count), 1);
    // Unit normals facing up, so that paths reflect (the room's random normals blend to
    // invalid ones and would end every path at its first segment).
    for (Vec3f& n : scene.normal) n = Vec3f(0, 1, 0);
    std::unique_ptr<GaussianTracer> fast = makeGaussianTracer("fast"), embree = makeGaussianTracer("embree-k16");
    double fastBuild = secondsOf([&] { fast->build(scene, trace); });
    double embreeBuild = secondsOf([&] { embree->build(scene, trace); });
    for (const auto& [where, cameras] : {std::pair<const char*, const std::vector<Camera>*>{"inside", &inside},
                                         {"outside", &outside}})
      for (int bounces : {0, 2}) {
        RenderSettings settings;
        settings.path.bounces = bounces;
        auto renderAll = [&](const GaussianTracer& tracer) {
          for (int r = 0; r < repeats; ++r)
            for (size_t v = 0; v < cameras->size(); ++v) renderGaussianView(tracer, (*cameras)[v], settings, v);
        };
        renderAll(*fast);  // warm-up: first-touch of the tracers' scratch
        // Reflected segments per path, from one wavefront of the first camera's rays.
        double reflectedPerPath = 0;
        {
          const Camera& c = (*cameras)[0];
          std::vector<TraceRay> primaries;
          std::vector<PathKey> keys;
          for (int y = 0; y < c.height; ++y)
            for (int x = 0; x < c.width; ++x) {
              Ray r = c.generateRay(x + 0.5, y + 0.5);
              primaries.push_back({Vec3f(r.origin), Vec3f(r.direction), 0.0f});
              keys.push_back({0, uint64_t(y) * uint64_t(c.width) + uint64_t(x), 0});
            }
          std::vector<PathResult> results(primaries.size());
          PathBatch batch;
          batch.trace(*fast, primaries, keys, 0, settings.path, results, /*record=*/false);
          for (const PathResult& r : results) reflectedPerPath += r.segments - 1;
          reflectedPerPath /= double(results.size());
        }
        double fastSeconds = secondsOf([&] { renderAll(*fast); });
        double embreeSeconds = secondsOf([&] { renderAll(*embree); });
        // The reflected rays in path order instead of sorted by origin and octant.
        double unsortedSeconds = 0;
        if (bounces > 0) {
          settings.path.reflectedOrder = ReflectedRayOrder::PathOrder;
          unsortedSeconds = secondsOf([&] { renderAll(*fast); });
          settings.path.reflectedOrder = ReflectedRayOrder::OriginAndOctant;
        }
        std::printf("%-9zu %-8s %-8d %10.2f %10.3f %10.3f %7.2fx %16.3f %9.1f %10.1f\n", scene.size(), where, bounces,
                    reflectedPerPath, fastSeconds, embreeSeconds, embreeSeconds / fastSeconds, unsortedSeconds,
                    fast->memoryBytes() / 1e6, embree->memoryBytes() / 1e6);
        json["runs"].push_back({{"gaussians", scene.size()}, {"cameras", where}, {"bounces", bounces},
                                {"reflected_segments_per_path", reflectedPerPath}, {"fast_s", fastSeconds}, {"embree_s", embreeSeconds},
                                {"ratio", embreeSeconds / fastSeconds}, {"fast_unsorted_reflections_s", unsortedSeconds},
                                {"fast_build_s", fastBuild},
                                {"embree_build_s", embreeBuild}, {"fast_tracer_bytes", fast->memoryBytes()},
                                {"embree_tracer_bytes", embree->memoryBytes()}});
      }
  }
  // The render's own buffers: one wavefront tile of paths (PathBatch) and the per-thread
  // hit buffers of the fast tracer.
  std::printf("\nmemory: wavefront tile of %zu rays %.1f MB total (shared by the threads); fast tracer hit buffers "
              "%.1f KB per thread (per-ray %zu B, bundle of %d rays %zu B)\n",
              renderTileRays(), renderTileBytes(2) / 1e6,
              FastGaussianTracer::threadScratchBytes() / 1e3, FastGaussianTracer::rayScratchBytes(),
              FastGaussianTracer::kDefaultBundleRays, FastGaussianTracer::bundleScratchBytes());
  json["render_tile_rays"] = renderTileRays();
  json["render_tile_bytes_2_bounces"] = renderTileBytes(2);
  json["fast_thread_scratch_bytes"] = FastGaussianTracer::threadScratchBytes();
  if (!jsonPath.empty()) std::ofstream(jsonPath) << json.dump(2) << "\n";
  return 0;
}
