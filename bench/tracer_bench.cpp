// Benchmark of the Gaussian tracers on the random "room of Gaussians" scenes of issue 3's
// prototype (100k and 500k Gaussians filling a room-sized box, camera inside and outside
// the cloud, 256x256 rays, 2 threads): build and refit time, rays and hits per second,
// memory, and each tracer's speed-up over the Embree k=16 baseline, side by side.
// Prints a table and writes JSON (--json FILE).
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/parallel.h"
#include "room_scene.h"
#include "math/rng.h"
#include "raytrace/fast/fast_tracer.h"
#include "tracers/compute_device.h"
#include "tracers/embree_tracer.h"

using namespace glint;

namespace {

// A pinhole camera at `eye` looking at `target` (60 degrees horizontal field of view).
std::vector<TraceRay> cameraRays(Vec3f eye, Vec3f target, int width, int height) {
  Vec3f forward = normalize(target - eye);
  Vec3f right = normalize(cross(forward, Vec3f(0, 1, 0)));
  Vec3f up = cross(right, forward);
  float focal = 0.5f * float(width) / std::tan(0.5f * 60.0f * 3.14159265f / 180.0f);
  std::vector<TraceRay> rays;
  rays.reserve(size_t(width) * height);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      float x = (float(i) + 0.5f - 0.5f * float(width)) / focal, y = -(float(j) + 0.5f - 0.5f * float(height)) / focal;
      rays.push_back({eye, normalize(forward + right * x + up * y), 0.0f});
    }
  return rays;
}

struct View {
  std::string name;
  Vec3f eye, target;
};

const std::vector<View>& views() {
  static const std::vector<View> kViews = {{"inside", {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}},
                                           {"outside", {0.0f, 0.5f, 9.0f}, {0.0f, 0.0f, 0.0f}}};
  return kViews;
}

double seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double cpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

struct Row {
  std::string tracer, scene;
  double buildSeconds = 0, refitSeconds = 0;
  double megaRays = 0;         // per wall-clock second, all threads
  double megaRaysPerCpu = 0;   // per CPU second (robust to other load on the machine)
  double megaHits = 0;         // composited hits per wall-clock second
  double hitsPerRay = 0;       // composited
  double allHitsPerRay = 0;    // every hit with alpha >= alphaMin (no termination)
  double evaluationsPerRay = 0;  // kernel evaluations (proxy reached), where the tracer counts them
  double nodesPerRay = 0;        // inner nodes visited (fast tracer, per-ray traversal)
  double blocksPerRay = 0;       // 8-lane leaf blocks tested (fast tracer, per-ray traversal)
  double memoryMb = 0;
  double speedup = 0;          // megaRays / the baseline's on the same scene
  double cpuSpeedup = 0;       // megaRaysPerCpu / the baseline's (robust to other load)
};

// The tracers measured, by name; the first is the baseline the speed-up refers to. The GPU
// tracer ("cuda") joins where a GPU is; its rays and results cross to and from the GPU in
// every timed batch, as they do in the product.
// "fast-per-ray" is the fast tracer with coherent bundles off: every ray traverses the BVH
// alone, as incoherent (reflected) rays do.
std::vector<std::pair<std::string, std::function<std::unique_ptr<GaussianTracer>()>>> tracersToMeasure(
    int bundleRays) {
  std::vector<std::pair<std::string, std::function<std::unique_ptr<GaussianTracer>()>>> tracers = {
          {"embree-k16", [] { return std::make_unique<EmbreeK16Tracer>(); }},
          {"fast-per-ray",
           [] {
             auto t = std::make_unique<FastGaussianTracer>();
             t->setBundleRays(0);
             return t;
           }},
          {"fast", [bundleRays] {
             auto t = std::make_unique<FastGaussianTracer>();
             t->setBundleRays(bundleRays);
             return t;
           }}};
  std::string why;
  if (std::optional<GpuInfo> gpu = findGpu(&why)) {
    std::printf("tracer_bench: GPU %s\n", gpu->name.c_str());
    tracers.push_back({"cuda", [] { return makeGaussianTracer("cuda"); }});
    tracers.push_back({"cuda-warp", [] { return makeGaussianTracer("cuda-warp"); }});
  } else {
    std::printf("tracer_bench: no GPU tracer: %s\n", why.c_str());
  }
  return tracers;
}

// Per-ray work counts, for the tracers that count them (zero otherwise): kernel
// evaluations (Gaussians whose proxy the ray reached), and for the fast tracer's per-ray
// traversal the inner nodes and leaf blocks it visits.
struct WorkCounts {
  double evaluations = 0, nodes = 0, blocks = 0;
};

WorkCounts workPerRay(const GaussianTracer& tracer, const std::vector<TraceRay>& rays) {
  int64_t evaluations = 0;
  WorkCounts counts;
  if (auto* fast = dynamic_cast<const FastGaussianTracer*>(&tracer)) {
    FastTraceStats stats;
    for (const TraceRay& ray : rays) fast->trace(ray, nullptr, &stats);
    evaluations = stats.evaluations;
    counts.nodes = double(stats.nodes) / double(rays.size());
    counts.blocks = double(stats.leaves) / double(rays.size());
  } else if (auto* embree = dynamic_cast<const EmbreeK16Tracer*>(&tracer)) {
    for (const TraceRay& ray : rays) {
      EmbreeTraceStats stats;
      embree->trace(ray, nullptr, &stats);
      evaluations += stats.evaluations;
    }
  }
  counts.evaluations = double(evaluations) / double(rays.size());
  return counts;
}

// Builds, refits and traces every view of one scene with one tracer.
std::vector<Row> measure(const std::string& tracerName, GaussianTracer& tracer, GaussianScene& scene,
                         const std::string& sceneName, const TraceSettings& settings, int width, int height,
                         int repeats, const std::vector<double>& allHitsPerRay) {
  auto start = std::chrono::steady_clock::now();
  tracer.build(scene, settings);
  double build = seconds(start);
  // Refit after a small change of every Gaussian (as an optimiser step makes), then
  // restore the parameters so every tracer traces the same scene.
  std::vector<Vec3f> positions = scene.position;
  for (Vec3f& p : scene.position) p += Vec3f(1e-3f);
  start = std::chrono::steady_clock::now();
  tracer.refit();
  double refit = seconds(start);
  scene.position = positions;
  tracer.refit();

  std::vector<Row> rows;
  for (size_t v = 0; v < views().size(); ++v) {
    const View& view = views()[v];
    std::vector<TraceRay> rays = cameraRays(view.eye, view.target, width, height);
    std::vector<RayResult> results(rays.size());
    tracer.traceBatch(rays, results);  // warm-up
    double cpu0 = cpuSeconds();
    start = std::chrono::steady_clock::now();
    for (int r = 0; r < repeats; ++r) tracer.traceBatch(rays, results);
    double wall = seconds(start), cpu = cpuSeconds() - cpu0;
    double hits = 0;
    for (const RayResult& r : results) hits += r.hitCount;
    double rayCount = double(rays.size()) * repeats;
    Row row;
    row.tracer = tracerName;
    row.scene = sceneName + " " + view.name;
    row.buildSeconds = build;
    row.refitSeconds = refit;
    row.megaRays = rayCount / wall * 1e-6;
    row.megaRaysPerCpu = rayCount / cpu * 1e-6;
    row.megaHits = hits * repeats / wall * 1e-6;
    row.hitsPerRay = hits / double(rays.size());
    row.allHitsPerRay = allHitsPerRay[v];
    WorkCounts work = workPerRay(tracer, rays);
    row.evaluationsPerRay = work.evaluations;
    row.nodesPerRay = work.nodes;
    row.blocksPerRay = work.blocks;
    row.memoryMb = double(tracer.memoryBytes()) / (1024.0 * 1024.0);
    rows.push_back(row);
  }
  return rows;
}

// Hits per ray without termination (the scene's depth complexity), from the fast tracer.
std::vector<double> allHitsPerRay(const GaussianScene& scene, TraceSettings settings) {
  settings.minTransmittance = 0.0f;
  FastGaussianTracer tracer;
  tracer.build(scene, settings);
  std::vector<double> out;
  for (const View& view : views()) {
    std::vector<TraceRay> rays = cameraRays(view.eye, view.target, 64, 64);
    std::vector<RayResult> results(rays.size());
    tracer.traceBatch(rays, results);
    double hits = 0;
    for (const RayResult& r : results) hits += r.hitCount;
    out.push_back(hits / double(rays.size()));
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Measures the Gaussian tracers side by side on random room scenes (issue 3's prototype)."};
  int width = 256, height = 256, threads = 2, repeats = 2;
  std::vector<int> sizes = {100000, 500000};
  std::vector<std::string> only;
  std::string jsonPath;
  app.add_option("--res-width", width, "Image width")->check(CLI::Range(8, 4096))->capture_default_str();
  app.add_option("--res-height", height, "Image height")->check(CLI::Range(8, 4096))->capture_default_str();
  app.add_option("--threads", threads, "Worker threads (0 = all)")->check(CLI::Range(0, 256))->capture_default_str();
  app.add_option("--repeats", repeats, "Timed passes over the image per row")->check(CLI::Range(1, 100))->capture_default_str();
  app.add_option("--gaussians", sizes, "Scene sizes")->capture_default_str();
  app.add_option("--tracers", only, "Measure only these tracers (default: all; the first is the speed-up baseline)");
  app.add_option("--json", jsonPath, "Also write the results to this JSON file");
  bool exactTail = false;
  app.add_flag("--exact-tail", exactTail,
               "Keep traversing after termination for the exact final transmittance (the training mode of "
               "appendix A.2) instead of stopping early (the rendering mode)");
  int bundleRays = FastGaussianTracer::kDefaultBundleRays;
  app.add_option("--bundle-rays", bundleRays, "Rays per coherent bundle of the fast tracer")
      ->check(CLI::Range(2, 4096))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  ThreadLimit limit(threads);
  TraceSettings settings;  // the defaults: p = 3, alphaMin 0.005, minTransmittance 0.01
  settings.exactTail = exactTail;
  std::vector<Row> rows;
  for (int n : sizes) {
    GaussianScene scene = makeRoom(size_t(n), 1);
    std::string sceneName = std::to_string(n / 1000) + "k";
    std::vector<double> depth = allHitsPerRay(scene, settings);
    std::vector<Row> baseline;
    for (auto& [name, make] : tracersToMeasure(bundleRays)) {
      if (!only.empty() && std::find(only.begin(), only.end(), name) == only.end()) continue;
      std::unique_ptr<GaussianTracer> tracer = make();
      std::vector<Row> measured = measure(name, *tracer, scene, sceneName, settings, width, height, repeats, depth);
      if (baseline.empty()) baseline = measured;
      for (size_t v = 0; v < measured.size(); ++v) {
        measured[v].speedup = measured[v].megaRays / baseline[v].megaRays;
        measured[v].cpuSpeedup = measured[v].megaRaysPerCpu / baseline[v].megaRaysPerCpu;
      }
      rows.insert(rows.end(), measured.begin(), measured.end());
    }
  }

  std::printf("tracer_bench: %dx%d rays, %d threads, p = %.0f, alphaMin %.3f, minTransmittance %.2f, %s\n", width,
              height, maxThreads(), settings.kernelPower, settings.alphaMin, settings.minTransmittance,
              settings.exactTail ? "exact tail" : "early termination");
  std::printf("Mhits/s and hits/ray count composited hits; all/ray = every hit with alpha >= alphaMin (no\n"
              "termination); evals/ray = kernel evaluations (proxy reached); nodes/ray and blocks/ray = inner\n"
              "nodes and 8-lane leaf blocks a per-ray traversal visits; Mrays/CPUs = per CPU-second\n\n");
  std::printf("%-12s %-12s %8s %8s %9s %10s %9s %9s %8s %9s %9s %10s %9s %9s %7s\n", "tracer", "scene", "build s",
              "refit s", "Mrays/s", "Mrays/CPUs", "Mhits/s", "hits/ray", "all/ray", "evals/ray", "nodes/ray", "blocks/ray",
              "memory MB", "speed-up", "(CPU)");
  nlohmann::json json = nlohmann::json::array();
  for (const Row& r : rows) {
    std::printf("%-12s %-12s %8.3f %8.4f %9.3f %10.3f %9.2f %9.1f %8.1f %9.1f %9.1f %10.1f %9.1f %8.2fx %6.2fx\n",
                r.tracer.c_str(), r.scene.c_str(), r.buildSeconds, r.refitSeconds, r.megaRays, r.megaRaysPerCpu,
                r.megaHits, r.hitsPerRay, r.allHitsPerRay, r.evaluationsPerRay, r.nodesPerRay, r.blocksPerRay,
                r.memoryMb, r.speedup, r.cpuSpeedup);
    json.push_back({{"tracer", r.tracer}, {"scene", r.scene}, {"exact_tail", settings.exactTail}, {"build_s", r.buildSeconds}, {"refit_s", r.refitSeconds},
                    {"mrays_per_s", r.megaRays}, {"mrays_per_cpu_s", r.megaRaysPerCpu}, {"mhits_per_s", r.megaHits},
                    {"composited_hits_per_ray", r.hitsPerRay}, {"all_hits_per_ray", r.allHitsPerRay},
                    {"evaluations_per_ray", r.evaluationsPerRay}, {"nodes_per_ray", r.nodesPerRay},
                    {"blocks_per_ray", r.blocksPerRay},
                    {"memory_mb", r.memoryMb}, {"speedup_vs_baseline", r.speedup},
                    {"cpu_speedup_vs_baseline", r.cpuSpeedup}, {"width", width},
                    {"height", height}, {"threads", maxThreads()}});
  }
  if (!jsonPath.empty()) {
    std::ofstream out(jsonPath);
    out << json.dump(2) << "\n";
    std::printf("\nwrote %s\n", jsonPath.c_str());
  }
  return 0;
}
