// Resumable training state on disk (RUN/checkpoint/state.bin): parameters, Adam moments and
// step, the pruning and densification accumulators, the step counter and the config it was made with. Written
// atomically; read back bit for bit, so a resumed run continues exactly.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "math/mat4.h"
#include "scene/gaussians.h"
#include "train/adam.h"

namespace glint {

struct TrainingState {
  int64_t step = 0;        // steps completed
  float sceneExtent = 0;
  GaussianScene scene;
  AdamOptimizer adam;
  std::vector<float> pruneWeight;  // blend weight accumulated since the last prune
  std::vector<float> densifyScore;  // split score since the last densify step (train/densify.h)
  float roughnessShift = 0;        // the shift-invariant roughness loss's offset (train/trainer.h)
  std::string configJson;          // the run's config, to refuse resuming with another
  // The training views' camera-to-world poses once camera refinement moved them (in the
  // views' order; empty: the dataset's cameras, unchanged).
  std::vector<Mat4> cameraPoses;
};

void writeCheckpoint(const std::filesystem::path& file, const TrainingState& state);
// Throws Error naming the file when it is missing, truncated, of another version or
// corrupt (a checksum covers every byte).
TrainingState readCheckpoint(const std::filesystem::path& file);

// The bytes of a checkpoint file, and back (`name` names them in errors); also how an MPI
// job's rank 0 hands its state to the others (train/training_loop.cpp).
std::vector<char> encodeCheckpoint(const TrainingState& state);
TrainingState decodeCheckpoint(std::span<const char> bytes, const std::string& name);

}  // namespace glint
