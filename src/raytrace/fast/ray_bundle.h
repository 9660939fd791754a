// Coherent ray bundles for the fast tracer: rays that share an origin and point into a
// narrow cone (a tile of camera rays) gather their candidate Gaussians from the BVH once,
// sorted by a lower bound on the key any of them can give each Gaussian; every ray then
// streams through that list front to back and composites in exact (key, id) order, as
// the per-ray traversal does. A tile rasteriser's per-tile lists, kept exact.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#ifdef __AVX2__
#include <immintrin.h>
#endif

#include "raytrace/fast/bvh8.h"
#include "raytrace/gaussian_tracer.h"

namespace glint {

// The cone holding a bundle's rays: apex at their shared origin, unit axis, half angle
// given by its cosine and sine (already widened for rounding).
struct RayCone {
  Vec3f apex;
  Vec3f axis;
  float cosAngle = 1.0f, sinAngle = 0.0f;
  float tMin = 0.0f;  // the smallest tMin of the bundle's rays
};

// Rays wider apart than this (half angle of the cone, radians) are not worth bundling:
// their candidate list would be most of what they see.
constexpr float kMaxBundleHalfAngle = 0.1f;

// The cone of rays[order[0..n)]; false if they do not share one origin (bit for bit) or
// are spread wider than kMaxBundleHalfAngle.
bool boundingCone(std::span<const TraceRay> rays, std::span<const uint32_t> order, RayCone* cone);

// True if the sphere (center, radius) may meet the cone (apex shared, unit axis a, half
// angle given by cosA and sinA) at a point in front of its apex; conservative (false only
// when it certainly does not). v = centre - apex. Written so that loops over 8 lanes (of
// spheres or of cones) vectorise.
inline bool sphereMeetsConeLane(float vx, float vy, float vz, float r, float ax, float ay, float az, float cosA,
                                float sinA) {
  float d2 = vx * vx + vy * vy + vz * vz;
  float along = vx * ax + vy * ay + vz * az;
  // |v x a|, without the cancellation of sqrt(d2 - along^2) for centres near the axis.
  float cx = vy * az - vz * ay, cy = vz * ax - vx * az, cz = vx * ay - vy * ax;
  float perp = std::sqrt(cx * cx + cy * cy + cz * cz);
  // The apex lies in the sphere; or else the nearest point of the cone's surface to the
  // centre, in the plane of axis and centre, lies on the boundary ray (cos, sin), and
  // behind the apex it is the apex itself, farther than the radius; the signed distance
  // to the boundary ray is negative inside the cone.
  // Bitwise operators, without branches, so that loops over lanes vectorise.
  return (d2 <= r * r) | ((along * cosA + perp * sinA >= 0.0f) & (perp * cosA - along * sinA <= r));
}

// The lanes whose flag is set (-1, else 0) as a bit mask. Lane loops store flags and
// convert them here: GCC vectorises a loop that fills an array, not one that shifts bits
// into a mask by the lane index.
inline uint32_t laneMask(const int32_t flags[kBvhWidth]) {
#ifdef __AVX2__
  return uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(flags)))));
#else
  uint32_t mask = 0;
  for (int i = 0; i < kBvhWidth; ++i) mask |= uint32_t(flags[i] & 1) << i;
  return mask;
#endif
}

inline bool sphereMeetsCone(const Vec3f& center, float radius, const RayCone& cone) {
  Vec3f v = center - cone.apex;
  return sphereMeetsConeLane(v.x, v.y, v.z, radius, cone.axis.x, cone.axis.y, cone.axis.z, cone.cosAngle,
                             cone.sinAngle);
}

// The cones of up to 8 packets of 8 rays of one bundle (shared apex), one per lane, so that
// a Gaussian's bounding sphere is tested against all 8 at once.
struct alignas(32) PacketCones {
  float axis[3][kBvhWidth];
  float cosAngle[kBvhWidth];
  float sinAngle[kBvhWidth];
};

// The lanes of `cones` (apex shared) whose cone the sphere (center, radius) may meet.
inline uint32_t conesMeetingSphere(const PacketCones& cones, const Vec3f& apex, const Vec3f& center, float radius) {
  const float vx = center.x - apex.x, vy = center.y - apex.y, vz = center.z - apex.z;
  alignas(32) int32_t meets[kBvhWidth];
  for (int i = 0; i < kBvhWidth; ++i)
    meets[i] = -int32_t(sphereMeetsConeLane(vx, vy, vz, radius, cones.axis[0][i], cones.axis[1][i], cones.axis[2][i],
                                            cones.cosAngle[i], cones.sinAngle[i]));
  return laneMask(meets);
}

// The candidate Gaussians of one bundle, as leaf blocks in the BVH's layout (copied lanes,
// so the tracer's kernels are the BVH's own). They are gathered lazily, front to back, in
// chunks: the BVH is walked nearest bounding sphere first, and a chunk ends once it holds
// enough candidates, so a bundle whose rays all terminate early never gathers what lies
// behind. Within a chunk, blocks follow the walk (leaf by leaf, nearest first).
class BundleCandidates {
 public:
  // Starts a front-to-back walk of the BVH for the cone; the first chunk is empty.
  void start(const Bvh8& bvh, const RayCone& cone);
  // Replaces the chunk with the next one: at least minCandidates Gaussians (fewer only at
  // the end) whose proxy's bounding sphere meets the cone. False when nothing is left.
  bool next(size_t minCandidates);
  // Every candidate at once: start, then one chunk holding them all.
  void gather(const Bvh8& bvh, const RayCone& cone);

  int blockCount() const { return int(blocks_.size()); }
  const Bvh8Block& block(int k) const { return blocks_[size_t(k)]; }
  // No Gaussian of block k, of a later block or of a later chunk gives any of the bundle's
  // rays a key below this (exact order does not depend on how well the blocks are sorted,
  // only the work does).
  float blockBound(int k) const { return blockBound_[size_t(k)]; }
  // No Gaussian of a later chunk gives a key below this (+infinity after the last chunk).
  float frontier() const { return frontier_; }
  size_t candidates() const { return count_; }

 private:
  struct Subtree {
    float bound;  // lower bound of the key of anything in it
    int32_t code;
    bool operator<(const Subtree& b) const { return bound > b.bound; }  // std heap: nearest on top
  };
  void collectLeaf(int32_t code);
  void pushChildren(const Bvh8Node& node, float parentBound);
  // Adds lane `from` of `in` as the chunk's next candidate; no ray of the cone gives it a
  // key below `bound`.
  void append(const Bvh8Block& in, int from, float bound);
  // Empties the last block's unused lanes and makes the block bounds suffix minima.
  void finishChunk();

  const Bvh8* bvh_ = nullptr;
  RayCone cone_;
  std::vector<Subtree> pending_;
  float frontier_ = 0.0f;
  size_t count_ = 0;  // candidates in the chunk
  std::vector<Bvh8Block> blocks_;
  std::vector<float> blockBound_;
};

// Orders the rays of rays[begin, end) (which share an origin) so that consecutive ones
// point in nearby directions: Morton order of their gnomonic projection about the mean
// direction, which for camera rays is the image plane, so runs of 64 are 8x8 tiles.
// Rays at 84 degrees or more from the mean come last (order them into no bundle).
// Returns how many rays lie within that range (at the front of `order`).
size_t orderByDirection(std::span<const TraceRay> rays, std::span<uint32_t> order);

}  // namespace glint
