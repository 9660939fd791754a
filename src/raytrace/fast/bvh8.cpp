// The 8-wide BVH's per-Gaussian data, refit, and bookkeeping (construction is in bvh8_builder.cpp).
#include "raytrace/fast/bvh8.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/parallel.h"
#include "raytrace/fast/bvh8_builder.h"
#include "raytrace/gaussian_kernel.h"

namespace glint {

void Bvh8Block::setLane(int lane, const GaussianLane& g, uint32_t gaussian) {
  for (int a = 0; a < 3; ++a) mean[a][lane] = g.mean[a];
  for (int k = 0; k < 9; ++k) worldToLocal[k][lane] = g.worldToLocal[k];
  opacity[lane] = g.opacity;
  radius2[lane] = g.radius2;
  boundRadius[lane] = g.boundRadius;
  id[lane] = gaussian;
}

void Bvh8Block::disableLane(int lane, uint32_t gaussian) {
  for (int a = 0; a < 3; ++a) mean[a][lane] = 0.0f;
  for (int k = 0; k < 9; ++k) worldToLocal[k][lane] = (k % 4 == 0) ? 1.0f : 0.0f;
  opacity[lane] = 0.0f;
  radius2[lane] = -1.0f;
  boundRadius[lane] = 0.0f;
  id[lane] = gaussian;
}

namespace {

// How far ahead refit prefetches the scene parameters of the leaf blocks' Gaussians.
constexpr int64_t kPrefetchBlocks = 4;

// (r/R)^2 at which the proxy ellipsoid lies: the r^2 solving proxyRadius() of
// gaussian_kernel.h, with the common kernel powers as roots instead of powf (which
// refit, run after every optimiser step, would otherwise spend much of its time in).
float proxyRadius2(float peak, const TraceSettings& s) {
  float p = s.kernelPower;
  float x = 2.0f * p * std::log(peak / s.alphaMin);
  if (p == 1.0f) return x;
  if (p == 2.0f) return std::sqrt(x);
  if (p == 3.0f) return std::cbrt(x);
  return std::pow(x, 1.0f / p);
}

}  // namespace

// The same frame as makeGaussianFrame<float> (to rounding), computed with fewer
// transcendental functions and divisions since build and refit run it for every Gaussian.
bool computeGaussianLane(const GaussianScene& scene, size_t i, const TraceSettings& settings, GaussianLane* lane,
                         Box3* box) {
  // Opacity first: a Gaussian that can never reach alphaMin has no proxy.
  float opacity = 1.0f / (1.0f + std::exp(-scene.opacityLogit[i]));
  float peak = kMaxAlpha * opacity;
  if (!(peak > settings.alphaMin)) return false;
  float radius2 = proxyRadius2(peak, settings);

  // Rotation of the normalised quaternion (quatToRotation), columns = local axes.
  const Quatf& q = scene.rotation[i];
  float n2 = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
  Mat3f rot;
  if (n2 > 0.0f) {
    float inv = 1.0f / std::sqrt(n2);
    float w = q.w * inv, x = q.x * inv, y = q.y * inv, z = q.z * inv;
    rot.m[0] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)};
    rot.m[1] = {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)};
    rot.m[2] = {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)};
  }
  const Vec3f& logScale = scene.logScale[i];
  float scale[3] = {std::exp(logScale.x), std::exp(logScale.y), std::exp(logScale.z)};
  float invScale[3] = {1.0f / scale[0], 1.0f / scale[1], 1.0f / scale[2]};

  // World-to-local S^-1 R^T: row r is local axis r divided by its scale.
  const Vec3f& mean = scene.position[i];
  for (int r = 0; r < 3; ++r) {
    lane->mean[r] = mean[r];
    for (int c = 0; c < 3; ++c) lane->worldToLocal[3 * r + c] = rot.m[c][r] * invScale[r];
  }
  lane->opacity = opacity;
  lane->radius2 = radius2;

  // The ellipsoid of radius R spans, along world axis k, R sqrt(sum_r (axis_r[k] s_r)^2)
  // on each side of the mean. Padded relatively (1e-5) and absolutely (1e-6 of the
  // coordinate) so float rounding in the slab tests never rejects a box the ellipsoid
  // touches.
  float radius = std::sqrt(radius2);
  bool finite = std::isfinite(radius);
  // The proxy's longest semi-axis, padded like the box below.
  float maxScale = std::max({scale[0], scale[1], scale[2]});
  lane->boundRadius = radius * maxScale * (1.0f + 1e-5f) + 1e-6f * (std::abs(mean.x) + std::abs(mean.y) + std::abs(mean.z));
  finite = finite && std::isfinite(lane->boundRadius);
  for (int k = 0; k < 3; ++k) {
    float a0 = rot.m[k][0] * scale[0], a1 = rot.m[k][1] * scale[1], a2 = rot.m[k][2] * scale[2];
    float e = radius * std::sqrt(a0 * a0 + a1 * a1 + a2 * a2) * (1.0f + 1e-5f) + 1e-6f * std::abs(mean[k]);
    box->lower[k] = mean[k] - e;
    box->upper[k] = mean[k] + e;
    finite = finite && std::isfinite(box->lower[k]) && std::isfinite(box->upper[k]);
  }
  for (int k = 0; k < 9; ++k) finite = finite && std::isfinite(lane->worldToLocal[k]);
  return finite;
}

void Bvh8::clear() {
  nodes_.clear();
  blocks_.clear();
  leftOut_.clear();
  stats_ = {};
}

void Bvh8::build(const GaussianScene& scene, const TraceSettings& settings) {
  GLINT_CHECK(scene.consistent(), "the Gaussian scene's arrays differ in length");
  GLINT_CHECK(scene.size() < size_t(INT32_MAX), "too many Gaussians for the BVH's 32-bit indices");
  scene_ = &scene;
  settings_ = settings;
  Bvh8BuildResult result;
  buildBvh8(scene, settings, &result);
  nodes_ = std::move(result.nodes);
  blocks_ = std::move(result.blocks);
  leftOut_ = std::move(result.leftOut);
  stats_ = result.stats;
  builtSize_ = scene.size();
}

void Bvh8::refit() {
  GLINT_CHECK(scene_ != nullptr, "refit before build");
  const GaussianScene& scene = *scene_;
  GLINT_CHECK(scene.consistent() && scene.size() == builtSize_,
              "refit: the Gaussian count changed since the build (build again instead)");

  // A Gaussian left out of the tree that now has a proxy would be missed: rebuild.
  std::atomic<bool> gained{false};
  parallelFor(int64_t(leftOut_.size()), 4096, [&](int64_t k) {
    GaussianLane lane;
    Box3 box;
    if (computeGaussianLane(scene, leftOut_[k], settings_, &lane, &box)) gained.store(true, std::memory_order_relaxed);
  });
  if (gained.load()) {
    build(scene, settings_);
    return;
  }

  // Leaf blocks: recompute every lane and the block's box. The Gaussians are scattered
  // over the scene's arrays, so each lane first requests the parameters of the same lane
  // a few blocks ahead: the loop is then not bound by memory latency.
  std::vector<Box3> blockBoxes(blocks_.size());
  parallelForChunks(int64_t(blocks_.size()), 256, [&](int64_t begin, int64_t end) {
    for (int64_t l = begin; l < end; ++l) {
      const Bvh8Block* ahead = l + kPrefetchBlocks < end ? &blocks_[l + kPrefetchBlocks] : nullptr;
      Bvh8Block& block = blocks_[l];
      Box3 bounds;
      for (int lane = 0; lane < kBvhWidth; ++lane) {
        if (ahead && ahead->id[lane] != Bvh8Block::kNoGaussian) {
          uint32_t next = ahead->id[lane];
          __builtin_prefetch(&scene.position[next]);
          __builtin_prefetch(&scene.rotation[next]);
          __builtin_prefetch(&scene.logScale[next]);
          __builtin_prefetch(&scene.opacityLogit[next]);
        }
        uint32_t id = block.id[lane];
        if (id == Bvh8Block::kNoGaussian) continue;
        GaussianLane g;
        Box3 box;
        if (computeGaussianLane(scene, id, settings_, &g, &box)) {
          block.setLane(lane, g, id);
          bounds.grow(box);
        } else {
          block.disableLane(lane, id);
        }
      }
      blockBoxes[l] = bounds;
    }
  });

  // Inner nodes bottom-up: children are stored after their parent, so a reverse sweep
  // sees every child's box before the parent needs it.
  std::vector<Box3> nodeBoxes(nodes_.size());
  constexpr float kInf = std::numeric_limits<float>::infinity();
  for (size_t n = nodes_.size(); n-- > 0;) {
    Bvh8Node& node = nodes_[n];
    Box3 bounds;
    for (int c = 0; c < kBvhWidth; ++c) {
      int32_t code = node.child[c];
      if (code == Bvh8Node::kNoChild) continue;
      Box3 box;
      if (Bvh8Node::isLeaf(code)) {
        uint32_t first = Bvh8Node::leafFirstBlock(code);
        for (int b = 0; b < Bvh8Node::leafBlocks(code); ++b) box.grow(blockBoxes[first + b]);
      } else {
        box = nodeBoxes[code];
      }
      for (int a = 0; a < 3; ++a) {
        node.bounds[2 * a][c] = box.valid() ? box.lower[a] : kInf;
        node.bounds[2 * a + 1][c] = box.valid() ? box.upper[a] : -kInf;
      }
      bounds.grow(box);
    }
    nodeBoxes[n] = bounds;
  }
}

size_t Bvh8::memoryBytes() const {
  return nodes_.capacity() * sizeof(Bvh8Node) + blocks_.capacity() * sizeof(Bvh8Block) +
         leftOut_.capacity() * sizeof(uint32_t);
}

}  // namespace glint
