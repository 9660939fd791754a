// A training run folder (made by `glint train`): where each of its files lives, its
// settings (read from config.json here for every command that opens a run), and who writes
// it: in an MPI job rank 0 alone, so the writing methods here do nothing on the other ranks
// and callers need not ask which rank they are.
#pragma once

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "core/folder_lock.h"

#include "train/train_config.h"

namespace glint {

class RunFolder {
 public:
  explicit RunFolder(std::filesystem::path root) : root_(std::move(root)) {}

  const std::filesystem::path& root() const { return root_; }
  std::filesystem::path configFile() const { return root_ / "config.json"; }  // every setting (TrainConfig)
  std::filesystem::path sceneFile() const { return root_ / "scene.ply"; }     // the latest saved scene
  std::filesystem::path checkpointFile() const { return root_ / "checkpoint" / "state.bin"; }  // resumable state
  std::filesystem::path logFile() const { return root_ / "log.csv"; }          // one row per step
  std::filesystem::path evalFolder() const { return root_ / "eval"; }          // `glint eval`'s output
  std::filesystem::path metricsFile() const { return evalFolder() / "metrics.json"; }
  std::filesystem::path reportFile() const { return root_ / "report.html"; }

  bool hasConfig() const { return std::filesystem::exists(configFile()); }
  bool hasCheckpoint() const { return std::filesystem::exists(checkpointFile()); }
  // A start that never got as far as a checkpoint or a scene (it failed, or was killed while
  // loading): config.json and perhaps log.csv, nothing worth keeping.
  bool isUnfinishedStart() const { return hasConfig() && !hasCheckpoint() && !std::filesystem::exists(sceneFile()); }

  // Whether this process writes the run (rank 0 of an MPI job; the only process otherwise).
  bool writes() const;
  // The folder's lock for `holder` (core/folder_lock.h) where this process writes; none on
  // the other ranks. Throws Error naming the process that holds it.
  std::unique_ptr<FolderLock> lockForWriting(const std::string& holder) const;
  // log.csv opened for appending where this process writes; elsewhere a stream that is not
  // open, whose writes go nowhere.
  std::ofstream openLog() const;

  // config.json: the defaults with every setting of the file applied and checked by
  // TrainConfig::validate, so every command refuses a bad file with the same message,
  // which names the file and the key. Throws Error.
  TrainConfig readConfig() const;

  // Makes the folder for a new run and writes config.json. A folder that exists must be
  // empty or hold an unfinished start (which is started afresh) unless `force` (then its
  // files are overwritten); throws Error otherwise. Only where this process writes.
  void create(const TrainConfig& config, bool force) const;
  // create's refusal alone, for a caller that checks before it locks the folder (likewise).
  void checkCanCreate(bool force) const;

  // Undoes a start that failed before its first step: removes the files a start writes
  // (config.json, log.csv, an empty checkpoint/) and then the folder itself if it was
  // `madeByThisStart` and is left empty. Never touches a checkpoint, a scene or any other file
  // (the folder's lock file, core/folder_lock.h, goes when nothing else is left). Only where
  // this process writes.
  void removeFailedStart(bool madeByThisStart) const;

 private:
  std::filesystem::path root_;
};

}  // namespace glint
