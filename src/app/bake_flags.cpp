// Setting up a reflection bake for `glint export` from a run's settings and its dataset.
#include "app/bake_flags.h"

#include <chrono>
#include <cstdio>

#include "app/trace_flags.h"
#include "core/error.h"
#include "raytrace/gaussian_tracer.h"
#include "render/sh_bake.h"
#include "scene/dataset.h"

namespace glint {

namespace fs = std::filesystem;

void BakeFlags::add(CLI::App* cmd) {
  cmd_ = cmd;
  cmd->add_flag("--bake-reflections", bake_,
                "Fit each Gaussian's spherical harmonics (degree --sh-degree) to the path-traced radiance leaving it "
                "(diffuse plus reflections, the scene's render bounces, after --exposure and the filmic tonemap), so a "
                "plain 3DGS viewer shows the reflections approximately. Directions come from the training cameras "
                "(of --dataset, else the run's) that see each Gaussian; the whole sphere without a dataset. For 3dgs, "
                "spz and compressed-ply; the bake sees the whole scene, far field included, before any is dropped");
  cmd->add_option("--bake-directions", directions_, "Paths traced through each Gaussian by --bake-reflections")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  cmd->add_option("--bake-ridge", ridge_,
                  "Ridge weight of --bake-reflections' fit on the view-dependent SH terms (relative to the samples' "
                  "total weight): larger is smoother, what the samples leave open stays a constant colour")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  cmd->add_option("--seed", seed_, "Seed of --bake-reflections' sampling")->capture_default_str();
  addDeviceFlag(cmd, &device_);
}

void BakeFlags::check() const {
  if (bake_) return;
  for (const char* flag : {"--bake-directions", "--bake-ridge", "--seed", "--device"})
    if (cmd_->get_option(flag)->count() > 0) throw Error(flag, "only applies with --bake-reflections");
}

SplatColour BakeFlags::bake(const GaussianScene& scene, const TrainConfig& run, int degree,
                            const std::string& datasetOverride, float exposure) const {
  ShBakeSettings settings;
  settings.degree = degree;
  settings.directions = directions_;
  settings.ridge = ridge_;
  settings.seed = seed_;
  settings.exposure = exposure;
  settings.path = run.renderPath();
  const fs::path dataset = datasetOverride.empty() ? fs::path(run.dataset) : fs::path(datasetOverride);
  if (!dataset.empty()) {
    const Dataset opened = Dataset::open(dataset, /*requireBuffers=*/false, run.holdout);
    const DatasetSplit& train = opened.split("train");
    for (size_t v = 0; v < train.views.size(); ++v) settings.cameras.push_back(train.camera(v));
  } else {
    std::fprintf(stderr, "glint export: no dataset known, so --bake-reflections samples every direction\n");
  }
  auto start = std::chrono::steady_clock::now();
  std::unique_ptr<GaussianTracer> tracer =
      makeGaussianTracer(resolveTracerForDevice(device_, "fast", /*tracerGiven=*/false, "glint export"));
  tracer->build(scene, run.trace);
  SplatColour colour = bakeReflections(scene, *tracer, settings);
  std::fprintf(stderr,
               "glint export: baked reflections into SH degree %d (%d paths per Gaussian, %d bounces, %zu cameras) "
               "in %.1f s\n",
               degree, directions_, settings.path.bounces, settings.cameras.size(),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return colour;
}

}  // namespace glint
