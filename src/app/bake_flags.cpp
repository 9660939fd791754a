// Setting up a reflection bake for `glint export` from a run's settings and its dataset.
#include "app/bake_flags.h"

#include <chrono>
#include <cstdio>

#include "core/error.h"
#include "raytrace/gaussian_tracer.h"
#include "render/sh_bake.h"
#include "scene/dataset.h"
#include "train/run_folder.h"

namespace glint {

namespace fs = std::filesystem;

void BakeFlags::add(CLI::App* cmd) {
  cmd_ = cmd;
  cmd->add_flag("--bake-reflections", bake_,
                "Fit each Gaussian's spherical harmonics (degree --sh-degree) to the path-traced radiance leaving it "
                "(diffuse plus reflections, the scene's render bounces, after the filmic tonemap), so a plain 3DGS "
                "viewer shows the reflections approximately. Directions come from the dataset's training cameras "
                "that see each Gaussian (the whole sphere without a dataset). For 3dgs, spz and compressed-ply");
  cmd->add_option("--sh-degree", shDegree_, "SH degree of --bake-reflections")
      ->check(CLI::Range(1, 3))
      ->capture_default_str();
  cmd->add_option("--bake-directions", directions_, "Paths traced through each Gaussian by --bake-reflections")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  cmd->add_option("--bake-ridge", ridge_,
                  "Ridge weight of --bake-reflections' fit on the view-dependent SH terms (relative to the samples' "
                  "total weight): larger is smoother, what the samples leave open stays a constant colour")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  cmd->add_option("--dataset", dataset_,
                  "Dataset whose training cameras set --bake-reflections' directions (default: the run's)");
  cmd->add_option("--seed", seed_, "Seed of --bake-reflections' sampling")->capture_default_str();
}

void BakeFlags::check() const {
  if (bake_) return;
  for (const char* flag : {"--sh-degree", "--bake-directions", "--bake-ridge", "--dataset", "--seed"})
    if (cmd_->get_option(flag)->count() > 0) throw Error(flag, "only applies with --bake-reflections");
}

SplatColour BakeFlags::bake(const fs::path& input, const GaussianScene& scene) const {
  TrainConfig run;  // a bare .ply renders with a new run's defaults, as `glint render` does
  if (fs::is_directory(input) && RunFolder(input).hasConfig()) run = RunFolder(input).readConfig();
  ShBakeSettings settings;
  settings.degree = shDegree_;
  settings.directions = directions_;
  settings.ridge = ridge_;
  settings.seed = seed_;
  settings.path = run.renderPath();
  const fs::path dataset = dataset_.empty() ? fs::path(run.dataset) : fs::path(dataset_);
  if (!dataset.empty()) {
    const DatasetSplit& train = Dataset::open(dataset, /*requireBuffers=*/false, run.holdout).split("train");
    for (size_t v = 0; v < train.views.size(); ++v) settings.cameras.push_back(train.camera(v));
  } else {
    std::fprintf(stderr, "glint export: no dataset known, so --bake-reflections samples every direction\n");
  }
  auto start = std::chrono::steady_clock::now();
  std::unique_ptr<GaussianTracer> tracer = makeGaussianTracer("fast");
  tracer->build(scene, run.trace);
  SplatColour colour = bakeReflections(scene, *tracer, settings);
  std::fprintf(stderr,
               "glint export: baked reflections into SH degree %d (%d paths per Gaussian, %d bounces, %zu cameras) "
               "in %.1f s\n",
               shDegree_, directions_, settings.path.bounces, settings.cameras.size(),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return colour;
}

}  // namespace glint
