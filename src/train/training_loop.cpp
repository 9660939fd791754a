// The training loop: set-up, steps, test-view scores, log rows, checkpoints.
#include "train/training_loop.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include "core/activity.h"
#include "core/atomic_file.h"
#include "core/cluster.h"
#include "core/error.h"
#include "core/parallel.h"
#include "eval/training_log.h"
#include "io/tensorboard_events.h"
#include "scene/capture_summary.h"
#include "scene/gaussian_ply.h"
#include "train/camera_culling.h"
#include "train/camera_refinement.h"
#include "train/checkpoint.h"
#include "train/dense_init.h"
#include "train/depth_consistency.h"
#include "train/divergence_monitor.h"
#include "train/scene_extent.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

constexpr const char* kLogHeader =
    "step,loss,diffuse_l1,depth_l1,normal_l1,roughness_l1,f0_l1,specular_l1,gaussians,hits_per_ray,rays_per_s,wall_s,"
    "test_diffuse_psnr,test_normal_deg\n";

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

// The row's figures as TensorBoard scalars, under the names of log.csv's columns.
void writeScalars(TensorBoardWriter& board, const StepReport& r, const std::optional<TestScore>& score) {
  board.scalar("loss", r.step, r.loss);
  board.scalar("loss/diffuse_l1", r.step, r.terms.diffuse);
  board.scalar("loss/depth_l1", r.step, r.terms.depth);
  board.scalar("loss/normal_l1", r.step, r.terms.normal);
  board.scalar("loss/roughness_l1", r.step, r.terms.roughness);
  board.scalar("loss/f0_l1", r.step, r.terms.f0);
  board.scalar("loss/specular_l1", r.step, r.terms.specular);
  if (r.terms.photograph != 0) board.scalar("loss/photograph_l1", r.step, r.terms.photograph);
  // How far the roughness priors sit from the model's (train/roughness_shift.h): a
  // predictor's bias shows here.
  board.scalar("roughness_prior_offset", r.step, r.roughnessOffset);
  board.scalar("gaussians", r.step, float(r.gaussians));
  board.scalar("hits_per_ray", r.step, float(double(r.hits) / double(std::max<int64_t>(r.rays, 1))));
  board.scalar("rays_per_s", r.step, float(double(r.rays) / r.seconds));
  if (score) {
    board.scalar("test/diffuse_psnr", r.step, float(score->diffusePsnr));
    board.scalar("test/normal_deg", r.step, float(score->normalDegrees));
  }
  board.flush();
}

// One row of log.csv; the test columns are empty on steps without a score.
std::string logRow(const StepReport& r, double wall, const std::optional<TestScore>& score) {
  std::string psnrField, normalField;
  if (score) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.3f", score->diffusePsnr);
    psnrField = buf;
    std::snprintf(buf, sizeof(buf), "%.3f", score->normalDegrees);
    normalField = buf;
  }
  char line[512];
  std::snprintf(line, sizeof(line), "%lld,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%zu,%.2f,%.0f,%.2f,%s,%s\n",
                (long long)r.step, r.loss, r.terms.diffuse, r.terms.depth, r.terms.normal, r.terms.roughness,
                r.terms.f0, r.terms.specular, r.gaussians, double(r.hits) / double(std::max<int64_t>(r.rays, 1)),
                double(r.rays) / r.seconds, wall, psnrField.c_str(), normalField.c_str());
  return line;
}

GaussianScene initialScene(const Dataset& dataset, const TrainConfig& config, const TrainingViews& views,
                           TrainingObserver& observer) {
  DenseInitSettings settings = config.init;
  settings.forceDepthBuffers = config.initSource == InitChoice::DepthBuffers;
  DepthTrust trusted;
  if (config.initConsistentDepthOnly && views.supervised().depth)
    trusted = [&views](size_t view, size_t pixel) { return views.depthTrusted(view, pixel); };
  DenseInit init = config.initSource == InitChoice::PointCloud ? initFromPointCloud(dataset, settings)
                                                                : denseInitialisation(dataset, settings, trusted);
  const DenseInitStats& st = init.stats;
  char voxelNote[96] = "";
  if (st.depthResidual > 0.0f && st.voxelSize <= settings.depthResidualVoxels * st.depthResidual)
    std::snprintf(voxelNote, sizeof(voxelNote), " = %gx the depth fits' median residual",
                  double(settings.depthResidualVoxels));
  char message[400];
  if (st.source == InitSource::CameraVolume)
    std::snprintf(message, sizeof(message),
                  "initialised %zu Gaussians at random in the volume the cameras look at (no depth buffers or points)"
                  "%s",
                  init.scene.size(),
                  st.shellGaussians > 0 ? (", " + std::to_string(st.shellGaussians) + " of them a shell in the "
                                           "background colour").c_str()
                                        : "");
  else if (st.source == InitSource::SparsePoints)
    std::snprintf(message, sizeof(message), "initialised %zu Gaussians from the capture's sparse points (%lld points)",
                  init.scene.size(), (long long)st.pointsUnprojected);
  else if (st.source == InitSource::PointCloud)
    std::snprintf(message, sizeof(message), "initialised %zu Gaussians from point_cloud_dense.ply (%lld points)",
                  init.scene.size(), (long long)st.pointsUnprojected);
  else
    std::snprintf(message, sizeof(message),
                  "initialised %zu Gaussians from the depth buffers (stride %d, %lld samples%s, voxel %.4g%s, %lld of "
                  "%lld voxels kept)",
                  init.scene.size(), st.pixelStride, (long long)st.pointsUnprojected,
                  st.samplesUntrusted > 0 ? (", " + std::to_string(st.samplesUntrusted) +
                                             " more the consistency check does not trust left out").c_str()
                                          : "",
                  st.voxelSize, voxelNote, (long long)st.voxelsKept, (long long)st.voxelsOccupied);
  observer.note(message);
  return std::move(init.scene);
}

// Whether a dataset's normal targets came from camera-space priors, which turn with a
// refined camera (TrainingViews::setCamera).
bool normalsFromCamera(const Dataset& dataset) {
  return dataset.capture() && !dataset.capture()->decoding.worldNormals;
}

// The trainer's state with the training views' poses, when refinement moved them.
TrainingState runState(const Trainer& trainer, const TrainingViews& views) {
  TrainingState state = trainer.state();
  if (views.camerasMoved())
    for (size_t v = 0; v < views.viewCount(); ++v) state.cameraPoses.push_back(views.camera(v).cameraToWorld);
  return state;
}

// Puts a checkpoint's refined poses back on the training views.
void restoreCameraPoses(const TrainingState& state, const Dataset& dataset, TrainingViews* views,
                        const std::string& source) {
  if (state.cameraPoses.empty()) return;
  if (state.cameraPoses.size() != views->viewCount())
    throw Error(source, "holds " + std::to_string(state.cameraPoses.size()) + " refined camera poses for " +
                            std::to_string(views->viewCount()) + " training views (was the dataset changed?)");
  for (size_t v = 0; v < views->viewCount(); ++v) {
    Camera camera = views->camera(v);
    camera.cameraToWorld = state.cameraPoses[v];
    views->setCamera(v, camera, normalsFromCamera(dataset));
  }
}

// Runs the multi-view depth check (TrainConfig::loss.depthConsistency) over the views'
// current cameras and says what it kept.
void keepConsistentDepthAndSay(const TrainConfig& config, const RunFolder& run, TrainingViews* views,
                           TrainingObserver& observer) {
  const DepthConsistency found = views->keepConsistentDepth(
      {.tolerance = config.loss.depthConsistency, .minAgreeing = config.loss.depthConsistencyViews});
  char message[300];
  std::snprintf(message, sizeof(message),
                "depth consistency: %.1f%% of the depth pixels agree with %d or more of their view's %d "
                "neighbours within %g%%; the depth term leaves out the other %lld",
                found.depthPixels > 0 ? 100.0 * double(found.trustedPixels) / double(found.depthPixels) : 0.0,
                config.loss.depthConsistencyViews, kDepthConsistencyNeighbours,
                100.0 * double(config.loss.depthConsistency), (long long)(found.depthPixels - found.trustedPixels));
  if (run.writes()) observer.note(message);
}

void saveRun(const RunFolder& run, const Trainer& trainer, const TrainingViews& views) {
  if (!run.writes()) return;
  writeCheckpoint(run.checkpointFile(), runState(trainer, views));
  writeGaussianPly(run.sceneFile(), trainer.scene());
}

// The trainer of a run: from its checkpoint when resuming one (the settings it was
// written with must be the config's but for iters), else from the dense initialisation,
// with log.csv started or cut back to the checkpoint. Returns the wall time already spent.
double setUpTrainer(const RunFolder& run, const TrainConfig& config, const TrainingSession& session,
                    const Dataset& dataset, TrainingViews& views, std::vector<CameraSphere> spheres,
                    TrainingObserver& observer, std::unique_ptr<Trainer>* trainer) {
  if (session.resume && run.hasCheckpoint()) {
    TrainingState state = readCheckpoint(run.checkpointFile());
    TrainConfig saved = config;
    applyJson(nlohmann::json::parse(state.configJson), &saved, run.checkpointFile().string());
    saved.iters = config.iters;
    if (toJson(saved) != toJson(config))
      throw Error(run.checkpointFile().string(),
                  "was written with other settings than " + run.configFile().string() + "; they must not change");
    observer.note("resuming " + run.root().string() + " at step " + std::to_string(state.step));
    double wallOffset = truncateLog(run.logFile(), state.step);
    restoreCameraPoses(state, dataset, &views, run.checkpointFile().string());
    if (views.camerasMoved() && config.loss.depthConsistency > 0 && views.supervised().depth)
      keepConsistentDepthAndSay(config, run, &views, observer);
    *trainer = std::make_unique<Trainer>(config, views, std::move(spheres), std::move(state), session.tracer);
    return wallOffset;
  }
  float extent = sceneExtent(dataset.train());
  GaussianScene initial = initialScene(dataset, config, views, observer);
  *trainer = std::make_unique<Trainer>(config, views, std::move(spheres), std::move(initial), extent, session.tracer);
  writeTextAtomically(run.logFile(), kLogHeader);
  return 0;
}

}  // namespace

TrainingOutcome trainRun(const RunFolder& run, const TrainConfig& config, const TrainingSession& session,
                         TrainingObserver& observer) {
  ActivityScope activity("preparing the training run " + run.root().string());
  ThreadLimit threads(config.threads);
  activity.describe("loading the dataset " + config.dataset);
  Dataset dataset = Dataset::open(config.dataset, config.datasetReading(/*requireBuffers=*/true));
  if (dataset.capture()) {
    // A normal map in another space than declared would train every normal wrong.
    std::istringstream check(normalSpaceCheck(dataset));
    for (std::string line; std::getline(check, line);)
      if (line.rfind("warning:", 0) == 0) std::fprintf(stderr, "glint train: %s\n", line.c_str());
  }
  TrainingViews views = TrainingViews::load(dataset, dataset.split("train"),  // split(): names a missing file
                                            config.baseline == Baseline::Rgb ? ColourTarget::Render
                                                                             : ColourTarget::Diffuse,
                                            config.f0TintFromReflections, config.loss.f0TintPrior,
                                            config.loss.photograph > 0);
  if (config.loss.depthConsistency > 0 && views.supervised().depth) {
    activity.describe("checking each training view's depth against its neighbours'");
    keepConsistentDepthAndSay(config, run, &views, observer);
  }
  std::vector<CameraSphere> spheres = cameraSpheres(dataset, dataset.train(), config.prune.cameraSphereFactor);
  // The test views are scored where the run is written (into log.csv).
  TestViews testViews = TestViews::load(dataset, dataset.test(), run.writes() ? session.evalViews : 0);
  if (dataset.capture() && run.writes())
    for (const std::string& line : dataset.capture()->droppedDepths())
      std::fprintf(stderr, "glint train: warning: %s\n", line.c_str());

  activity.describe("setting up the training of " + run.root().string());
  const bool checkpointAtStart = session.resume && run.hasCheckpoint();
  std::unique_ptr<Trainer> trainer;
  double wallOffset = 0;
  if (run.writes()) {  // the others start from its state
    wallOffset = setUpTrainer(run, config, session, dataset, views, std::move(spheres), observer, &trainer);
    if (cluster::distributed()) {
      // The other ranks of an MPI job start from rank 0's state, the same bytes a
      // checkpoint holds.
      std::vector<char> bytes = encodeCheckpoint(runState(*trainer, views));
      std::vector<std::byte> message(bytes.size());
      std::memcpy(message.data(), bytes.data(), bytes.size());
      cluster::broadcast(&message);
    }
  } else {
    std::vector<std::byte> message;
    cluster::broadcast(&message);
    std::vector<char> bytes(message.size());
    std::memcpy(bytes.data(), message.data(), message.size());
    TrainingState state = decodeCheckpoint(bytes, "the state rank 0 sent");
    restoreCameraPoses(state, dataset, &views, "the state rank 0 sent");
    if (views.camerasMoved() && config.loss.depthConsistency > 0 && views.supervised().depth)
      keepConsistentDepthAndSay(config, run, &views, observer);
    trainer = std::make_unique<Trainer>(config, views, std::move(spheres), std::move(state), session.tracer);
  }
  trainer->setExchangeMode(session.exchange);
  observer.started(*trainer, dataset, views);

  // Only the process that writes the run opens the log and saves (RunFolder::writes).
  std::ofstream log = run.openLog();
  // The same figures for TensorBoard, in an event file beside log.csv, from the first step
  // (a start that fails before it leaves none).
  std::optional<TensorBoardWriter> board;
  auto start = std::chrono::steady_clock::now();
  DivergenceMonitor divergence(trainer->sceneExtent());
  bool saveDue = false;  // a checkpoint waits while the monitor suspects a collapse
  int64_t lastSaved = trainer->stepCount();
  bool checkpointOnDisk = checkpointAtStart;
  while (trainer->stepCount() < config.iters) {
    activity.describe("training step " + std::to_string(trainer->stepCount() + 1) + " of " + run.root().string());
    StepReport r = trainer->step();
    if (std::optional<std::string> problem = divergence.check(r, trainer->scene())) {
      std::string kept = checkpointOnDisk ? "the last good checkpoint (step " + std::to_string(lastSaved) +
                                                ") is kept in " + run.checkpointFile().string()
                                          : "no checkpoint was written";
      throw Error(run.root().string(), "training diverged " + *problem + "; " + kept +
                                           ". Likely cause: learning rates (lr.* in --config) or loss weights too "
                                           "large for this scene; start again with smaller ones");
    }
    if (config.cameras.every > 0 && r.step % config.cameras.every == 0 &&
        r.step <= config.cameras.lastStep(config.iters) && r.step < config.iters) {
      activity.describe("refining the training cameras at step " + std::to_string(r.step) + " of " +
                        run.root().string());
      const CameraRefinementRound round =
          refineTrainingCameras(trainer->tracer(), config.path(), &views, normalsFromCamera(dataset));
      if (run.writes()) observer.note("step " + std::to_string(r.step) + ": " + round.summary());
      if (round.moved > 0 && config.loss.depthConsistency > 0 && views.supervised().depth)
        keepConsistentDepthAndSay(config, run, &views, observer);
    }
    double wall = wallOffset + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::optional<TestScore> score;
    if (!testViews.empty() && (r.step % config.evalEvery == 0 || r.step == config.iters))
      score = testViews.score(trainer->tracer(), session.evalSpp, config.path());
    if (run.writes()) {
      log << logRow(r, wall, score) << std::flush;
      if (!board) board.emplace(run.root());
      writeScalars(*board, r, score);
    }
    observer.stepped(r, score);
    saveDue = saveDue || r.step % config.saveEvery == 0 || r.step == config.iters;
    if (saveDue && (divergence.clean() || r.step == config.iters)) {
      saveRun(run, *trainer, views);
      saveDue = false;
      lastSaved = r.step;
      checkpointOnDisk = true;
    }
    observer.betweenSteps(*trainer, r);
    // Every rank stops at the step rank 0 heard Ctrl-C (mpirun forwards it to all, but not
    // necessarily between the same steps).
    if (cluster::broadcastFlag(observer.stopRequested())) {
      saveRun(run, *trainer, views);
      return {true, r.step, trainer->scene().size()};
    }
  }
  if (trainer->stepCount() >= config.iters && !fs::exists(run.sceneFile())) saveRun(run, *trainer, views);
  return {false, trainer->stepCount(), trainer->scene().size()};
}

}  // namespace glint
