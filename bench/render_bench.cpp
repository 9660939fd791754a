// Benchmark of the product's render path (renderGaussianView, what `glint render` and
// `glint eval` call per view) with the fast tracer against the Embree k-buffer baseline, on
// the same scene, cameras and settings: a dense initialisation of builtin:room cut to
// 100k and 500k Gaussians, seen from the dataset's test cameras (inside the room) and from
// cameras orbiting outside it, primary rays only and 2-bounce paths. Prints a table of
// times and ratios, the memory of the tracers and of the render's wavefront buffers, and
// writes JSON (--json FILE).
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/viewer/viewer_camera.h"
#include "core/parallel.h"
#include "math/rng.h"
#include "raytrace/fast/fast_tracer.h"
#include "render/gaussian_renderer.h"
#include "scene/dataset.h"
#include "synth/builtin_scenes.h"
#include "synth/dataset_generator.h"
#include "train/dense_init.h"

using namespace glint;
namespace fs = std::filesystem;

namespace {

double secondsOf(const std::function<void()>& f) {
  auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A random subset of `count` Gaussians (all of them when there are fewer), in index order.
GaussianScene subset(const GaussianScene& scene, size_t count, uint64_t seed) {
  if (scene.size() <= count) return scene;
  std::vector<uint32_t> order(scene.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = uint32_t(i);
  Rng rng(seed);
  for (size_t i = 0; i < count; ++i) std::swap(order[i], order[i + rng.uniformInt(uint32_t(order.size() - i))]);
  std::vector<bool> keep(scene.size(), false);
  for (size_t i = 0; i < count; ++i) keep[order[i]] = true;
  GaussianScene out = scene;
  out.filter(keep);
  return out;
}

// Cameras on a circle around the scene's bounding box, outside it, looking at its centre.
std::vector<Camera> outsideCameras(const GaussianScene& scene, int views, int width, int height) {
  Vec3f lo = scene.position[0], hi = lo;
  for (const Vec3f& p : scene.position) lo = min(lo, p), hi = max(hi, p);
  Vec3d centre((lo + hi) * 0.5f);
  double radius = 0.5 * double(length(hi - lo));
  std::vector<Camera> cameras;
  for (int v = 0; v < views; ++v) {
    double a = 6.283185307 * (v + 0.5) / views;
    ViewerCamera c;
    c.eye = centre + Vec3d(1.6 * radius * std::sin(a), 0.5 * radius, 1.6 * radius * std::cos(a));
    c.forward = normalize(centre - c.eye);
    c.fovX = 0.9;
    cameras.push_back(c.camera(width, height));
  }
  return cameras;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"glint render's path (renderGaussianView) with the fast tracer vs the Embree k=16 baseline"};
  std::string datasetPath, jsonPath;
  int width = 320, height = 240, views = 4, threads = 2, repeats = 1;
  std::vector<int> counts{100000, 500000};
  app.add_option("--dataset", datasetPath, "Dataset to initialise from (default: builtin:room, 60 views of 160x120, "
                                           "rendered into a temporary folder)");
  app.add_option("--gaussians", counts, "Scene sizes (a random subset of a dense initialisation)")->capture_default_str();
  app.add_option("--width", width, "Image width")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--height", height, "Image height")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--views", views, "Views rendered per measurement")->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--repeats", repeats, "Renders of each view per measurement")->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--threads", threads, "Threads")->check(CLI::Range(1, 1024))->capture_default_str();
  app.add_option("--json", jsonPath, "Write the results as JSON here");
  CLI11_PARSE(app, argc, argv);
  ThreadLimit limit(threads);

  fs::path temp;
  if (datasetPath.empty()) {
    temp = fs::temp_directory_path() / ("glint_render_bench_" + std::to_string(::getpid()));
    SynthSettings s;
    s.trainViews = 60;
    s.testViews = views;
    s.width = 160;
    s.height = 120;
    s.spp = 2;
    std::fprintf(stderr, "rendering builtin:room (60 views, 160x120, 2 spp) into %s\n", temp.c_str());
    generateDataset(makeBuiltinScene("room"), s, temp);
    datasetPath = temp.string();
  }
  Dataset dataset = Dataset::open(datasetPath);
  DenseInitSettings initSettings;
  initSettings.pixelStride = 1;
  initSettings.maxPixelSamples = kMaxInitialSamples;
  initSettings.voxelFraction = 1.0f / 1024.0f;
  initSettings.minSamplesPerVoxel = 1;
  GaussianScene dense = denseInitialisation(dataset, initSettings).scene;
  std::fprintf(stderr, "dense initialisation: %zu Gaussians\n", dense.size());

  std::vector<Camera> inside;
  for (size_t v = 0; v < dataset.test().views.size() && int(v) < views; ++v) {
    Camera c = dataset.test().camera(v);
    c.width = width, c.height = height;
    inside.push_back(c);
  }
  TraceSettings trace;  // the defaults glint render uses for a scene without a run
  std::printf("render_bench: renderGaussianView at %dx%d, 1 spp, %d views x %d repeats per measurement, %d threads\n",
              width, height, views, repeats, threads);
  std::printf("%-9s %-8s %-8s %12s %12s %8s %14s %10s %10s\n", "gaussians", "cameras", "bounces", "fast s",
              "embree s", "ratio", "fast unsorted s", "fast MB", "embree MB");
  nlohmann::json json;
  json["width"] = width, json["height"] = height, json["views"] = views, json["threads"] = threads;
  for (int count : counts) {
    GaussianScene scene = subset(dense, size_t(count), 7);
    std::vector<Camera> outside = outsideCameras(scene, views, width, height);
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
        double fastSeconds = secondsOf([&] { renderAll(*fast); });
        double embreeSeconds = secondsOf([&] { renderAll(*embree); });
        // The reflected rays in path order instead of sorted by origin and octant.
        double unsortedSeconds = 0;
        if (bounces > 0) {
          settings.path.reflectedOrder = ReflectedRayOrder::PathOrder;
          unsortedSeconds = secondsOf([&] { renderAll(*fast); });
          settings.path.reflectedOrder = ReflectedRayOrder::OriginAndOctant;
        }
        std::printf("%-9zu %-8s %-8d %12.3f %12.3f %7.2fx %14.3f %10.1f %10.1f\n", scene.size(), where, bounces,
                    fastSeconds, embreeSeconds, embreeSeconds / fastSeconds, unsortedSeconds, fast->memoryBytes() / 1e6,
                    embree->memoryBytes() / 1e6);
        json["runs"].push_back({{"gaussians", scene.size()}, {"cameras", where}, {"bounces", bounces},
                                {"fast_s", fastSeconds}, {"embree_s", embreeSeconds},
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
  if (!temp.empty()) fs::remove_all(temp);
  return 0;
}
