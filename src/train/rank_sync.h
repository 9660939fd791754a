// What rank 0 of an MPI training job decides and the other ranks take over, so that every
// rank holds the same scene after every step even where a decision depends on data that
// could differ in the last bit between machines (docs/cluster.md).
#pragma once

#include <vector>

#include "scene/gaussians.h"

namespace glint {

// Rank 0's scene on every rank (the far field and reflection seeds of the warm-up's end).
void broadcastScene(GaussianScene* scene);
// Rank 0's mask on every rank (which Gaussians a pruning keeps).
void broadcastMask(std::vector<bool>* mask);

}  // namespace glint
