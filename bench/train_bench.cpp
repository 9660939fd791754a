// Benchmark of the training pass on the same scene and rays: the forward pass alone (in
// rendering mode, and in training mode with the exact tail and hit lists), the fused
// forward+backward pass, and whole training steps (with reduction, Adam and refit). The
// scene is a dense initialisation trained for --warmup steps, so that hit counts are
// those of training. Whole-image batches (glint train --batch-images) are measured beside
// the random pixels. Prints a table with the ratios (time per ray) and writes JSON (--json FILE).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/parallel.h"
#include "math/rng.h"
#include "raytrace/fast/fast_tracer.h"
#include "scene/dataset.h"
#include "synth/builtin_scenes.h"
#include "synth/dataset_generator.h"
#include "train/camera_culling.h"
#include "train/dense_init.h"
#include "train/scene_extent.h"
#include "render/gaussian_path.h"
#include "train/trainer.h"
#include "bench_timing.h"
#include "training_dataset.h"

using namespace glint;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  CLI::App app{"Forward vs fused forward+backward throughput of Glint's training pass"};
  std::string datasetPath, jsonPath;
  int warmup = 800, batches = 8, batchRays = 16384, threads = 2, reflectionWarmup = TrainConfig{}.reflectionWarmup;
  int batchImages = 1;
  int64_t wavefrontPaths = Trainer::kWavefrontRays;
  std::string tracerKind = "fast";
  app.add_option("--dataset", datasetPath, "Dataset to train on (default: builtin:spheres, 40 views of 160x120, "
                                           "rendered into a temporary folder)");
  app.add_option("--warmup", warmup, "Training steps before measuring (the default passes the reflection warm-up of "
                                     "750 steps, so the measured steps trace 2-bounce paths)")->check(CLI::Range(0, 1000000));
  app.add_option("--reflection-warmup", reflectionWarmup, "Steps before reflections are trained (training's default; "
                                                         "lower it to profile reflected paths sooner)")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  app.add_option("--batches", batches, "Batches measured per pass")->check(CLI::Range(1, 100000));
  app.add_option("--batch-rays", batchRays, "Rays per batch")->check(CLI::Range(1, 1 << 24));
  app.add_option("--batch-images", batchImages, "Views per whole-image batch in the rows that train on whole images "
                                               "(glint train --batch-images)")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  app.add_option("--threads", threads, "Threads")->check(CLI::Range(1, 1024));
  app.add_option("--wavefront-rays", wavefrontPaths, "Paths per wavefront of the trainer's steps (Trainer::kWavefrontRays "
                                              "by default)")
      ->check(CLI::Range(int64_t(1), int64_t(1) << 24))
      ->capture_default_str();
  app.add_option("--tracer", tracerKind, "Gaussian tracer of the trainer (fast; cuda or cuda-warp: the GPU traces the "
                                         "wavefronts and runs the backward pass)")
      ->capture_default_str();
  app.add_option("--json", jsonPath, "Write the results as JSON here");
  CLI11_PARSE(app, argc, argv);
  ThreadLimit limit(threads);

  fs::path temp;
  if (datasetPath.empty()) {
    temp = fs::temp_directory_path() / ("glint_train_bench_" + std::to_string(::getpid()));
    renderTrainingBenchDataset(temp);
    datasetPath = temp.string();
  }
  Dataset dataset = Dataset::open(datasetPath);
  TrainingViews views = TrainingViews::load(dataset, dataset.train());
  TrainConfig config;
  config.dataset = datasetPath;
  config.batchRays = batchRays;
  config.reflectionWarmup = reflectionWarmup;
  DenseInit init = denseInitialisation(dataset);
  Trainer trainer(config, views, cameraSpheres(dataset, dataset.train()), std::move(init.scene),
                  sceneExtent(dataset.train()), tracerKind);
  const bool gpu = isGpuTracer(tracerKind);
  trainer.setWavefrontRays(wavefrontPaths);
  std::fprintf(stderr, "warming up: %d training steps on %zu Gaussians\n", warmup, trainer.scene().size());
  for (int i = 0; i < warmup; ++i) trainer.step();

  // The same batches for every pass (drawn for steps beyond the warm-up).
  std::vector<std::vector<BatchRay>> rays(static_cast<size_t>(batches));
  for (int b = 0; b < batches; ++b) views.drawBatch(config.seed, 1000000 + b, batchRays, config.batchViews, &rays[b]);
  const double totalRays = double(batches) * batchRays;

  // Rendering mode: no exact tail, no hit list, the tracer's own batch loop.
  TraceSettings renderSettings = config.trace;
  renderSettings.exactTail = false;
  std::unique_ptr<GaussianTracer> renderTracer = makeGaussianTracer(tracerKind);
  renderTracer->build(trainer.scene(), renderSettings);
  std::vector<TraceRay> traceRays;
  std::vector<RayResult> results(static_cast<size_t>(batchRays));
  double renderSeconds = secondsOf([&] {
    for (const auto& batch : rays) {
      traceRays.clear();
      for (const BatchRay& r : batch) traceRays.push_back(r.ray);
      renderTracer->traceBatch(traceRays, results);
    }
  });
  StepReport forwardReport, fusedReport;
  double forwardSeconds = secondsOf([&] {
    for (const auto& batch : rays) trainer.forwardBackward(batch, false, &forwardReport);
  });
  double fusedSeconds = secondsOf([&] {
    for (const auto& batch : rays) trainer.forwardBackward(batch, true, &fusedReport);
  });
  // On the GPU, the backward pass's sums both ways (raytrace/backward_batch.h): records
  // sorted by Gaussian (the default, reproducible) and atomic adds.
  double atomicSeconds = 0;
  StepReport atomicReport;
  if (gpu) {
    trainer.setBackwardBatch(makeBackwardBatch(tracerKind, GradientSum::Atomic));
    atomicSeconds = secondsOf([&] {
      for (const auto& batch : rays) trainer.forwardBackward(batch, true, &atomicReport);
    });
    trainer.setBackwardBatch(makeBackwardBatch(tracerKind, GradientSum::Sorted));
  }
  // The forward pass's paths alone, four ways on the trainer's own scene and settings: the
  // wavefront as the trainer runs it (camera rays traced one by one, reflected rays sorted
  // by origin and octant), with the reflected rays in path order, with the camera rays in
  // bundles (as renders trace them), and the per-ray design that training ran before the
  // wavefront (each thread traces whole paths with tracePath, one by one).
  PathSettings paths = config.path();
  paths.hitListCapacity = hitCapacityWithoutOverflow(config.trace);
  std::vector<std::vector<TraceRay>> primaries(rays.size());
  std::vector<std::vector<PathKey>> keys(rays.size());
  for (size_t b = 0; b < rays.size(); ++b)
    for (const BatchRay& r : rays[b]) {
      primaries[b].push_back(r.ray);
      keys[b].push_back({r.view, r.pixel, uint64_t(1000000 + b)});
    }
  std::vector<PathResult> pathResults(static_cast<size_t>(batchRays));
  auto wavefrontSeconds = [&](ReflectedRayOrder order, RayCoherence coherence) {
    PathSettings p = paths;
    p.reflectedOrder = order;
    p.primaryCoherence = coherence;
    PathBatch wavefront;
    pathResults.resize(std::min(primaries[0].size(), size_t(wavefrontPaths)));
    wavefront.trace(trainer.tracer(), std::span(primaries[0]).first(pathResults.size()),
                    std::span(keys[0]).first(pathResults.size()), config.seed, p, pathResults, /*record=*/true);  // warm
    return secondsOf([&] {
      for (size_t b = 0; b < rays.size(); ++b)
        for (size_t first = 0; first < primaries[b].size(); first += size_t(wavefrontPaths)) {
          const size_t count = std::min(size_t(wavefrontPaths), primaries[b].size() - first);
          pathResults.resize(count);
          wavefront.trace(trainer.tracer(), std::span(primaries[b]).subspan(first, count),
                          std::span(keys[b]).subspan(first, count), config.seed, p, pathResults, /*record=*/true);
        }
    });
  };
  const double sortedSeconds = wavefrontSeconds(ReflectedRayOrder::OriginAndOctant, RayCoherence::Scattered);
  const double pathOrderSeconds = wavefrontSeconds(ReflectedRayOrder::PathOrder, RayCoherence::Scattered);
  const double bundledSeconds = wavefrontSeconds(ReflectedRayOrder::OriginAndOctant, RayCoherence::Coherent);
  // A what-if for the next step: the same views, each view's pixels drawn as 8x8 tiles
  // (64 random tiles of the image's 8x8 grid per view) instead of scattered, traced in
  // bundles and ray by ray. Not what training does today.
  const std::vector<std::vector<TraceRay>> scattered = primaries;
  const std::vector<std::vector<PathKey>> scatteredKeys = keys;
  for (size_t b = 0; b < rays.size(); ++b) {
    primaries[b].clear(), keys[b].clear();
    Rng rng(1000 + b);
    const int width = views.camera(0).width;  // the bench's datasets have one image size
    const int tilesX = width / 8, tilesY = views.camera(0).height / 8;
    size_t first = 0;
    while (first < rays[b].size()) {
      const uint32_t view = rays[b][first].view;
      size_t count = 0;
      while (first + count < rays[b].size() && rays[b][first + count].view == view) ++count;
      for (size_t t = 0; t * 64 < count; ++t) {
        const int tx = int(rng.uniformInt(uint32_t(tilesX))), ty = int(rng.uniformInt(uint32_t(tilesY)));
        for (int k = 0; k < 64 && t * 64 + size_t(k) < count; ++k) {
          const uint64_t pixel = uint64_t(ty * 8 + k / 8) * uint64_t(width) + uint64_t(tx * 8 + k % 8);
          primaries[b].push_back(views.pixelRay(view, pixel));
          keys[b].push_back({view, pixel, uint64_t(1000000 + b)});
        }
      }
      first += count;
    }
  }
  const double tilesBundledSeconds = wavefrontSeconds(ReflectedRayOrder::OriginAndOctant, RayCoherence::Coherent);
  const double tilesAloneSeconds = wavefrontSeconds(ReflectedRayOrder::OriginAndOctant, RayCoherence::Scattered);
  // Whole images (glint train --batch-images): every pixel of the batch's views in row
  // order, camera rays in bundles (as the trainer traces them) and one by one.
  std::vector<std::vector<BatchRay>> wholeImages(static_cast<size_t>(batches));
  double wholeImageRays = 0;
  for (size_t b = 0; b < rays.size(); ++b) {
    views.drawWholeImages(config.seed, 1000000 + int64_t(b), batchImages, &wholeImages[b]);
    primaries[b].clear(), keys[b].clear();
    for (const BatchRay& r : wholeImages[b]) {
      primaries[b].push_back(r.ray);
      keys[b].push_back({r.view, r.pixel, uint64_t(1000000 + b)});
    }
    wholeImageRays += double(wholeImages[b].size());
  }
  const double wholeBundledSeconds = wavefrontSeconds(ReflectedRayOrder::OriginAndOctant, RayCoherence::Coherent);
  const double wholeAloneSeconds = wavefrontSeconds(ReflectedRayOrder::OriginAndOctant, RayCoherence::Scattered);
  primaries = scattered, keys = scatteredKeys;
  // (Not on the GPU, where one ray at a time is one launch each.)
  const double perRaySeconds = gpu ? 0.0 : secondsOf([&] {
    for (size_t b = 0; b < rays.size(); ++b)
      parallelForChunks(int64_t(primaries[b].size()), 64, [&](int64_t begin, int64_t end) {
        thread_local std::vector<PathSegment> segments;
        for (int64_t r = begin; r < end; ++r) {
          const PathKey& k = keys[b][size_t(r)];
          pathResults[size_t(r)] = tracePath(trainer.tracer(), primaries[b][size_t(r)], paths, config.seed, k.view,
                                             k.pixel, k.sample, &segments);
        }
      });
  });
  // Whole training steps on whole images: the same scene and state, the trainer set to
  // --batch-images (its steps draw their own views).
  TrainConfig wholeConfig = config;
  wholeConfig.batchImages = batchImages;
  Trainer wholeTrainer(wholeConfig, views, cameraSpheres(dataset, dataset.train()), trainer.state(), tracerKind);
  wholeTrainer.setWavefrontRays(wavefrontPaths);
  double wholeStepRays = 0;
  const double wholeStepSeconds = secondsOf([&] {
    for (int b = 0; b < batches; ++b) wholeStepRays += double(wholeTrainer.step().rays);
  });
  StepReport parts;  // the whole steps' parts, summed
  double stepSeconds = secondsOf([&] {
    for (int b = 0; b < batches; ++b) parts.addTimes(trainer.step());
  });

  // Each row's rays: the batches of random pixels, or (whole-image rows) of whole views.
  struct Row {
    const char* name;
    double seconds;
    double rays;
  } rows[] = {{"forward, rendering mode (batch camera rays, bundled)", renderSeconds, totalRays},
              {"forward, training mode (paths, hit lists, loss)", forwardSeconds, totalRays},
              {"fused forward+backward", fusedSeconds, totalRays},
              {"fused forward+backward, GPU sums by atomic adds", atomicSeconds, totalRays},
              {"paths only: wavefront (as trained)", sortedSeconds, totalRays},
              {"paths only: wavefront, reflected rays in path order", pathOrderSeconds, totalRays},
              {"paths only: wavefront, camera rays in bundles", bundledSeconds, totalRays},
              {"paths only, what-if 8x8 tiles: camera rays in bundles", tilesBundledSeconds, totalRays},
              {"paths only, what-if 8x8 tiles: camera rays one by one", tilesAloneSeconds, totalRays},
              {"paths only, whole images: camera rays in bundles", wholeBundledSeconds, wholeImageRays},
              {"paths only, whole images: camera rays one by one", wholeAloneSeconds, wholeImageRays},
              {"paths only: per-ray design before the wavefront", perRaySeconds, totalRays},
              {"whole step (+ reduction, Adam, refit)", stepSeconds, totalRays},
              {"whole step, whole images (--batch-images)", wholeStepSeconds, wholeStepRays}};
  std::printf("train_bench: %zu Gaussians, %.1f composited hits per ray, %d rays per batch, %d batches, %d threads, "
              "tracer %s%s%s\n",
              trainer.scene().size(), double(fusedReport.hits) / double(fusedReport.rays), batchRays, batches,
              threads, tracerKind.c_str(), trainer.backwardBatch() ? ", backward pass " : "",
              trainer.backwardBatch() ? trainer.backwardBatch()->name() : "");
  std::printf("whole-image rows: every pixel of %d view(s) a batch (%.0f rays)\n", batchImages,
              wholeImageRays / double(batches));
  std::printf("%-55s %10s %12s\n", "pass", "Mrays/s", "time ratio");
  nlohmann::json json;
  json["gaussians"] = trainer.scene().size();
  json["hits_per_ray"] = double(fusedReport.hits) / double(fusedReport.rays);
  json["batch_rays"] = batchRays;
  json["tracer"] = tracerKind;
  json["wavefront_rays"] = wavefrontPaths;
  json["threads"] = threads;
  json["batch_images"] = batchImages;
  // The time ratio is per ray, against the training forward pass.
  const double forwardPerRay = forwardSeconds / totalRays;
  for (const Row& r : rows) {
    if (r.seconds <= 0) continue;  // not measured on this device
    const double ratio = r.seconds / r.rays / forwardPerRay;
    std::printf("%-55s %10.3f %11.2fx\n", r.name, r.rays / r.seconds / 1e6, ratio);
    json["passes"][r.name] = {{"mrays_per_s", r.rays / r.seconds / 1e6}, {"ratio_to_training_forward", ratio}};
  }
  const double wavefrontRays = double(std::min<int64_t>(batchRays, wavefrontPaths));
  std::printf("reflected segments per ray %.2f; wavefront records %.1f MB for a wavefront of %.0f rays (%.0f B per "
              "ray, shared by the threads); fast tracer scratch %.1f KB per thread\n",
              double(fusedReport.reflectedSegments) / double(fusedReport.rays), trainer.wavefrontBytes() / 1e6,
              wavefrontRays, double(trainer.wavefrontBytes()) / wavefrontRays, FastGaussianTracer::threadScratchBytes() / 1e3);
  json["reflected_segments_per_ray"] = double(fusedReport.reflectedSegments) / double(fusedReport.rays);
  json["wavefront_bytes"] = trainer.wavefrontBytes();
  json["fast_thread_scratch_bytes"] = FastGaussianTracer::threadScratchBytes();
  std::printf("fused / forward (training mode): %.2fx   fused / forward (rendering mode): %.2fx   (paper: 2.23x, "
              "target <= 2.5x)\n",
              fusedSeconds / forwardSeconds, fusedSeconds / renderSeconds);
  json["fused_over_forward_training_mode"] = fusedSeconds / forwardSeconds;
  json["fused_over_forward_rendering_mode"] = fusedSeconds / renderSeconds;
  // A step's parts (StepReport): the wavefronts' tracing; the losses and backward pass (on
  // the GPU: the jobs built and uploaded, the kernels) and the reduction (the threads'
  // buffers summed, or the GPU's sums downloaded); the Adam step; housekeeping (pruning,
  // densification, the tracer's refit); and the rest (drawing the batch, the scale decay).
  const double backwardAlone = parts.backwardSeconds - parts.reduceSeconds;
  const double rest = parts.seconds - parts.traceSeconds - parts.backwardSeconds - parts.adamSeconds -
                      parts.housekeepingSeconds;
  std::printf("whole step's parts, ms per step: trace %.1f, backward %.1f, reduction %.1f, Adam %.1f, housekeeping "
              "(refit) %.1f, rest %.1f; total %.1f\n",
              1e3 * parts.traceSeconds / batches, 1e3 * backwardAlone / batches, 1e3 * parts.reduceSeconds / batches,
              1e3 * parts.adamSeconds / batches, 1e3 * parts.housekeepingSeconds / batches, 1e3 * rest / batches,
              1e3 * parts.seconds / batches);
  json["step_parts_ms"] = {{"trace", 1e3 * parts.traceSeconds / batches},
                           {"backward", 1e3 * backwardAlone / batches},
                           {"reduction", 1e3 * parts.reduceSeconds / batches},
                           {"adam", 1e3 * parts.adamSeconds / batches},
                           {"housekeeping", 1e3 * parts.housekeepingSeconds / batches},
                           {"rest", 1e3 * rest / batches},
                           {"total", 1e3 * parts.seconds / batches}};
  if (gpu) {
    if (!jsonPath.empty()) std::ofstream(jsonPath) << json.dump(2) << "\n";
    if (!temp.empty()) fs::remove_all(temp);
    return 0;
  }
  // The step of the per-ray design: today's step with its wavefront swapped for per-ray paths.
  const double perRayStep = stepSeconds - sortedSeconds + perRaySeconds;
  std::printf("whole step, per-ray design (estimated: the step with per-ray paths instead of the wavefront): "
              "%.3f Mrays/s; wavefront step is %.2fx faster\n",
              totalRays / perRayStep / 1e6, perRayStep / stepSeconds);
  json["per_ray_design_step_mrays_per_s"] = totalRays / perRayStep / 1e6;
  json["step_speedup_over_per_ray_design"] = perRayStep / stepSeconds;
  if (!jsonPath.empty()) std::ofstream(jsonPath) << json.dump(2) << "\n";
  if (!temp.empty()) fs::remove_all(temp);
  return 0;
}
