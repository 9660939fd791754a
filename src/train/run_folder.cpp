// Reading a run's config.json and starting a new run folder.
#include "train/run_folder.h"

#include "core/atomic_file.h"
#include "core/error.h"

namespace glint {

namespace fs = std::filesystem;

TrainConfig RunFolder::readConfig() const { return readTrainConfig(configFile()); }

void RunFolder::create(const TrainConfig& config, bool force) const {
  if (fs::exists(root_) && !fs::is_directory(root_)) throw Error(root_.string(), "exists and is not a folder");
  if (fs::exists(root_) && !fs::is_empty(root_) && !force)
    throw Error(root_.string(), hasConfig()
                                    ? "holds a training run; continue it with --resume, choose another -o folder, "
                                      "or pass --force to start over (its files are overwritten)"
                                    : "is not empty and holds no training run; choose another -o folder, or pass "
                                      "--force to write into it");
  fs::create_directories(root_);
  writeTextAtomically(configFile(), toJson(config).dump(2) + "\n");
}

}  // namespace glint
