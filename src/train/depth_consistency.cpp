// Multi-view agreement of per-view depth targets (see the header).
#include "train/depth_consistency.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/parallel.h"
#include "scene/predicted_buffers.h"

namespace glint {

namespace {

constexpr int kOverlapSamplesPerSide = 16;  // the grid that ranks neighbours: about 256 pixels

// The point a view's depth puts at a pixel's centre.
Vec3d depthPoint(const Camera& camera, size_t pixel, double depth) {
  const size_t x = pixel % size_t(camera.width), y = pixel / size_t(camera.width);
  const Ray ray = camera.generateRay(double(x) + 0.5, double(y) + 0.5);
  return ray.origin + ray.direction * depth;
}

// View u's depth (ray distance) at the continuous pixel position p. Where the four pixel
// centres around p all have depth within kOneSurfaceSpread of each other, their inverse
// z-depths are interpolated bilinearly (exact on planes, whose 1/z is affine in the pixel);
// elsewhere (an edge: mixing two surfaces would match neither) the pixel containing p's.
// 0 where that pixel has none.
constexpr double kOneSurfaceSpread = 0.1;
double depthAt(const Camera& camera, const DepthLookup& depth, size_t u, const Vec2d& p) {
  const int w = camera.width, h = camera.height;
  const double gx = p.x - 0.5, gy = p.y - 0.5;
  const int x0 = int(std::floor(gx)), y0 = int(std::floor(gy));
  if (x0 >= 0 && y0 >= 0 && x0 + 1 < w && y0 + 1 < h) {
    double d[4];
    bool surface = true;
    for (int k = 0; k < 4; ++k) {
      d[k] = depth(u, size_t(y0 + k / 2) * size_t(w) + size_t(x0 + k % 2));
      surface = surface && d[k] > 0.0;
    }
    if (surface) {
      const double lo = std::min({d[0], d[1], d[2], d[3]}), hi = std::max({d[0], d[1], d[2], d[3]});
      if (hi <= lo * (1.0 + kOneSurfaceSpread)) {
        const RayIntrinsics k{camera.fx, camera.fy, camera.cx, camera.cy};
        double inverseZ[4];
        for (int c = 0; c < 4; ++c) inverseZ[c] = rayLengthPerZ(k, x0 + c % 2, y0 + c / 2) / d[c];
        const double fx = gx - x0, fy = gy - y0;
        const double inverseZAtP = (inverseZ[0] * (1 - fx) + inverseZ[1] * fx) * (1 - fy) +
                                   (inverseZ[2] * (1 - fx) + inverseZ[3] * fx) * fy;
        return length(cameraRay(k, p.x, p.y)) / inverseZAtP;
      }
    }
  }
  const int x = std::clamp(int(p.x), 0, w - 1), y = std::clamp(int(p.y), 0, h - 1);
  return depth(u, size_t(y) * size_t(w) + size_t(x));
}

}  // namespace

std::vector<uint32_t> overlappingViews(std::span<const Camera> cameras, const DepthLookup& depth, size_t v,
                                       int count) {
  const Camera& camera = cameras[v];
  std::vector<Vec3d> points;
  for (int j = 0; j < kOverlapSamplesPerSide; ++j)
    for (int i = 0; i < kOverlapSamplesPerSide; ++i) {
      const size_t x = size_t((i + 0.5) * camera.width / kOverlapSamplesPerSide);
      const size_t y = size_t((j + 0.5) * camera.height / kOverlapSamplesPerSide);
      const size_t pixel = y * size_t(camera.width) + x;
      if (const float d = depth(v, pixel); d > 0.0f) points.push_back(depthPoint(camera, pixel, d));
    }
  std::vector<std::pair<int, uint32_t>> seen;  // (-overlap, view): sorts most first, then by index
  for (size_t u = 0; u < cameras.size(); ++u) {
    if (u == v) continue;
    const Mat4 worldToCamera = cameras[u].cameraToWorld.inverse();
    int overlap = 0;
    for (const Vec3d& x : points) {
      Vec2d p;
      if (!cameras[u].project(worldToCamera, x, &p)) continue;
      const double d = depthAt(cameras[u], depth, u, p);
      if (d > 0.0 && std::abs(length(x - cameras[u].position()) - d) <= kOverlapGap * d) ++overlap;
    }
    if (overlap > 0) seen.push_back({-overlap, uint32_t(u)});
  }
  std::sort(seen.begin(), seen.end());
  std::vector<uint32_t> views;
  for (size_t k = 0; k < seen.size() && int(k) < count; ++k) views.push_back(seen[k].second);
  return views;
}

DepthConsistency checkDepthConsistency(std::span<const Camera> cameras, const DepthLookup& depth,
                                       const DepthConsistencyOptions& options) {
  const size_t n = cameras.size();
  DepthConsistency result;
  result.agreeing.resize(n);
  result.neighbours.resize(n);
  std::vector<int64_t> depthPixels(n, 0), trustedPixels(n, 0);
  parallelFor(int64_t(n), 1, [&](int64_t vi) {
    const size_t v = size_t(vi);
    const Camera& camera = cameras[v];
    std::vector<uint32_t>& neighbours = result.neighbours[v];
    neighbours = overlappingViews(cameras, depth, v, options.neighbours);
    std::vector<Mat4> worldToCamera;
    for (uint32_t u : neighbours) worldToCamera.push_back(cameras[u].cameraToWorld.inverse());
    std::vector<uint8_t>& agreeing = result.agreeing[v];
    agreeing.assign(size_t(camera.width) * size_t(camera.height), 0);
    for (size_t pixel = 0; pixel < agreeing.size(); ++pixel) {
      const float d = depth(v, pixel);
      if (!(d > 0.0f)) continue;
      ++depthPixels[v];
      const Vec3d x = depthPoint(camera, pixel, d);
      int agree = 0;
      for (size_t k = 0; k < neighbours.size(); ++k) {
        const Camera& other = cameras[neighbours[k]];
        Vec2d p;
        if (!other.project(worldToCamera[k], x, &p)) continue;
        const double du = depthAt(other, depth, neighbours[k], p);
        if (du > 0.0 && std::abs(length(x - other.position()) - du) <= options.tolerance * du) ++agree;
      }
      agreeing[pixel] = uint8_t(std::min(agree, 255));
      if (agree >= options.minAgreeing) ++trustedPixels[v];
    }
  });
  result.depthPixels = std::accumulate(depthPixels.begin(), depthPixels.end(), int64_t(0));
  result.trustedPixels = std::accumulate(trustedPixels.begin(), trustedPixels.end(), int64_t(0));
  return result;
}

}  // namespace glint
