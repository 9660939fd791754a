#include "raytrace/fast/ray_bundle.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace glint {

namespace {

// Widening of the cone and of the spheres tested against it, so that float rounding in
// the culling never drops a Gaussian the per-ray kernel would hit: 1e-4 rad of angle is
// 1 mm at 10 m, far above the rounding of the kernel's entry distance.
constexpr double kAngleMargin = 1e-4;
constexpr float kRelativeMargin = 1e-5f;

// Spreads the low 16 bits of x to the even bits of the result (Morton interleaving).
uint32_t spreadBits(uint32_t x) {
  x &= 0xffffu;
  x = (x | (x << 8)) & 0x00ff00ffu;
  x = (x | (x << 4)) & 0x0f0f0f0fu;
  x = (x | (x << 2)) & 0x33333333u;
  x = (x | (x << 1)) & 0x55555555u;
  return x;
}

bool sameOrigin(const Vec3f& a, const Vec3f& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

// No point of a sphere of this radius whose centre lies this far from the apex is nearer to
// it than the result (lowered for rounding): a lower bound on the key of anything inside.
float nearestDistanceBound(float distance, float radius) {
  return distance - radius - kRelativeMargin * (distance + radius);
}

}  // namespace

bool boundingCone(std::span<const TraceRay> rays, std::span<const uint32_t> order, RayCone* cone) {
  if (order.empty()) return false;
  const Vec3f apex = rays[order[0]].origin;
  if (!isFinite(apex)) return false;
  Vec3d sum(0.0);
  float tMin = std::numeric_limits<float>::infinity();
  for (uint32_t i : order) {
    const TraceRay& r = rays[i];
    // Negative tMin would let rays hit what lies behind the apex, outside the cone.
    if (!sameOrigin(r.origin, apex) || !(r.tMin >= 0.0f)) return false;
    sum += Vec3d(normalize(r.direction));
    tMin = std::min(tMin, r.tMin);
  }
  double sumLength = length(sum);
  if (!(sumLength > 0.0)) return false;
  Vec3d axis = sum / sumLength;
  double cosMin = 1.0;
  for (uint32_t i : order) cosMin = std::min(cosMin, dot(axis, Vec3d(normalize(rays[i].direction))));
  double angle = std::acos(std::clamp(cosMin, -1.0, 1.0)) + kAngleMargin;
  if (!(angle <= double(kMaxBundleHalfAngle))) return false;
  cone->apex = apex;
  cone->axis = Vec3f(axis);
  cone->cosAngle = float(std::cos(angle));
  cone->sinAngle = float(std::sin(angle));
  cone->tMin = tMin;
  return true;
}

namespace {

// The lanes of a leaf block whose proxy's bounding sphere meets the cone (sphereMeetsCone
// on all 8 at once, in a form the compiler vectorises), as a bit mask; *distance receives
// each centre's distance from the apex.
uint32_t lanesMeetingCone(const Bvh8Block& block, const RayCone& cone, float* distance) {
  alignas(32) int32_t flags[kBvhWidth];
  for (int i = 0; i < kBvhWidth; ++i) {
    float vx = block.mean[0][i] - cone.apex.x, vy = block.mean[1][i] - cone.apex.y, vz = block.mean[2][i] - cone.apex.z;
    bool meets = sphereMeetsConeLane(vx, vy, vz, block.boundRadius[i], cone.axis.x, cone.axis.y, cone.axis.z,
                                     cone.cosAngle, cone.sinAngle);
    bool proxy = block.radius2[i] >= 0.0f;  // false for a lane without a Gaussian
    distance[i] = std::sqrt(vx * vx + vy * vy + vz * vz);
    flags[i] = -int32_t(meets & proxy);
  }
  return laneMask(flags);
}

// The children of `node` whose box's bounding sphere meets the cone (empty lanes and boxes
// emptied by refit never do), as a bit mask; bound[c] receives the distance from the apex
// within which nothing of child c lies: the sphere holds every proxy of the subtree.
uint32_t childrenMeetingCone(const Bvh8Node& node, const RayCone& cone, float* bound) {
  alignas(32) int32_t flags[kBvhWidth];
  for (int c = 0; c < kBvhWidth; ++c) {
    float lx = node.bounds[0][c], ux = node.bounds[1][c], ly = node.bounds[2][c], uy = node.bounds[3][c],
          lz = node.bounds[4][c], uz = node.bounds[5][c];
    bool box = (lx <= ux) & (ly <= uy) & (lz <= uz);
    float cx = 0.5f * (lx + ux), cy = 0.5f * (ly + uy), cz = 0.5f * (lz + uz);
    float ex = ux - lx, ey = uy - ly, ez = uz - lz;
    float radius = 0.5f * std::sqrt(ex * ex + ey * ey + ez * ez);
    radius += kRelativeMargin * (radius + std::abs(cx) + std::abs(cy) + std::abs(cz));
    float vx = cx - cone.apex.x, vy = cy - cone.apex.y, vz = cz - cone.apex.z;
    bool meets = sphereMeetsConeLane(vx, vy, vz, radius, cone.axis.x, cone.axis.y, cone.axis.z, cone.cosAngle,
                                     cone.sinAngle);
    float distance = std::sqrt(vx * vx + vy * vy + vz * vz);
    bound[c] = nearestDistanceBound(distance, radius);
    flags[c] = -int32_t(box & meets & (node.child[c] != Bvh8Node::kNoChild));
  }
  return laneMask(flags);
}

}  // namespace

void BundleCandidates::start(const Bvh8& bvh, const RayCone& cone) {
  bvh_ = &bvh;
  cone_ = cone;
  count_ = 0;
  blocks_.clear();
  blockBound_.clear();
  pending_.clear();
  if (!bvh.empty()) pending_.push_back({cone.tMin, 0});
  frontier_ = pending_.empty() ? std::numeric_limits<float>::infinity() : cone.tMin;
}

void BundleCandidates::gather(const Bvh8& bvh, const RayCone& cone) {
  start(bvh, cone);
  next(std::numeric_limits<size_t>::max());
}

bool BundleCandidates::next(size_t minCandidates) {
  count_ = 0;
  blocks_.clear();
  blockBound_.clear();
  // Subtrees nearest first; their bounds only grow along the walk, so when the chunk is
  // full the heap's top bounds everything not yet gathered.
  while (!pending_.empty() && count_ < minCandidates) {
    std::pop_heap(pending_.begin(), pending_.end());
    Subtree s = pending_.back();
    pending_.pop_back();
    if (Bvh8Node::isLeaf(s.code))
      collectLeaf(s.code);
    else
      pushChildren(bvh_->nodes()[s.code], s.bound);
  }
  frontier_ = pending_.empty() ? std::numeric_limits<float>::infinity() : pending_.front().bound;
  finishChunk();
  return count_ > 0;
}

void BundleCandidates::collectLeaf(int32_t code) {
  uint32_t first = Bvh8Node::leafFirstBlock(code);
  for (int b = 0; b < Bvh8Node::leafBlocks(code); ++b) {
    const Bvh8Block& block = bvh_->blocks()[first + uint32_t(b)];
    alignas(32) float distance[kBvhWidth];
    for (uint32_t mask = lanesMeetingCone(block, cone_, distance); mask; mask &= mask - 1) {
      int lane = std::countr_zero(mask);
      // Every point of the proxy is at least |mean - apex| - radius from the apex, so no
      // ray of the cone enters it (and its key) before that.
      append(block, lane, std::max(nearestDistanceBound(distance[lane], block.boundRadius[lane]), cone_.tMin));
    }
  }
}

void BundleCandidates::pushChildren(const Bvh8Node& node, float parentBound) {
  alignas(32) float bound[kBvhWidth];
  for (uint32_t mask = childrenMeetingCone(node, cone_, bound); mask; mask &= mask - 1) {
    int c = std::countr_zero(mask);
    // The parent's sphere need not hold the child's: the larger bound is kept, so bounds
    // never drop along the walk and the heap's top bounds all the rest.
    pending_.push_back({std::max(bound[c], parentBound), node.child[c]});
    std::push_heap(pending_.begin(), pending_.end());
  }
}

// Blocks take the candidates in the order of the walk, which visits leaves nearest first,
// so the bounds rise from block to block and each ray's hits arrive nearly in key order.
// (A sort by depth slab and then across the cone, for compact blocks, cost more than it
// saved when rays were tested against blocks.)
void BundleCandidates::append(const Bvh8Block& in, int from, float bound) {
  int lane = int(count_ % kBvhWidth);
  if (lane == 0) {
    blocks_.emplace_back();
    blockBound_.push_back(std::numeric_limits<float>::infinity());
  }
  Bvh8Block& out = blocks_.back();
  for (int a = 0; a < 3; ++a) out.mean[a][lane] = in.mean[a][from];
  for (int m = 0; m < 9; ++m) out.worldToLocal[m][lane] = in.worldToLocal[m][from];
  out.opacity[lane] = in.opacity[from];
  out.radius2[lane] = in.radius2[from];
  out.boundRadius[lane] = in.boundRadius[from];
  out.id[lane] = in.id[from];
  blockBound_.back() = std::min(blockBound_.back(), bound);
  ++count_;
}

void BundleCandidates::finishChunk() {
  if (blocks_.empty()) return;
  for (int lane = int(count_ % kBvhWidth); lane > 0 && lane < kBvhWidth; ++lane) blocks_.back().disableLane(lane);
  // Suffix minima, the last block's capped by the frontier: a bound for it and all after.
  size_t blockCount = blocks_.size();
  blockBound_[blockCount - 1] = std::min(blockBound_[blockCount - 1], frontier_);
  for (size_t k = blockCount - 1; k-- > 0;) blockBound_[k] = std::min(blockBound_[k], blockBound_[k + 1]);
}

size_t orderByDirection(std::span<const TraceRay> rays, std::span<uint32_t> order) {
  if (order.empty()) return 0;
  Vec3d sum(0.0);
  for (uint32_t i : order) sum += Vec3d(normalize(rays[i].direction));
  Vec3f mean = length(sum) > 0.0 ? Vec3f(normalize(sum)) : Vec3f(0, 0, 1);
  // An orthonormal frame about the mean direction.
  Vec3f helper = std::abs(mean.x) < 0.9f ? Vec3f(1, 0, 0) : Vec3f(0, 1, 0);
  Vec3f e1 = normalize(cross(helper, mean)), e2 = cross(mean, e1);

  // Gnomonic projection onto the plane at unit distance along the mean: the image plane
  // of a camera looking that way. Rays at 84 degrees or more (cos < 0.1) are left out.
  constexpr float kMinCos = 0.1f;
  std::vector<Vec2f> uv(order.size());
  float lo[2] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity()};
  float hi[2] = {-lo[0], -lo[1]};
  for (size_t k = 0; k < order.size(); ++k) {
    Vec3f d = normalize(rays[order[k]].direction);
    float c = dot(d, mean);
    if (!(c >= kMinCos)) {
      uv[k] = {std::numeric_limits<float>::quiet_NaN(), 0.0f};
      continue;
    }
    uv[k] = {dot(d, e1) / c, dot(d, e2) / c};
    lo[0] = std::min(lo[0], uv[k].x), hi[0] = std::max(hi[0], uv[k].x);
    lo[1] = std::min(lo[1], uv[k].y), hi[1] = std::max(hi[1], uv[k].y);
  }
  // One scale for both axes keeps the tiles square.
  float extent = std::max({hi[0] - lo[0], hi[1] - lo[1], 1e-20f});
  // (Morton code, ray index): the index breaks ties, so the order is deterministic.
  std::vector<std::pair<uint64_t, uint32_t>> keys(order.size());
  size_t inside = 0;
  for (size_t k = 0; k < order.size(); ++k) {
    uint64_t code = uint64_t(1) << 32;  // left out: after every 32-bit Morton code
    if (!std::isnan(uv[k].x)) {
      uint32_t qx = uint32_t(std::clamp((uv[k].x - lo[0]) / extent, 0.0f, 1.0f) * 65535.0f);
      uint32_t qy = uint32_t(std::clamp((uv[k].y - lo[1]) / extent, 0.0f, 1.0f) * 65535.0f);
      code = spreadBits(qx) | (spreadBits(qy) << 1);
      ++inside;
    }
    keys[k] = {code, order[k]};
  }
  std::sort(keys.begin(), keys.end());
  for (size_t k = 0; k < order.size(); ++k) order[k] = keys[k].second;
  return inside;
}

}  // namespace glint
