// A hash grid of Gaussian means for radius queries: the neighbourhoods of healing
// (edit/heal_uncovered), of relighting's filter and of its cover of the receivers to trace
// (render/differential_relight), and of selection growth (edit/selection_growth).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "math/vec.h"
#include "scene/gaussians.h"

namespace glint {

// Gaussians hashed by the cell of their mean, for radius queries (fastest up to one cell).
class CellGrid {
 public:
  CellGrid(const GaussianScene& scene, std::span<const uint32_t> indices, float cell) : scene_(scene), cell_(cell) {
    for (uint32_t i : indices) add(i);
  }
  void add(uint32_t i) { cells_[keyOf(scene_.position[i])].push_back(i); }
  // Calls visit(i) for every Gaussian whose mean lies within `radius` of p.
  template <typename Visit>
  void near(const Vec3f& p, float radius, Visit&& visit) const {
    const int64_t cx = coordinate(p.x), cy = coordinate(p.y), cz = coordinate(p.z);
    const float r2 = radius * radius;
    const int64_t span = std::max<int64_t>(1, int64_t(std::ceil(radius / cell_)));
    for (int64_t dx = -span; dx <= span; ++dx)
      for (int64_t dy = -span; dy <= span; ++dy)
        for (int64_t dz = -span; dz <= span; ++dz) {
          auto found = cells_.find(key(cx + dx, cy + dy, cz + dz));
          if (found == cells_.end()) continue;
          for (uint32_t i : found->second) {
            Vec3f d = scene_.position[i] - p;
            if (dot(d, d) <= r2) visit(i);
          }
        }
  }

 private:
  int64_t coordinate(float v) const { return int64_t(std::floor(v / cell_)); }
  static uint64_t key(int64_t x, int64_t y, int64_t z) {
    auto bits = [](int64_t v) { return uint64_t(v) & 0x1fffff; };  // 21 bits each
    return bits(x) | (bits(y) << 21) | (bits(z) << 42);
  }
  uint64_t keyOf(const Vec3f& p) const { return key(coordinate(p.x), coordinate(p.y), coordinate(p.z)); }

  const GaussianScene& scene_;
  float cell_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

}  // namespace glint
