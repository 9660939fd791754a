// `glint train DATASET -o RUN`: learns a Gaussian scene from a dataset. The run folder holds
// config.json (every hyper-parameter), log.csv, scene.ply and a resumable checkpoint; the
// loop itself is train/training_loop.h: this file parses the flags and prints.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>

#include "app/commands.h"
#include "app/dataset_flags.h"
#include "app/thread_flag.h"
#include "app/trace_flags.h"
#include "app/viewer/viewer_setup.h"
#include "core/cluster.h"
#include "core/error.h"
#include "core/folder_lock.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "raytrace/gaussian_tracer.h"
#include "tracers/compute_device.h"
#include "train/run_folder.h"
#include "train/train_config.h"
#include "train/training_loop.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

struct TrainOptions {
  std::string dataset;
  std::string output;
  std::string configFile;
  bool force = false;
  TrainingSession session;
  std::string baseline;    // the words of --baseline and --init (train/config_choices.h)
  std::string initSource;
  std::string exchange = "dense";  // the word of --exchange
  bool view = false;       // serve the viewer page showing the scene as it trains
  bool keepServing = false;  // ... and go on serving the final scene after training
  ViewerFlags viewer;
  DatasetFlags reading;    // --downscale, --background
  double viewEvery = 2.0;  // seconds between the snapshots the viewer shows
  TrainConfig config;  // defaults, overridden by --config, then by explicit flags
  std::string device = "cpu";  // the word of --device
};

std::atomic<bool> gInterrupted{false};
extern "C" void onInterrupt(int) { gInterrupted = true; }

// In an MPI job the launcher ends the other ranks with SIGTERM when one fails; they may be
// waiting in a collective for it and could never reach a step's end, so rank 0 says what
// happened and where the run stands, and exits at once (the checkpoint on disk is whole:
// it is written atomically). Ctrl-C (SIGINT) still stops at the next step and saves.
char gJobEndedMessage[1024] = "";
extern "C" void onJobEnded(int) {
  ssize_t written = write(STDERR_FILENO, gJobEndedMessage, std::strlen(gJobEndedMessage));
  (void)written;
  _exit(143);
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

// The RGB-only baseline: colours fitted to the final images, no G-buffer losses, no reflections.
void useRgbBaseline(TrainConfig* config) {
  config->baseline = Baseline::Rgb;
  config->bounces = 0;
  config->loss = LossWeights{.diffuse = config->loss.diffuse, .depth = 0, .normal = 0, .roughness = 0, .f0 = 0,
                             .specular = 0};
}

// True when a synthetic dataset's first training view has its final image and nothing else
// (the NeRF-synthetic layout): no diffuse, specular or G-buffers for the method to train on.
// A real capture's photographs train the method, with its sparse points for the geometry
// (docs/capture-format.md).
// What decides a new run's defaults about its dataset.
struct DatasetTraits {
  bool finalImagesOnly = false;   // no diffuse, specular or G-buffers: the RGB-only baseline
  bool predictedBuffers = false;  // a capture whose buffers a network predicted
};

DatasetTraits datasetTraits(const TrainConfig& config) {
  const Dataset dataset = Dataset::open(config.dataset, config.datasetReading(/*requireBuffers=*/true));
  const DatasetSplit& train = dataset.split("train");
  bool anyBuffer = false;
  for (Buffer b : kAllBuffers)
    if (b != Buffer::Render && dataset.findBufferFile(train.views[0], b)) anyBuffer = true;
  const CaptureSource* capture = dataset.capture();
  DatasetTraits traits;
  traits.predictedBuffers = capture && capture->decoding.predictedPriors && anyBuffer;
  traits.finalImagesOnly =
      !anyBuffer && !(capture && !capture->alphaBackground && !capture->priorTransforms);
  return traits;
}

// The config of a new run: the defaults, then --config, then the flags given.
TrainConfig newRunConfig(const TrainOptions& o, const CLI::App& cmd) {
  TrainConfig config = o.configFile.empty() ? TrainConfig() : readTrainConfig(o.configFile);
  auto given = [&](const char* flag) { return cmd.get_option(flag)->count() > 0; };
  if (given("--iters")) config.iters = o.config.iters;
  if (given("--holdout")) config.holdout = o.config.holdout;
  if (given("--seed")) config.seed = o.config.seed;
  if (given("--threads")) config.threads = o.config.threads;
  if (given("--bounces")) config.bounces = o.config.bounces;
  if (given("--batch-rays")) config.batchRays = o.config.batchRays;
  if (given("--batch-views")) config.batchViews = o.config.batchViews;
  if (given("--batch-images")) config.batchImages = o.config.batchImages;
  if (config.batchImages > 0 && (given("--batch-rays") || given("--batch-views")))
    throw Error(o.configFile, "batch_images is " + std::to_string(config.batchImages) +
                                  ": steps take whole views, so --batch-rays and --batch-views would do nothing "
                                  "(give \"batch_images\": 0 for random pixels)");
  if (given("--eval-every")) config.evalEvery = o.config.evalEvery;
  if (given("--save-every")) config.saveEvery = o.config.saveEvery;
  if (given("--init")) config.initSource = *choiceFromName<InitChoice>(o.initSource);  // IsMember checked it
  o.reading.applyTo(&config);
  config.dataset = fs::absolute(o.dataset).lexically_normal().string();
  // Opening the dataset here refuses a broken one before the run folder is made. One with
  // final images only trains the RGB-only baseline unless --baseline says otherwise: the
  // method has nothing to separate reflections with.
  const DatasetTraits traits = datasetTraits(config);
  if (traits.predictedBuffers && o.configFile.empty()) {
    usePredictedBufferSetting(&config);
    if (given("--bounces")) config.bounces = o.config.bounces;
    std::fprintf(stderr, "glint train: %s holds predicted buffers (capture.json \"priors\"): training with the "
                 "real-capture setting (no depth loss, specular weight 0.01); --config overrides it\n",
                 o.dataset.c_str());
  }
  const bool autoRgb = !given("--baseline") && config.baseline == Baseline::None && traits.finalImagesOnly;
  if (autoRgb || (given("--baseline") && choiceFromName<Baseline>(o.baseline) == Baseline::Rgb)) {
    if (given("--bounces") && o.config.bounces != 0)
      throw Error("command line", autoRgb ? o.dataset + " has final images only, which train the RGB-only baseline "
                                                        "(no reflections): leave out --bounces, or pass --baseline none"
                                          : "--baseline rgb trains no reflections: leave out --bounces");
    useRgbBaseline(&config);
    if (autoRgb)
      std::fprintf(stderr, "glint train: %s has final images only (no diffuse, specular or G-buffers): training "
                   "the RGB-only baseline, as --baseline rgb\n", o.dataset.c_str());
  }
  config.validate("command line");
  return config;
}

// Prints the loop's progress, serves the live viewer and passes Ctrl-C on.
class TrainPrinter : public TrainingObserver {
 public:
  TrainPrinter(const TrainOptions& o, const TrainConfig& config, const RunFolder& run)
      : o_(o), config_(config), run_(run) {}

  void note(const std::string& message) override {
    if (progress_)
      progress_->note(message);
    else
      std::fprintf(stderr, "glint train: %s\n", message.c_str());
  }

  void started(const Trainer& trainer, const Dataset& dataset, const TrainingViews& views) override {
    // The viewer gets a copy of the scene every viewEvery seconds, taken between steps, and
    // builds its tracer on its own thread: the loop pays only for the copy.
    if (o_.view && run_.writes()) {
      ViewerOptions options = makeViewerOptions(o_.viewer, std::optional<Dataset>(dataset), trainer.scene(),
                                                run_.root());
      options.editable = false;
      options.maxSamples = 64;  // the scene changes every few seconds anyway; leave the cores to training
      options.path = config_.path();
      viewer_ = std::make_unique<ViewerServer>(std::move(options), trainer.scene(), config_.trace);
      viewer_->bind();
      viewer_->start();
      std::printf("glint train: viewer at %s\n", viewer_->url().c_str());
      std::fflush(stdout);
      lastSnapshot_ = std::chrono::steady_clock::now();
    }
    std::signal(SIGINT, onInterrupt);
    if (cluster::distributed()) {
      std::snprintf(gJobEndedMessage, sizeof(gJobEndedMessage),
                    "\nglint train: the MPI job was ended (a rank failed or was killed, or the job was cancelled); "
                    "the last checkpoint is %s (written every %d steps): continue with `glint train --resume -o %s`, "
                    "with any number of ranks\n",
                    run_.checkpointFile().string().c_str(), config_.saveEvery, run_.root().string().c_str());
      std::signal(SIGTERM, onJobEnded);
    } else {
      std::signal(SIGTERM, onInterrupt);
    }
    const std::string workers = cluster::distributed()
                                    ? std::to_string(cluster::size()) + " MPI ranks of " + std::to_string(maxThreads()) +
                                          " threads (each traces 1/" + std::to_string(cluster::size()) + " of the rays)"
                                    : std::to_string(maxThreads()) + " threads";
    const std::string batch =
        config_.batchImages > 0
            ? "every pixel of " + std::to_string(std::min<size_t>(size_t(config_.batchImages), views.viewCount())) +
                  (config_.batchImages == 1 ? " view" : " views") + " per step"
            : std::to_string(config_.batchRays) + " rays per step";
    std::fprintf(stderr, "glint train: %zu Gaussians, %zu training views (the first %dx%d), %s, %s\n",
                 trainer.scene().size(), views.viewCount(), views.camera(0).width, views.camera(0).height,
                 batch.c_str(), workers.c_str());
    const PruneSettings& prune = config_.prune;
    const int64_t viewsPerInterval = int64_t(prune.every) * int64_t(config_.batchImages);
    if (config_.batchImages > 0 && viewsPerInterval < int64_t(views.viewCount()) && prune.start < config_.iters)
      std::fprintf(stderr,
                   "glint train: warning: a pruning interval (prune.every = %d steps of %d %s) sees %lld of the %zu "
                   "training views, so a Gaussian that only the others see is pruned; prune.every of at least %lld "
                   "sees them all\n",
                   prune.every, config_.batchImages, config_.batchImages == 1 ? "view" : "views",
                   (long long)viewsPerInterval, views.viewCount(),
                   (long long)((int64_t(views.viewCount()) + config_.batchImages - 1) / config_.batchImages));
    const SupervisedBuffers& s = views.supervised();
    if (s.finalColour)
      std::fprintf(stderr, "glint train: colours fitted to the final (render) images%s\n",
                   config_.bounces > 0 ? " as diffuse plus the paths' specular" : "");
    if (s.photograph)
      std::fprintf(stderr,
                   "glint train: diffuse plus specular also fitted to the photographs (loss.photograph %g) once "
                   "reflections train\n",
                   double(config_.loss.photograph));
    if (!s.list(false).empty())
      std::fprintf(stderr, "glint train: the dataset has no %s buffers: training without their losses\n",
                   s.list(false).c_str());
    progress_ = std::make_unique<ProgressBar>("train", config_.iters, "steps");
    progress_->resumeAt(trainer.stepCount());  // the rate and ETA count this session's steps only
    onGpu_ = isGpuTracer(trainer.tracer().name());
  }

  void stepped(const StepReport& r, const std::optional<TestScore>& score) override {
    if (score) lastPsnr_ = score->diffusePsnr;
    // On the GPU, the memory in use on it (all processes'), asked at most once a second.
    const auto now = std::chrono::steady_clock::now();
    if (onGpu_ && now - lastGpuQuery_ >= std::chrono::seconds(1)) {
      lastGpuQuery_ = now;
      std::string why;
      if (const std::optional<GpuInfo> gpu = findGpu(&why)) {
        char text[48];
        std::snprintf(text, sizeof text, " | GPU %.1f/%.0f GiB", double(gpu->totalBytes - gpu->freeBytes) / 1073741824.0,
                      double(gpu->totalBytes) / 1073741824.0);
        gpuMemory_ = text;
      }
    }
    char status[240];
    std::snprintf(status, sizeof(status), "loss %.4f | %s Gaussians | %s rays/s%s%s", r.loss,
                  formatCount(double(r.gaussians)).c_str(), formatCount(double(r.rays) / r.seconds).c_str(),
                  gpuMemory_.c_str(),
                  std::isnan(lastPsnr_) ? "" : (" | test " + std::to_string(lastPsnr_).substr(0, 5) + " dB").c_str());
    progress_->setStatus(status);
    progress_->advance();
    if (r.farFieldAdded > 0)
      progress_->note("reflections on at step " + std::to_string(r.step - 1) + ": " +
                      formatCount(double(r.farFieldAdded)) + " far-field Gaussians added (" +
                      formatCount(double(r.reflectionSeedsAdded)) + " of them seeded along mirror reflections)");
    if (r.overflowedRays > 0)
      std::fprintf(stderr, "glint train: warning: %lld rays overflowed their hit list at step %lld\n",
                   (long long)r.overflowedRays, (long long)r.step);
  }

  void betweenSteps(const Trainer& trainer, const StepReport& r) override {
    auto now = std::chrono::steady_clock::now();
    if (viewer_ && (std::chrono::duration<double>(now - lastSnapshot_).count() >= o_.viewEvery ||
                    r.step == config_.iters)) {
      viewer_->showScene(trainer.scene());
      lastSnapshot_ = now;
    }
  }

  bool stopRequested() override { return gInterrupted; }

  // Ends the progress line before the closing messages.
  void finish() {
    if (progress_) progress_->finish();
  }
  ViewerServer* viewer() { return viewer_.get(); }
  // Whether the loop got as far as its first step (the dataset loaded, the scene set up).
  bool hasStarted() const { return progress_ != nullptr; }

 private:
  const TrainOptions& o_;
  const TrainConfig& config_;
  const RunFolder& run_;
  std::unique_ptr<ProgressBar> progress_;
  std::unique_ptr<ViewerServer> viewer_;
  std::chrono::steady_clock::time_point lastSnapshot_;
  double lastPsnr_ = NAN;
  bool onGpu_ = false;
  std::chrono::steady_clock::time_point lastGpuQuery_;
  std::string gpuMemory_;  // " | GPU 1.2/79 GiB", or empty on the CPU
};

// The run's settings at its start, as config.json holds them (floats as written), one line
// per setting or section, so a log of the run says what it ran with.
void printSettings(const TrainConfig& config, const RunFolder& run) {
  std::fprintf(stderr, "glint train: settings (%s):\n", run.configFile().string().c_str());
  const nlohmann::json settings = toJson(config);
  for (auto it = settings.begin(); it != settings.end(); ++it)
    std::fprintf(stderr, "  %s: %s\n", it.key().c_str(), it.value().dump().c_str());
}

void runTrain(const TrainOptions& o, const CLI::App& cmd) {
  const RunFolder run(o.output);
  if (fs::exists(run.root()) && !fs::is_directory(run.root()))
    throw Error(run.root().string(), "exists and is not a folder");
  const bool folderExisted = fs::exists(run.root());
  if (o.session.resume && !run.hasConfig())
    throw Error(run.root().string(), "has no config.json: not a training run to resume");
  if (!o.session.resume) run.checkCanCreate(o.force);  // before the lock file goes in
  // A new run's settings are read and checked before anything is written: a bad --config
  // leaves no run folder behind.
  TrainConfig config;
  if (!o.session.resume) config = newRunConfig(o, cmd);
  // One writer per run folder: a second `train` (or a viewer saving into it) is refused with
  // the holder's PID. In an MPI job the rank that writes alone locks.
  std::unique_ptr<FolderLock> lock = run.lockForWriting("glint train");
  if (o.session.resume) {
    config = run.readConfig();  // after the lock: no other writer is changing it
    if (cmd.get_option("--iters")->count() > 0) config.iters = o.config.iters;  // a resumed run may run longer
    // A run killed (or failed) before its first checkpoint has its config.json but no
    // state: it starts again from step 0 with that config.
    if (!run.hasCheckpoint())
      std::fprintf(stderr, "glint train: %s has no checkpoint yet; starting it from step 0 with its config.json\n",
                   run.root().string().c_str());
    if (!o.dataset.empty() &&
        fs::absolute(o.dataset).lexically_normal() != fs::path(config.dataset).lexically_normal())
      throw Error(run.root().string(), "was trained on " + config.dataset + ", not " + o.dataset);
  }
  // A new run that fails before its first step (a broken dataset, a bad setting) takes back
  // what it wrote, so that the retry is not refused; only from a folder that held nothing
  // else, and the folder itself only if this start made it.
  bool undoFailedStart = false, madeFolder = false;
  if (!o.session.resume) {
    madeFolder = !folderExisted;
    undoFailedStart = madeFolder || (fs::is_directory(run.root()) && isEmptyButForLock(run.root())) ||
                      run.isUnfinishedStart();
    if (run.isUnfinishedStart())
      std::fprintf(stderr, "glint train: %s holds a start that never saved a checkpoint; starting afresh (its "
                   "config.json and log.csv are replaced)\n", run.root().string().c_str());
    run.create(config, o.force);  // by the rank that writes; the others only read the dataset
    undoFailedStart = undoFailedStart && run.writes();
  }

  if (run.writes()) printSettings(config, run);
  TrainPrinter printer(o, config, run);
  TrainingOutcome outcome;
  try {
    TrainingSession session = o.session;
    session.tracer = resolveTracerForDevice(o.device, o.session.tracer, cmd.get_option("--tracer")->count() > 0,
                                            "glint train");
    outcome = trainRun(run, config, session, printer);
  } catch (...) {
    if (undoFailedStart && !printer.hasStarted()) run.removeFailedStart(madeFolder);
    throw;
  }
  printer.finish();
  if (outcome.stopped) {
    std::fprintf(stderr, "glint train: interrupted; saved step %lld to %s (continue with --resume)\n",
                 (long long)outcome.step, run.checkpointFile().string().c_str());
    cluster::leave();
    std::exit(130);
  }
  std::fprintf(stderr, "glint train: done; %zu Gaussians in %s\n", outcome.gaussians,
               run.sceneFile().string().c_str());
  if (printer.viewer() && o.keepServing) {
    std::fprintf(stderr, "glint train: still serving the final scene at %s (Ctrl-C stops)\n",
                 printer.viewer()->url().c_str());
    waitForInterrupt();
  } else if (printer.viewer()) {
    printer.viewer()->stop();
    std::fprintf(stderr, "glint train: the viewer has stopped (--keep-serving keeps it serving the final scene)\n");
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
  cmd->add_option("--iters", o->config.iters, "Training steps (with --resume: the run's, unless given; the other "
                                                "settings of a resumed run are always its config.json's)")
      ->check(CLI::Range(kItersRange.min, kItersRange.max))
      ->default_val(defaults.iters);
  cmd->add_option("--holdout", o->config.holdout,
                  "For a capture without a train/test split (COLMAP or nerfstudio): every N-th image, from the "
                  "first, is a test view (LLFF's convention); render, eval and report use the run's")
      ->check(CLI::Range(kHoldoutRange.min, kHoldoutRange.max))
      ->default_val(defaults.holdout);
  cmd->add_option("--config", o->configFile,
                  "JSON file of hyper-parameters (the layout of RUN/config.json); flags given explicitly override it. "
                  "A capture with predicted buffers (capture.json \"priors\": \"predicted\", the default) "
                  "trains without a config file with the paper's setting for them (no depth loss, specular weight "
                  "0.01; scripts/real-capture-train.json), which measured 2.7 dB better than the defaults on "
                  "COLMAP cameras; a --config replaces it")
      ->check(CLI::ExistingFile);
  o->reading.add(cmd, /*withBackground=*/true);
  cmd->add_option("--seed", o->config.seed, "Seed of the ray batches")->default_val(defaults.seed);
  addThreadsFlag(cmd, &o->config.threads, "a run is reproducible for a given seed and thread count");
  cmd->add_option("--bounces", o->config.bounces, "Reflected segments trained with L_r after the warm-up "
                                                  "(reflection_warmup steps); 0 = first segment only")
      ->check(CLI::Range(kBouncesRange.min, kBouncesRange.max))
      ->default_val(defaults.bounces);
  cmd->add_option("--baseline", o->baseline,
                  "rgb: the ray-traced RGB-only baseline, for comparison: the same tracer and schedule, the colours "
                  "fitted to the render buffer alone (no G-buffer losses, no reflections); its diffuse pass is its "
                  "output; it needs the final images only. none: the method. Default: rgb for a dataset with final "
                  "images only (NeRF-synthetic), else none")
      ->check(CLI::IsMember(choiceNames<Baseline>()));
  cmd->add_option("--batch-rays", o->config.batchRays, "Rays per step")
      ->check(CLI::Range(kBatchRaysRange.min, kBatchRaysRange.max))
      ->default_val(defaults.batchRays);
  CLI::Option* batchRays = cmd->get_option("--batch-rays");
  CLI::Option* batchViews =
      cmd->add_option("--batch-views", o->config.batchViews, "Training views each step's rays are drawn from")
          ->check(CLI::Range(kBatchViewsRange.min, kBatchViewsRange.max))
          ->default_val(defaults.batchViews);
  cmd->add_option("--batch-images", o->config.batchImages,
                  "Whole-image batches (the paper's protocol): each step traces every pixel of N training views, "
                  "each view once per epoch in a seeded order, in place of --batch-rays random pixels of "
                  "--batch-views views; 0 = random pixels")
      ->check(CLI::Range(kBatchImagesRange.min, kBatchImagesRange.max))
      ->default_val(defaults.batchImages)
      ->excludes(batchRays)
      ->excludes(batchViews);
  cmd->add_option("--eval-every", o->config.evalEvery, "Steps between test-view scores in the log")
      ->check(CLI::Range(kEveryStepsRange.min, kEveryStepsRange.max))
      ->default_val(defaults.evalEvery);
  cmd->add_option("--eval-views", o->session.evalViews, "Test views scored during training (evenly spaced; 0 = none)")
      ->check(CLI::Range(0, 100000))
      ->default_val(o->session.evalViews);
  cmd->add_option("--eval-spp", o->session.evalSpp, "Jittered samples per pixel of the logged test diffuse PSNR (glint eval "
                                             "uses 16)")
      ->check(CLI::Range(1, 1024))
      ->default_val(o->session.evalSpp);
  cmd->add_option("--save-every", o->config.saveEvery, "Steps between checkpoints (and scene.ply)")
      ->check(CLI::Range(kEveryStepsRange.min, kEveryStepsRange.max))
      ->default_val(defaults.saveEvery);
  cmd->add_option("--init", o->initSource, "Initialisation: auto (point_cloud_dense.ply if present, else "
                                                   "the depth buffers), depth, point-cloud")
      ->check(CLI::IsMember(choiceNames<InitChoice>()))
      ->default_val(choiceName(defaults.initSource));
  cmd->add_option("--tracer", o->session.tracer,
                  "Gaussian tracer (fast, embree-k16, reference; cuda or cuda-warp on the GPU)")
      ->default_val(o->session.tracer);
  cmd->add_option("--device", o->device,
                  "Where training traces its paths: cpu, cuda (the GPU traces every wavefront of a step and its "
                  "test-view scores; the backward pass, Adam and the schedule stay on the CPU; an error without "
                  "a GPU), or auto (the GPU when one is present). Default cpu until the GPU's step is measured "
                  "(docs/gpu.md). A run's checkpoint resumes on either device")
      ->check(CLI::IsMember(deviceRequestNames()))
      ->default_val(o->device);
  cmd->add_option("--exchange", o->exchange,
                  "Under MPI (mpirun/srun): how the ranks sum their gradients each step. dense: every Gaussian's "
                  "(measured faster here and through shared memory); sparse: only those the rank's rays touched, "
                  "2.4-4.4x fewer bytes, modelled faster at 500k Gaussians on 10 Gbit/s networks (README, Running "
                  "on a cluster). Both give identical results")
      ->check(CLI::IsMember({"dense", "sparse"}))
      ->capture_default_str();
  CLI::Option* viewFlag = cmd->add_flag("--view", o->view,
                                        "Serve the viewer page (as glint view, without editing) showing the scene as "
                                        "it trains; the URL is printed");
  cmd->add_option("--view-port", o->viewer.port, "Port of --view (0 = any free port)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  cmd->add_option("--view-host", o->viewer.host, "Address of --view (a warning unless loopback)")->capture_default_str();
  cmd->add_option("--view-res", o->viewer.resolution, "Image size of --view WIDTHxHEIGHT (default: the dataset's, "
                                                      "at most 640 wide)");
  cmd->add_option("--view-every", o->viewEvery, "Seconds between the snapshots --view shows")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  cmd->add_flag("--keep-serving", o->keepServing,
                "With --view: go on serving the final scene after training, until Ctrl-C (without it the viewer "
                "stops when training ends)")
      ->needs(viewFlag);
  cmd->add_flag("--resume", o->session.resume, "Continue the run in -o from its checkpoint, exactly as if never stopped");
  cmd->add_flag("--force", o->force, "Start a new run in a non-empty -o folder (its files are overwritten)");
  cmd->callback([o, cmd]() {
    if (!o->session.resume && o->dataset.empty()) throw Error("glint train", "needs a DATASET folder (or --resume)");
    o->session.exchange = o->exchange == "sparse" ? ExchangeMode::Sparse : ExchangeMode::Dense;
    runTrain(*o, *cmd);
  });
}

}  // namespace glint
