// Broadcasts of scenes and masks from rank 0 (core/cluster.h); nothing in a job of one.
#include "train/rank_sync.h"

#include <cstdint>

#include "core/cluster.h"
#include "scene/gaussian_parameters.h"

namespace glint {

void broadcastScene(GaussianScene* scene) {
  if (!cluster::distributed()) return;
  forEachParameter([&](const auto& p) { cluster::broadcastVector(&(scene->*p.values)); });
}

void broadcastMask(std::vector<bool>* mask) {
  if (!cluster::distributed()) return;
  std::vector<uint8_t> bytes(mask->begin(), mask->end());
  cluster::broadcastVector(&bytes);
  mask->assign(bytes.begin(), bytes.end());
}

}  // namespace glint
