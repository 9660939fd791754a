// `glint train DATASET -o RUN`: learns a Gaussian scene from a dataset. The run folder holds
// config.json (every hyper-parameter), log.csv, scene.ply and a resumable checkpoint.
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/commands.h"
#include "app/viewer/viewer_setup.h"
#include "core/activity.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "eval/training_log.h"
#include "scene/dataset.h"
#include "scene/gaussian_ply.h"
#include "train/camera_culling.h"
#include "train/checkpoint.h"
#include "train/dense_init.h"
#include "train/divergence_monitor.h"
#include "train/scene_extent.h"
#include "train/train_config.h"
#include "train/trainer.h"
#include "train/training_eval.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

struct TrainOptions {
  std::string dataset;
  std::string output;
  std::string configFile;
  bool resume = false;
  bool force = false;
  std::string tracer = "fast";
  int evalViews = 20;
  int evalSpp = 4;
  bool view = false;       // serve the viewer page showing the scene as it trains
  ViewerFlags viewer;
  double viewEvery = 2.0;  // seconds between the snapshots the viewer shows
  TrainConfig config;  // defaults, overridden by --config, then by explicit flags
};

std::atomic<bool> gInterrupted{false};
extern "C" void onInterrupt(int) { gInterrupted = true; }

constexpr const char* kLogHeader =
    "step,loss,diffuse_l1,depth_l1,normal_l1,roughness_l1,f0_l1,specular_l1,gaussians,hits_per_ray,rays_per_s,wall_s,"
    "test_diffuse_psnr,test_normal_deg\n";

fs::path checkpointFile(const fs::path& run) { return run / "checkpoint" / "state.bin"; }

// Keeps the log rows up to `step` (a resumed run rewrites what came after its checkpoint)
// and returns the wall time of the last kept row. A last row without its newline was cut
// short by a crash or a full disk and is dropped; any other row that does not parse is an
// error naming the file and line, since the run's history would be lost with it.
double truncateLog(const fs::path& log, int64_t step) {
  std::string text = fs::exists(log) ? readTextFile(log) : std::string(kLogHeader);
  if (!text.empty() && text.back() != '\n') text.erase(text.rfind('\n') + 1);
  if (text.empty()) text = kLogHeader;
  TrainingLog parsed = parseTrainingLog(text, log.string(), {"step", "wall_s"});
  const std::vector<double>& steps = parsed.column("step");
  const std::vector<double>& walls = parsed.column("wall_s");
  std::string kept = kLogHeader;
  double wall = 0;
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);  // the header, rewritten as today's
  for (size_t row = 0; row < parsed.rows() && std::getline(lines, line);) {
    if (line.empty() || line == "\r") continue;  // rows the parser skips too
    if (!(steps[row] <= double(step))) break;
    wall = walls[row];
    kept += line + "\n";
    ++row;
  }
  writeTextAtomically(log, kept);
  return wall;
}

std::string formatCount(double n) {
  char buf[32];
  if (n >= 1e6)
    std::snprintf(buf, sizeof(buf), "%.2fM", n / 1e6);
  else if (n >= 1e3)
    std::snprintf(buf, sizeof(buf), "%.1fk", n / 1e3);
  else
    std::snprintf(buf, sizeof(buf), "%.0f", n);
  return buf;
}

GaussianScene initialScene(const Dataset& dataset, const TrainConfig& config) {
  DenseInitSettings settings = config.init;
  settings.forceDepthBuffers = config.initSource == "depth";
  DenseInit init = config.initSource == "point-cloud" ? initFromPointCloud(dataset, settings)
                                                      : denseInitialisation(dataset, settings);
  const DenseInitStats& st = init.stats;
  if (st.source == InitSource::PointCloud)
    std::fprintf(stderr, "glint train: initialised %zu Gaussians from point_cloud_dense.ply (%lld points)\n",
                 init.scene.size(), (long long)st.pointsUnprojected);
  else
    std::fprintf(stderr,
                 "glint train: initialised %zu Gaussians from the depth buffers (stride %d, %lld samples, "
                 "voxel %.4g, %lld of %lld voxels kept)\n",
                 init.scene.size(), st.pixelStride, (long long)st.pointsUnprojected, st.voxelSize,
                 (long long)st.voxelsKept, (long long)st.voxelsOccupied);
  return std::move(init.scene);
}

void saveRun(const fs::path& run, const Trainer& trainer) {
  writeCheckpoint(checkpointFile(run), trainer.state());
  writeGaussianPly(run / "scene.ply", trainer.scene());
}

void runTrain(TrainOptions& o, const CLI::App& cmd) {
  const fs::path run = o.output;
  ActivityScope activity("preparing the training run " + run.string());
  TrainConfig config;
  // A run killed (or failed) before its first checkpoint has its config.json but no state:
  // --resume starts it again from step 0 with that config, as the advice below promises.
  const bool haveCheckpoint = fs::exists(checkpointFile(run));
  if (o.resume) {
    if (!fs::exists(run / "config.json"))
      throw Error(run.string(), "has no config.json: not a training run to resume");
    config = readTrainConfig(run / "config.json");
    if (cmd.get_option("--iters")->count() > 0) config.iters = o.config.iters;  // a resumed run may run longer
    if (!haveCheckpoint)
      std::fprintf(stderr, "glint train: %s has no checkpoint yet; starting it from step 0 with its config.json\n",
                   run.string().c_str());
  } else {
    if (fs::exists(run) && !fs::is_directory(run)) throw Error(run.string(), "exists and is not a folder");
    if (fs::exists(run) && !fs::is_empty(run) && !o.force)
      throw Error(run.string(), fs::exists(run / "config.json")
                                    ? "holds a training run; continue it with --resume, choose another -o folder, "
                                      "or pass --force to start over (its files are overwritten)"
                                    : "is not empty and holds no training run; choose another -o folder, or pass "
                                      "--force to write into it");
    config = o.configFile.empty() ? TrainConfig() : readTrainConfig(o.configFile);
    // Explicit flags win over the config file.
    auto given = [&](const char* flag) { return cmd.get_option(flag)->count() > 0; };
    if (given("--iters")) config.iters = o.config.iters;
    if (given("--seed")) config.seed = o.config.seed;
    if (given("--threads")) config.threads = o.config.threads;
    if (given("--bounces")) config.bounces = o.config.bounces;
    if (given("--batch-rays")) config.batchRays = o.config.batchRays;
    if (given("--batch-views")) config.batchViews = o.config.batchViews;
    if (given("--eval-every")) config.evalEvery = o.config.evalEvery;
    if (given("--save-every")) config.saveEvery = o.config.saveEvery;
    if (given("--init")) config.initSource = o.config.initSource;
    if (given("--baseline") && o.config.baseline == "rgb") {
      if (given("--bounces") && o.config.bounces != 0)
        throw Error("command line", "--baseline rgb trains no reflections: leave out --bounces");
      config.baseline = "rgb";
      config.bounces = 0;
      config.loss = LossWeights{.diffuse = config.loss.diffuse, .depth = 0, .normal = 0, .roughness = 0, .f0 = 0,
                                .specular = 0};
    }
    config.dataset = fs::absolute(o.dataset).lexically_normal().string();
    config.validate("command line");
    fs::create_directories(run);
    writeTextAtomically(run / "config.json", toJson(config).dump(2) + "\n");
  }
  if (!o.dataset.empty() && o.resume &&
      fs::absolute(o.dataset).lexically_normal() != fs::path(config.dataset).lexically_normal())
    throw Error(run.string(), "was trained on " + config.dataset + ", not " + o.dataset);

  ThreadLimit threads(config.threads);
  activity.describe("loading the dataset " + config.dataset);
  Dataset dataset = Dataset::open(config.dataset);
  TrainingViews views = TrainingViews::load(dataset, dataset.train(),
                                            config.baseline == "rgb" ? ColourTarget::Render : ColourTarget::Diffuse);
  std::vector<CameraSphere> spheres = cameraSpheres(dataset, dataset.train(), config.prune.cameraSphereFactor);
  TestViews testViews = TestViews::load(dataset, dataset.test(), o.evalViews);

  std::unique_ptr<Trainer> trainer;
  double wallOffset = 0;
  activity.describe("setting up the training of " + run.string());
  if (o.resume && haveCheckpoint) {
    TrainingState state = readCheckpoint(checkpointFile(run));
    TrainConfig saved = config;
    applyJson(nlohmann::json::parse(state.configJson), &saved, checkpointFile(run).string());
    saved.iters = config.iters;
    if (toJson(saved) != toJson(config))
      throw Error(checkpointFile(run).string(), "was written with other settings than " +
                                                    (run / "config.json").string() + "; they must not change");
    std::fprintf(stderr, "glint train: resuming %s at step %lld\n", run.string().c_str(), (long long)state.step);
    wallOffset = truncateLog(run / "log.csv", state.step);
    trainer = std::make_unique<Trainer>(config, views, spheres, std::move(state), o.tracer);
  } else {
    float extent = sceneExtent(dataset.train());
    GaussianScene initial = initialScene(dataset, config);
    trainer = std::make_unique<Trainer>(config, views, spheres, std::move(initial), extent, o.tracer);
    writeTextAtomically(run / "log.csv", kLogHeader);
  }

  // The viewer gets a copy of the scene every viewEvery seconds, taken between steps, and
  // builds its tracer on its own thread: the loop pays only for the copy.
  std::unique_ptr<ViewerServer> viewer;
  auto lastSnapshot = std::chrono::steady_clock::now();
  if (o.view) {
    ViewerOptions options = makeViewerOptions(o.viewer, std::optional<Dataset>(dataset), trainer->scene(), run);
    options.editable = false;
    options.maxSamples = 64;  // the scene changes every few seconds anyway; leave the cores to training
    viewer = std::make_unique<ViewerServer>(std::move(options), trainer->scene(), config.trace);
    viewer->bind();
    viewer->start();
    std::printf("glint train: viewer at %s\n", viewer->url().c_str());
    std::fflush(stdout);
  }

  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
  std::ofstream log(run / "log.csv", std::ios::app);
  auto start = std::chrono::steady_clock::now();
  std::fprintf(stderr, "glint train: %zu Gaussians, %zu training views of %dx%d, %d rays per step, %d threads\n",
               trainer->scene().size(), views.viewCount(), views.width(), views.height(), config.batchRays,
               maxThreads());
  ProgressBar progress("train", config.iters, "steps");
  progress.advance(trainer->stepCount());
  double lastPsnr = NAN;
  DivergenceMonitor divergence(trainer->sceneExtent());
  bool saveDue = false;  // a checkpoint waits while the monitor suspects a collapse
  int64_t lastSaved = trainer->stepCount();
  bool checkpointOnDisk = o.resume && haveCheckpoint;
  while (trainer->stepCount() < config.iters) {
    activity.describe("training step " + std::to_string(trainer->stepCount() + 1) + " of " + run.string());
    StepReport r = trainer->step();
    if (std::optional<std::string> problem = divergence.check(r, trainer->scene())) {
      progress.finish();
      std::string kept = checkpointOnDisk
                             ? "the last good checkpoint (step " + std::to_string(lastSaved) + ") is kept in " +
                                   checkpointFile(run).string()
                             : "no checkpoint was written";
      throw Error(run.string(), "training diverged " + *problem + "; " + kept +
                                    ". Likely cause: learning rates (lr.* in --config) or loss weights too large "
                                    "for this scene; start again with smaller ones");
    }
    double wall = wallOffset + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::string psnrField, normalField;
    if (!testViews.empty() && (r.step % config.evalEvery == 0 || r.step == config.iters)) {
      TestScore score = testViews.score(trainer->tracer(), o.evalSpp);
      lastPsnr = score.diffusePsnr;
      char buf[64];
      std::snprintf(buf, sizeof(buf), "%.3f", score.diffusePsnr);
      psnrField = buf;
      std::snprintf(buf, sizeof(buf), "%.3f", score.normalDegrees);
      normalField = buf;
    }
    char line[512];
    std::snprintf(line, sizeof(line), "%lld,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%zu,%.2f,%.0f,%.2f,%s,%s\n",
                  (long long)r.step, r.loss, r.terms.diffuse, r.terms.depth, r.terms.normal, r.terms.roughness,
                  r.terms.f0, r.terms.specular, r.gaussians, double(r.hits) / double(std::max<int64_t>(r.rays, 1)),
                  double(r.rays) / r.seconds, wall, psnrField.c_str(), normalField.c_str());
    log << line << std::flush;
    char status[200];
    std::snprintf(status, sizeof(status), "loss %.4f | %s Gaussians | %s rays/s%s", r.loss,
                  formatCount(double(r.gaussians)).c_str(), formatCount(double(r.rays) / r.seconds).c_str(),
                  std::isnan(lastPsnr) ? "" : (" | test " + std::to_string(lastPsnr).substr(0, 5) + " dB").c_str());
    progress.setStatus(status);
    progress.advance();
    if (r.farFieldAdded > 0)
      progress.note("reflections on at step " + std::to_string(r.step - 1) + ": " +
                    formatCount(double(r.farFieldAdded)) + " far-field Gaussians added");
    if (r.overflowedRays > 0)
      std::fprintf(stderr, "glint train: warning: %lld rays overflowed their hit list at step %lld\n",
                   (long long)r.overflowedRays, (long long)r.step);
    saveDue = saveDue || r.step % config.saveEvery == 0 || r.step == config.iters;
    if (saveDue && (divergence.clean() || r.step == config.iters)) {
      saveRun(run, *trainer);
      saveDue = false;
      lastSaved = r.step;
      checkpointOnDisk = true;
    }
    auto now = std::chrono::steady_clock::now();
    if (viewer && (std::chrono::duration<double>(now - lastSnapshot).count() >= o.viewEvery || r.step == config.iters)) {
      viewer->showScene(trainer->scene());
      lastSnapshot = now;
    }
    if (gInterrupted) {
      saveRun(run, *trainer);
      progress.finish();
      std::fprintf(stderr, "glint train: interrupted; saved step %lld to %s (continue with --resume)\n",
                   (long long)r.step, checkpointFile(run).string().c_str());
      std::exit(130);
    }
  }
  progress.finish();
  if (trainer->stepCount() >= config.iters && !fs::exists(run / "scene.ply")) saveRun(run, *trainer);
  std::fprintf(stderr, "glint train: done; %zu Gaussians in %s\n", trainer->scene().size(),
               (run / "scene.ply").string().c_str());
  if (viewer) {
    std::fprintf(stderr, "glint train: still serving the final scene at %s (Ctrl-C stops)\n", viewer->url().c_str());
    waitForInterrupt();
  }
}

}  // namespace

void addTrainCommand(CLI::App& app) {
  auto o = std::make_shared<TrainOptions>();
  CLI::App* cmd = app.add_subcommand(
      "train", "Learn a Gaussian scene from a dataset: diffuse and G-buffer supervision of the first segment, then "
               "(after reflection_warmup steps, with --bounces > 0) specular supervision of reflections path-traced "
               "through the Gaussians, with far-field Gaussians added. Writes RUN/config.json, "
               "RUN/log.csv, RUN/scene.ply and a resumable RUN/checkpoint/; Ctrl-C saves and stops.");
  const TrainConfig defaults;
  cmd->add_option("dataset", o->dataset, "Dataset folder (transforms_train.json, train/...); optional with --resume");
  cmd->add_option("-o,--output", o->output, "Run folder to create (or to continue with --resume)")->required();
  cmd->add_option("--iters", o->config.iters, "Training steps")->check(CLI::Range(kItersRange.min, kItersRange.max))->default_val(defaults.iters);
  cmd->add_option("--config", o->configFile, "JSON file of hyper-parameters (the layout of RUN/config.json); flags "
                                             "given explicitly override it")->check(CLI::ExistingFile);
  cmd->add_option("--seed", o->config.seed, "Seed of the ray batches")->default_val(defaults.seed);
  cmd->add_option("--threads", o->config.threads, "Worker threads (0 = all cores); a run is reproducible for a "
                                                  "given seed and thread count")
      ->check(CLI::Range(kThreadsRange.min, kThreadsRange.max))
      ->default_val(defaults.threads);
  cmd->add_option("--bounces", o->config.bounces, "Reflected segments trained with L_r after the warm-up "
                                                  "(reflection_warmup steps); 0 = first segment only")
      ->check(CLI::Range(kBouncesRange.min, kBouncesRange.max))
      ->default_val(defaults.bounces);
  cmd->add_option("--baseline", o->config.baseline,
                  "rgb: the ray-traced RGB-only baseline, for comparison: the same tracer and schedule, the colours "
                  "fitted to the render buffer alone (no G-buffer losses, no reflections); its diffuse pass is its "
                  "output. none: the method")
      ->check(CLI::IsMember({"none", "rgb"}))
      ->default_val(defaults.baseline);
  cmd->add_option("--batch-rays", o->config.batchRays, "Rays per step")
      ->check(CLI::Range(kBatchRaysRange.min, kBatchRaysRange.max))
      ->default_val(defaults.batchRays);
  cmd->add_option("--batch-views", o->config.batchViews, "Training views each step's rays are drawn from")
      ->check(CLI::Range(kBatchViewsRange.min, kBatchViewsRange.max))
      ->default_val(defaults.batchViews);
  cmd->add_option("--eval-every", o->config.evalEvery, "Steps between test-view scores in the log")
      ->check(CLI::Range(kEveryStepsRange.min, kEveryStepsRange.max))
      ->default_val(defaults.evalEvery);
  cmd->add_option("--eval-views", o->evalViews, "Test views scored during training (evenly spaced; 0 = none)")
      ->check(CLI::Range(0, 100000))
      ->default_val(o->evalViews);
  cmd->add_option("--eval-spp", o->evalSpp, "Jittered samples per pixel of the logged test diffuse PSNR (glint eval "
                                             "uses 16)")
      ->check(CLI::Range(1, 1024))
      ->default_val(o->evalSpp);
  cmd->add_option("--save-every", o->config.saveEvery, "Steps between checkpoints (and scene.ply)")
      ->check(CLI::Range(kEveryStepsRange.min, kEveryStepsRange.max))
      ->default_val(defaults.saveEvery);
  cmd->add_option("--init", o->config.initSource, "Initialisation: auto (point_cloud_dense.ply if present, else "
                                                   "the depth buffers), depth, point-cloud")
      ->check(CLI::IsMember({"auto", "depth", "point-cloud"}))
      ->default_val(defaults.initSource);
  cmd->add_option("--tracer", o->tracer, "Gaussian tracer (fast, embree-k16, reference)")->default_val(o->tracer);
  cmd->add_flag("--view", o->view, "Serve the viewer page (as glint view, without editing) showing the scene as it "
                                   "trains; the URL is printed");
  cmd->add_option("--view-port", o->viewer.port, "Port of --view (0 = any free port)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  cmd->add_option("--view-host", o->viewer.host, "Address of --view (a warning unless loopback)")->capture_default_str();
  cmd->add_option("--view-res", o->viewer.resolution, "Image size of --view WIDTHxHEIGHT (default: the dataset's, "
                                                      "at most 640 wide)");
  cmd->add_option("--view-every", o->viewEvery, "Seconds between the snapshots --view shows")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  cmd->add_flag("--resume", o->resume, "Continue the run in -o from its checkpoint, exactly as if never stopped");
  cmd->add_flag("--force", o->force, "Start a new run in a non-empty -o folder (its files are overwritten)");
  cmd->callback([o, cmd]() {
    if (!o->resume && o->dataset.empty()) throw Error("glint train", "needs a DATASET folder (or --resume)");
    runTrain(*o, *cmd);
  });
}

}  // namespace glint
