// The 8-wide bounding volume hierarchy of the fast Gaussian tracer: node and leaf layouts
// (structure of arrays over 8 lanes, so one AVX2 instruction handles 8 children or 8
// Gaussians), a multi-threaded binned-SAH build over the proxy boxes, and refit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#ifdef __SSE__
#include <immintrin.h>
#endif

#include "core/cpu_gpu.h"
#include "raytrace/trace_settings.h"
#include "scene/gaussians.h"

namespace glint {

constexpr int kBvhWidth = 8;
// Leaves hold up to kMaxLeafBlocks x 8 Gaussians: the proxies of a radiance field overlap
// far more than they are apart, so larger leaves hit more Gaussians per visit and need
// fewer inner nodes (on tracer_bench's room scenes 32 per leaf traced about 25% faster
// than 8; 48 and 64 were slower again).
constexpr int kMaxLeafBlocks = 4;

// An axis-aligned box, 4 lanes wide so that box operations are single SIMD instructions
// (lane 3 is not a coordinate). Empty when lower > upper.
struct alignas(16) Box3 {
  float lower[4] = {1e30f, 1e30f, 1e30f, 1e30f};
  float upper[4] = {-1e30f, -1e30f, -1e30f, -1e30f};

  void grow(const Box3& b) {
#ifdef __SSE__
    _mm_store_ps(lower, _mm_min_ps(_mm_load_ps(b.lower), _mm_load_ps(lower)));
    _mm_store_ps(upper, _mm_max_ps(_mm_load_ps(b.upper), _mm_load_ps(upper)));
#else
    for (int a = 0; a < 4; ++a) {
      lower[a] = b.lower[a] < lower[a] ? b.lower[a] : lower[a];
      upper[a] = b.upper[a] > upper[a] ? b.upper[a] : upper[a];
    }
#endif
  }
  bool valid() const { return lower[0] <= upper[0]; }
  // Half the surface area (the SAH only compares areas).
  float halfArea() const {
    if (!valid()) return 0.0f;
    float dx = upper[0] - lower[0], dy = upper[1] - lower[1], dz = upper[2] - lower[2];
    return dx * dy + dy * dz + dz * dx;
  }
};

// An inner node: the boxes of up to 8 children, one lane per child. bounds[2 a] holds the
// lower and bounds[2 a + 1] the upper planes along axis a, so a ray picks its near plane
// per axis by the direction's sign. Unused lanes have an inverted (+inf, -inf) box that no
// ray enters.
struct alignas(64) Bvh8Node {
  float bounds[6][kBvhWidth];
  // >= 0: index of an inner node; < 0: a leaf (see leafCode); kNoChild in unused lanes.
  int32_t child[kBvhWidth];

  static constexpr int32_t kNoChild = INT32_MIN;
  GLINT_CPU_GPU static bool isLeaf(int32_t c) { return c < 0; }
  // A leaf is a run of 1 to kMaxLeafBlocks consecutive Bvh8Blocks.
  GLINT_CPU_GPU static int32_t leafCode(uint32_t firstBlock, int blocks) { return ~int32_t(firstBlock << 3 | uint32_t(blocks - 1)); }
  GLINT_CPU_GPU static uint32_t leafFirstBlock(int32_t c) { return uint32_t(~c) >> 3; }
  GLINT_CPU_GPU static int leafBlocks(int32_t c) { return int(uint32_t(~c) & 7u) + 1; }
};

// What the kernel needs of one Gaussian: its GaussianFrame (gaussian_kernel.h) in float.
struct GaussianLane {
  float mean[3];
  float worldToLocal[9];  // row-major S^-1 R^T
  float opacity;
  float radius2;          // proxy radius squared (local units)
  float boundRadius;      // radius of a world-space sphere about the mean holding the proxy
};

// A leaf block: up to 8 Gaussians' kernel data, one lane per Gaussian. Lanes without a
// proxy have radius2 = -1 and an identity frame, so they never pass the proxy test.
struct alignas(32) Bvh8Block {
  float mean[3][kBvhWidth];
  float worldToLocal[9][kBvhWidth];
  float opacity[kBvhWidth];
  float radius2[kBvhWidth];
  float boundRadius[kBvhWidth];  // GaussianLane::boundRadius (coherent bundles cull with it)
  uint32_t id[kBvhWidth];  // Gaussian index; kNoGaussian in unused lanes

  static constexpr uint32_t kNoGaussian = UINT32_MAX;

  void setLane(int lane, const GaussianLane& g, uint32_t gaussian);
  // A lane that never hits; keeps the Gaussian index (refit may give it a proxy again).
  void disableLane(int lane, uint32_t gaussian = kNoGaussian);
};

// Build statistics (for benchmarks and tests).
struct Bvh8Stats {
  size_t gaussians = 0;  // Gaussians in the tree (those with a proxy)
  size_t nodes = 0;
  size_t leaves = 0;
  size_t blocks = 0;     // 8-lane leaf blocks
  int depth = 0;         // inner-node levels on the longest path
};

class Bvh8 {
 public:
  // Builds the tree over every Gaussian with a proxy (proxy radius > 0 and finite
  // parameters). The scene is referenced: it must outlive the tree.
  void build(const GaussianScene& scene, const TraceSettings& settings);
  // Recomputes leaf data and boxes from the scene's current parameters, keeping the
  // topology. Rebuilds instead when a Gaussian left out of the tree now has a proxy, so
  // the result is always exact.
  void refit();
  void clear();

  bool empty() const { return nodes_.empty(); }
  const Bvh8Node* nodes() const { return nodes_.data(); }
  const Bvh8Block* blocks() const { return blocks_.data(); }
  size_t nodeCount() const { return nodes_.size(); }
  size_t blockCount() const { return blocks_.size(); }
  const GaussianScene* scene() const { return scene_; }
  const TraceSettings& settings() const { return settings_; }
  const Bvh8Stats& stats() const { return stats_; }
  // Stack entries a depth-first traversal can need at most.
  int maxStackSize() const { return 1 + (kBvhWidth - 1) * stats_.depth; }
  size_t memoryBytes() const;

 private:
  const GaussianScene* scene_ = nullptr;
  TraceSettings settings_;
  std::vector<Bvh8Node> nodes_;   // node 0 is the root; children come after their parent
  std::vector<Bvh8Block> blocks_;
  std::vector<uint32_t> leftOut_;  // Gaussians without a proxy at build time
  Bvh8Stats stats_;
  size_t builtSize_ = 0;
};

// Gaussian i's kernel data (the frame of makeGaussianFrame, in float) and the world box of
// its proxy ellipsoid, padded slightly so rounding never loses a grazing hit. Returns
// false when the Gaussian has no proxy (it can never reach alphaMin) or non-finite
// parameters.
bool computeGaussianLane(const GaussianScene& scene, size_t i, const TraceSettings& settings, GaussianLane* lane,
                         Box3* box);

}  // namespace glint
