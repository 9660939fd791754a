// Breadth-first growth of a selection over a hash grid of cells as wide as the growth
// distance, so that each Gaussian looks at its 27 neighbouring cells only.
#include "edit/selection_growth.h"

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace glint {

namespace {

struct Material {
  float diffuse, f0, roughness;
};

Material materialOf(const GaussianScene& scene, size_t i) {
  auto mean = [](const Rgb& c) { return (c.x + c.y + c.z) / 3.0f; };
  return {mean(scene.diffuse[i]), mean(scene.f0[i]), scene.roughness[i]};
}

bool similar(const Material& a, const Material& b, float tolerance) {
  return std::abs(a.diffuse - b.diffuse) <= tolerance && std::abs(a.f0 - b.f0) <= tolerance &&
         std::abs(a.roughness - b.roughness) <= tolerance;
}

// The key of the cell holding integer coordinates (x, y, z).
uint64_t cellKey(int64_t x, int64_t y, int64_t z) {
  auto bits = [](int64_t v) { return uint64_t(v) & 0x1fffff; };  // 21 bits each
  return bits(x) | (bits(y) << 21) | (bits(z) << 42);
}

}  // namespace

void growSelection(const SelectionGrowth& growth, const GaussianScene& scene, GaussianMask& mask) {
  const float cell = growth.distance;
  auto coordinate = [&](float v) { return int64_t(std::floor(v / cell)); };
  std::unordered_map<uint64_t, std::vector<uint32_t>> grid;
  for (size_t i = 0; i < scene.size(); ++i) {
    const Vec3f& p = scene.position[i];
    grid[cellKey(coordinate(p.x), coordinate(p.y), coordinate(p.z))].push_back(uint32_t(i));
  }
  std::vector<Material> materials(scene.size());
  for (size_t i = 0; i < scene.size(); ++i) materials[i] = materialOf(scene, i);
  // Breadth-first from every selected Gaussian; the set reached is the closure of the
  // relation, whatever the order.
  std::vector<uint32_t> frontier;
  for (size_t i = 0; i < mask.size(); ++i)
    if (mask[i]) frontier.push_back(uint32_t(i));
  const float distanceSquared = growth.distance * growth.distance;
  while (!frontier.empty()) {
    std::vector<uint32_t> next;
    for (uint32_t i : frontier) {
      const Vec3f& p = scene.position[i];
      const Material& material = materials[i];
      const int64_t cx = coordinate(p.x), cy = coordinate(p.y), cz = coordinate(p.z);
      for (int64_t dx = -1; dx <= 1; ++dx)
        for (int64_t dy = -1; dy <= 1; ++dy)
          for (int64_t dz = -1; dz <= 1; ++dz) {
            auto found = grid.find(cellKey(cx + dx, cy + dy, cz + dz));
            if (found == grid.end()) continue;
            for (uint32_t j : found->second) {
              if (mask[j]) continue;
              Vec3f d = scene.position[j] - p;
              if (dot(d, d) > distanceSquared || !similar(material, materials[j], growth.tolerance)) continue;
              mask[j] = 1;
              next.push_back(j);
            }
          }
    }
    frontier = std::move(next);
  }
}

}  // namespace glint
