// The training loop of a run folder (`glint train`): sets the trainer up, fresh from the
// dense initialisation or from the run's checkpoint, runs the steps, scores the test views
// every eval_every steps, appends a row per step to log.csv and saves the checkpoint and
// scene.ply atomically every save_every steps (held back while the divergence monitor
// suspects a collapse). What happens is told to a TrainingObserver; the command prints it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "scene/dataset.h"
#include "train/run_folder.h"
#include "train/trainer.h"
#include "train/training_eval.h"

namespace glint {

// Settings of a training session that config.json does not hold: they do not change the
// trained scene, so a resumed run may pick them anew.
struct TrainingSession {
  bool resume = false;          // continue from the run's checkpoint when it has one
  std::string tracer = "fast";  // Gaussian tracer of training and of its test-view score
  int evalViews = 20;           // test views scored (evenly spaced; 0 = none)
  int evalSpp = 4;              // jittered samples per pixel of the score
  // How the ranks of an MPI job sum their gradients (identical results either way).
  ExchangeMode exchange = ExchangeMode::Dense;
};

// Everything the loop reports; each method does nothing unless overridden.
class TrainingObserver {
 public:
  virtual ~TrainingObserver() = default;
  // An event worth a line of its own: the initialisation, resuming.
  virtual void note(const std::string& /*message*/) {}
  // Once, before the first step: the trainer as set up, and what it trains on.
  virtual void started(const Trainer& /*trainer*/, const Dataset& /*dataset*/, const TrainingViews& /*views*/) {}
  // After each step, once its log row is written: the step's report, and the test-view
  // score when this step took one.
  virtual void stepped(const StepReport& /*report*/, const std::optional<TestScore>& /*score*/) {}
  // After each step and any checkpoint, between steps: the scene may be read (the live
  // viewer's snapshots).
  virtual void betweenSteps(const Trainer& /*trainer*/, const StepReport& /*report*/) {}
  // Asked after each step; true saves a checkpoint and ends the loop (Ctrl-C).
  virtual bool stopRequested() { return false; }
};

struct TrainingOutcome {
  bool stopped = false;  // by stopRequested, before config.iters steps
  int64_t step = 0;      // steps done
  size_t gaussians = 0;  // in the saved scene
};

// Trains `config` (the contents of the run's config.json) in `run` up to config.iters
// steps. With session.resume and a checkpoint, continues from it exactly as if never
// stopped: the checkpoint must have been written with the same settings but iters, and
// log.csv is cut back to its step. Throws Error for bad input and when training diverges
// (naming the checkpoint kept).
TrainingOutcome trainRun(const RunFolder& run, const TrainConfig& config, const TrainingSession& session,
                         TrainingObserver& observer);

}  // namespace glint
