// Benchmark of the reference path tracer (`glint synth`): rays per second on the built-in
// scenes, with 1 thread and with all threads in the same run, and the scaling ratio.
// Prints a table and writes JSON (--json FILE).
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/parallel.h"
#include "synth/builtin_scenes.h"
#include "synth/camera_paths.h"
#include "synth/dataset_generator.h"
#include "synth/light_sampler.h"
#include "synth/ray_caster.h"

using namespace glint;

namespace {

struct Row {
  std::string scene;
  int threads;
  double seconds;
  double megaRays;
  double megaSamples;
};

Row measure(const std::string& name, int threads, int width, int height, int spp, int views) {
  MeshScene scene = makeBuiltinScene(name);
  RayCaster caster(scene);
  LightSampler lights(scene);
  PathTracer tracer(scene, caster, lights, PathTracerSettings{6, 3});
  SynthSettings settings;
  settings.spp = spp;
  std::vector<Mat4> poses = orbitCameras(scene.cameras.train, views);
  ThreadLimit limit(threads);
  caster.resetRayCount();
  auto start = std::chrono::steady_clock::now();
  for (int v = 0; v < views; ++v) {
    Camera camera = Camera::fromFieldOfView(poses[v], scene.cameras.fovX, width, height);
    renderView(tracer, camera, settings, uint64_t(v));
  }
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double samples = double(width) * height * spp * views;
  return {name, maxThreads(), seconds, caster.rayCount() / seconds * 1e-6, samples / seconds * 1e-6};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Measures the reference path tracer of `glint synth` (rays per second, thread scaling)."};
  int width = 128, height = 96, spp = 32, views = 2;
  std::string jsonPath;
  app.add_option("--res-width", width, "Image width")->check(CLI::Range(8, 4096))->capture_default_str();
  app.add_option("--res-height", height, "Image height")->check(CLI::Range(8, 4096))->capture_default_str();
  app.add_option("--spp", spp, "Samples per pixel")->check(CLI::Range(1, 4096))->capture_default_str();
  app.add_option("--views", views, "Views rendered per measurement")->check(CLI::Range(1, 100))->capture_default_str();
  app.add_option("--json", jsonPath, "Also write the results to this JSON file");
  CLI11_PARSE(app, argc, argv);

  std::vector<Row> rows;
  for (const std::string& name : builtinSceneNames()) {
    rows.push_back(measure(name, 1, width, height, spp, views));
    rows.push_back(measure(name, 0, width, height, spp, views));
  }

  std::printf("synth_bench: %dx%d, %d spp, %d views per row, 6 bounces\n\n", width, height, spp, views);
  std::printf("%-10s %8s %10s %10s %14s %16s\n", "scene", "threads", "seconds", "Mrays/s", "Msamples/s", "speed-up vs 1");
  nlohmann::json json = nlohmann::json::array();
  for (size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    const Row& single = rows[i - i % 2];
    double speedup = r.megaRays / single.megaRays;
    std::printf("%-10s %8d %10.2f %10.2f %14.3f %16.2f\n", r.scene.c_str(), r.threads, r.seconds, r.megaRays,
                r.megaSamples, speedup);
    json.push_back({{"scene", r.scene}, {"threads", r.threads}, {"seconds", r.seconds}, {"mrays_per_s", r.megaRays},
                    {"msamples_per_s", r.megaSamples}, {"speedup_vs_1_thread", speedup},
                    {"width", width}, {"height", height}, {"spp", spp}, {"views", views}});
  }
  if (!jsonPath.empty()) {
    std::ofstream out(jsonPath);
    out << json.dump(2) << "\n";
    std::printf("\nwrote %s\n", jsonPath.c_str());
  }
  return 0;
}
