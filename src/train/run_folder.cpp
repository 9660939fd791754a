// Reading a run's config.json, starting a new run folder, and undoing a failed start.
#include "train/run_folder.h"

#include "core/atomic_file.h"
#include "core/cluster.h"
#include "core/error.h"
#include "core/folder_lock.h"

namespace glint {

namespace fs = std::filesystem;

TrainConfig RunFolder::readConfig() const { return readTrainConfig(configFile()); }

bool RunFolder::writes() const { return cluster::isRoot(); }

std::unique_ptr<FolderLock> RunFolder::lockForWriting(const std::string& holder) const {
  return writes() ? std::make_unique<FolderLock>(root_, holder) : nullptr;
}

std::ofstream RunFolder::openLog() const {
  std::ofstream log;
  if (writes()) log.open(logFile(), std::ios::app);
  return log;
}

void RunFolder::checkCanCreate(bool force) const {
  if (!writes()) return;
  if (fs::exists(root_) && !fs::is_directory(root_)) throw Error(root_.string(), "exists and is not a folder");
  if (fs::exists(root_) && !isEmptyButForLock(root_) && !force && !isUnfinishedStart())
    throw Error(root_.string(), hasConfig()
                                    ? "holds a training run; continue it with --resume, choose another -o folder, "
                                      "or pass --force to start over (its files are overwritten)"
                                    : "is not empty and holds no training run; choose another -o folder, or pass "
                                      "--force to write into it");
}

void RunFolder::create(const TrainConfig& config, bool force) const {
  if (!writes()) return;
  checkCanCreate(force);
  fs::create_directories(root_);
  writeTextAtomically(configFile(), toJson(config).dump(2) + "\n");
}

void RunFolder::removeFailedStart(bool madeByThisStart) const {
  if (!writes()) return;
  if (hasCheckpoint() || fs::exists(sceneFile())) return;
  std::error_code ignored;  // best effort: the error being reported matters more
  fs::remove(configFile(), ignored);
  fs::remove(logFile(), ignored);
  for (const fs::directory_entry& e : fs::directory_iterator(root_, ignored))
    if (e.path().filename().string().rfind("events.out.tfevents.", 0) == 0) fs::remove(e.path(), ignored);
  const fs::path checkpointFolder = checkpointFile().parent_path();
  if (fs::is_directory(checkpointFolder, ignored) && fs::is_empty(checkpointFolder, ignored))
    fs::remove(checkpointFolder, ignored);
  // The lock file this start put in goes too, so that a folder the user made is left as empty
  // as it was found.
  if (isEmptyButForLock(root_)) fs::remove(root_ / kFolderLockName, ignored);
  if (madeByThisStart && fs::is_empty(root_, ignored)) fs::remove(root_, ignored);
}

}  // namespace glint
