// Multi-threaded binned-SAH construction of the fast tracer's 8-wide BVH over the
// Gaussians' proxy boxes.
#pragma once

#include <cstdint>
#include <vector>

#include "raytrace/fast/bvh8.h"

namespace glint {

struct Bvh8BuildResult {
  std::vector<Bvh8Node> nodes;
  std::vector<Bvh8Block> blocks;
  std::vector<uint32_t> leftOut;  // Gaussians without a proxy
  Bvh8Stats stats;
};

// Top-down binned SAH over the proxy boxes' centres (Wald 2007, "On fast Construction of
// SAH-based Bounding Volume Hierarchies"), forming each 8-wide node by splitting its
// largest child until it has 8 (as Embree's wide builders do); leaves hold up to
// kMaxLeafBlocks x 8 Gaussians. Large subtrees are built in parallel.
void buildBvh8(const GaussianScene& scene, const TraceSettings& settings, Bvh8BuildResult* out);

}  // namespace glint
