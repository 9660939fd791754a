// Light regions: the brightest surface Gaussians, linked where their footprints touch, each
// cluster bounded by a sphere.
#include "render/light_regions.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

#include "math/percentile.h"
#include "math/sampling.h"
#include "scene/gaussian_cell_grid.h"

namespace glint {

namespace {

// Union-find with path halving over light indices.
uint32_t rootOf(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

std::vector<LightRegion> lightRegionsOf(const GaussianScene& scene, const LightRegionSettings& settings) {
  if (!(settings.factor > 0) || settings.maxRegions <= 0) return {};
  // The surfaces set the scale of brightness and size: far-field Gaussians (no normal) are a
  // backdrop. Lights need no normal: a trained emitter's often has none (its ground truth
  // gives it none), like the ceiling lamps of the Blender spheres_room.
  auto isSurface = [&](size_t i) {
    return length(scene.normal[i]) >= settings.minNormalLength && scene.opacity(i) >= settings.minOpacity;
  };
  std::vector<float> surfaceLuminance, surfaceSigma;
  for (size_t i = 0; i < scene.size(); ++i)
    if (isSurface(i)) {
      surfaceLuminance.push_back(luminance(scene.diffuse[i]));
      const Vec3f s = scene.scale(i);
      surfaceSigma.push_back(std::max({s.x, s.y, s.z}));
    }
  if (surfaceLuminance.empty()) return {};
  const float threshold = settings.factor * percentileOf(surfaceLuminance, 0.9);
  const float largestSigma = percentileOf(surfaceSigma, 0.99);
  if (!(threshold > 0) || !std::isfinite(threshold)) return {};

  std::vector<uint32_t> lights;
  std::vector<float> sigma;  // largest standard deviation of each light
  for (size_t i = 0; i < scene.size(); ++i) {
    if (!(scene.opacity(i) >= settings.minOpacity) || !(luminance(scene.diffuse[i]) >= threshold)) continue;
    const Vec3f s = scene.scale(i);
    const float largest = std::max({s.x, s.y, s.z});
    if (largest > largestSigma) continue;
    lights.push_back(uint32_t(i));
    sigma.push_back(largest);
  }
  if (lights.empty()) return {};

  // Lights i and j link when their means lie within linkSigmas x 2 x min(sigma_i, sigma_j):
  // each light looks within 2 linkSigmas of its own sigma and links to those no larger than
  // it within their own reach. Cells as wide as most queries; wider ones span several cells.
  std::vector<float> reach(sigma.size());
  for (size_t k = 0; k < sigma.size(); ++k) reach[k] = 2.0f * settings.linkSigmas * sigma[k];
  const float cell = std::max(percentileOf(reach, 0.9), 1e-6f);
  const CellGrid grid(scene, lights, cell);
  std::vector<uint32_t> lightOf(scene.size(), UINT32_MAX);
  for (size_t k = 0; k < lights.size(); ++k) lightOf[lights[k]] = uint32_t(k);
  std::vector<uint32_t> parent(lights.size());
  std::iota(parent.begin(), parent.end(), 0u);
  for (size_t k = 0; k < lights.size(); ++k)
    grid.near(scene.position[lights[k]], reach[k], [&](uint32_t g) {
      const uint32_t j = lightOf[g];
      if (sigma[j] > sigma[k] || length(scene.position[g] - scene.position[lights[k]]) > reach[j]) return;
      const uint32_t a = rootOf(parent, uint32_t(k)), b = rootOf(parent, j);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    });

  // Each cluster: its power, its power-weighted centre, then the sphere around it.
  std::vector<LightRegion> regions;
  std::vector<uint32_t> regionOf(lights.size(), UINT32_MAX);
  std::vector<Vec3d> weightedSum;
  std::vector<double> power;
  std::vector<float> brightest;  // each region's largest luminance
  auto powerOf = [&](size_t k) {
    const uint32_t g = lights[k];
    Vec3f s = scene.scale(g);
    const float smallest = std::min({s.x, s.y, s.z});
    // The footprint is the ellipse of the two largest axes: their product is the product of
    // all three over the smallest.
    const float area = kPi * s.x * s.y * s.z / std::max(smallest, 1e-12f);
    return double(luminance(scene.diffuse[g])) * scene.opacity(g) * area;
  };
  for (size_t k = 0; k < lights.size(); ++k) {
    const uint32_t root = rootOf(parent, uint32_t(k));
    if (regionOf[root] == UINT32_MAX) {
      regionOf[root] = uint32_t(regions.size());
      regions.emplace_back();
      weightedSum.emplace_back(0.0);
      power.push_back(0.0);
      brightest.push_back(0.0f);
    }
    brightest[regionOf[root]] = std::max(brightest[regionOf[root]], luminance(scene.diffuse[lights[k]]));
  }
  auto inCore = [&](size_t k, uint32_t r) {
    return luminance(scene.diffuse[lights[k]]) >= settings.coreFraction * brightest[r];
  };
  for (size_t k = 0; k < lights.size(); ++k) {
    const uint32_t r = regionOf[rootOf(parent, uint32_t(k))];
    if (!inCore(k, r)) continue;
    const double p = std::max(powerOf(k), 1e-30);
    weightedSum[r] += Vec3d(scene.position[lights[k]]) * p;
    power[r] += p;
  }
  for (size_t r = 0; r < regions.size(); ++r) {
    regions[r].centre = Vec3f(weightedSum[r] * (1.0 / power[r]));
    regions[r].power = float(power[r]);
  }
  for (size_t k = 0; k < lights.size(); ++k) {
    const uint32_t r = regionOf[rootOf(parent, uint32_t(k))];
    if (!inCore(k, r)) continue;
    regions[r].radius = std::max(regions[r].radius, length(scene.position[lights[k]] - regions[r].centre) +
                                                        settings.boundSigmas * sigma[k]);
  }
  // Most powerful first; ties by position, so the order never depends on the scene's.
  std::sort(regions.begin(), regions.end(), [](const LightRegion& a, const LightRegion& b) {
    if (a.power != b.power) return a.power > b.power;
    return std::tie(a.centre.x, a.centre.y, a.centre.z) < std::tie(b.centre.x, b.centre.y, b.centre.z);
  });
  if (regions.size() > size_t(settings.maxRegions)) regions.resize(size_t(settings.maxRegions));
  return regions;
}

}  // namespace glint
