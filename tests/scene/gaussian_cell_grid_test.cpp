// The cell grid's radius queries against a scan of every Gaussian, for radii below, at and
// above the cell size (healing widens its plane fits past one cell).
#include "scene/gaussian_cell_grid.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "math/rng.h"

namespace glint {
namespace {

TEST(CellGrid, NearFindsExactlyTheGaussiansWithinTheRadius) {
  GaussianScene scene;
  scene.resize(2000);
  Rng rng(7);
  for (size_t i = 0; i < scene.size(); ++i)
    scene.position[i] = Vec3f(rng.uniform() * 4 - 2, rng.uniform() * 4 - 2, rng.uniform() * 4 - 2);
  std::vector<uint32_t> indices;
  for (uint32_t i = 0; i < scene.size(); i += 2) indices.push_back(i);  // half of them in the grid
  const float cell = 0.3f;
  const CellGrid grid(scene, indices, cell);
  for (float radius : {0.1f, 0.3f, 0.5f, 1.7f}) {
    for (int q = 0; q < 20; ++q) {
      const Vec3f p(rng.uniform() * 4 - 2, rng.uniform() * 4 - 2, rng.uniform() * 4 - 2);
      std::vector<uint32_t> found, expected;
      grid.near(p, radius, [&](uint32_t i) { found.push_back(i); });
      for (uint32_t i : indices)
        if (dot(scene.position[i] - p, scene.position[i] - p) <= radius * radius) expected.push_back(i);
      std::sort(found.begin(), found.end());
      EXPECT_EQ(found, expected) << "radius " << radius << " query " << q;
    }
  }
}

}  // namespace
}  // namespace glint
