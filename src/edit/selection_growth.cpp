// Breadth-first growth of a selection over a hash grid of cells as wide as the growth
// distance, so that each Gaussian looks at its 27 neighbouring cells only.
#include "edit/selection_growth.h"

#include <cmath>
#include <cstdint>
#include <vector>

#include "scene/gaussian_cell_grid.h"

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

}  // namespace

void growSelection(const SelectionGrowth& growth, const GaussianScene& scene, GaussianMask& mask) {
  std::vector<uint32_t> all(scene.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = uint32_t(i);
  const CellGrid grid(scene, all, growth.distance);
  std::vector<Material> materials(scene.size());
  for (size_t i = 0; i < scene.size(); ++i) materials[i] = materialOf(scene, i);
  // Breadth-first from every selected Gaussian; the set reached is the closure of the
  // relation, whatever the order.
  std::vector<uint32_t> frontier;
  for (size_t i = 0; i < mask.size(); ++i)
    if (mask[i]) frontier.push_back(uint32_t(i));
  while (!frontier.empty()) {
    std::vector<uint32_t> next;
    for (uint32_t i : frontier) {
      const Material& material = materials[i];
      grid.near(scene.position[i], growth.distance, [&](uint32_t j) {
        if (mask[j] || !similar(material, materials[j], growth.tolerance)) return;
        mask[j] = 1;
        next.push_back(j);
      });
    }
    frontier = std::move(next);
  }
}

}  // namespace glint
