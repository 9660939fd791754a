// Points from depth buffers: surface pixels counted per view, then every stride-th kept.
#include "synth/depth_point_cloud.h"

#include <algorithm>
#include <cstring>
#include <span>

#include "core/cluster.h"
#include "core/error.h"
#include "io/transfer.h"
#include "scene/buffers.h"

namespace glint {

namespace {

// A point's colour: the diffuse colour in [0, 1], sRGB-encoded (io/transfer.h).
float srgbEncode(float linear) { return toDisplay(Transfer::Srgb, std::clamp(linear, 0.0f, 1.0f)); }

int64_t surfacePixels(const Image& depth) {
  int64_t count = 0;
  for (float d : depth.pixels) count += hasSurface(d) ? 1 : 0;
  return count;
}

// Keep every stride-th surface pixel to respect maxPoints.
int64_t pointStride(int64_t surface, int maxPoints) {
  return std::max<int64_t>(1, (surface + maxPoints - 1) / std::max(1, maxPoints));
}

// Appends the points of one view; `counter` numbers the surface pixels of all views so far.
void addViewPoints(const DepthView& v, int64_t stride, int64_t* counter, PointCloud* cloud) {
  const Image& depth = v.depth;
  const Image& diffuse = v.diffuse;
  for (int y = 0; y < depth.height; ++y)
    for (int x = 0; x < depth.width; ++x) {
      float d = depth.at(x, y);
      if (!hasSurface(d) || ((*counter)++ % stride) != 0) continue;
      Ray ray = v.camera.generateRay(x + 0.5, y + 0.5);
      cloud->positions.push_back(Vec3f(ray.origin + ray.direction * double(d)));
      Rgb c = diffuse.rgb(x, y);
      cloud->colors.push_back({srgbEncode(c.x), srgbEncode(c.y), srgbEncode(c.z)});
    }
}

}  // namespace

PointCloud pointCloudFromDepth(const std::vector<DepthView>& views, int maxPoints) {
  PointCloud cloud;
  int64_t surface = 0;
  for (const DepthView& v : views) surface += surfacePixels(v.depth);
  if (surface == 0) return cloud;
  const int64_t stride = pointStride(surface, maxPoints);
  int64_t counter = 0;
  for (const DepthView& v : views) addViewPoints(v, stride, &counter, &cloud);
  return cloud;
}

PointCloud pointCloudFromDepthOverRanks(const std::vector<DepthView>& mine, const std::vector<size_t>& index,
                                        size_t viewCount, int maxPoints) {
  GLINT_CHECK(mine.size() == index.size(), "pointCloudFromDepthOverRanks: one index per view");
  if (!cluster::distributed()) return pointCloudFromDepth(mine, maxPoints);
  // Every view's surface pixels on every rank (each count comes from one rank, the others add 0).
  std::vector<int64_t> counts(viewCount, 0);
  for (size_t k = 0; k < mine.size(); ++k) counts[index[k]] = surfacePixels(mine[k].depth);
  cluster::sumInRankOrder(counts);
  int64_t surface = 0;
  for (int64_t c : counts) surface += c;
  if (surface == 0) return PointCloud();
  const int64_t stride = pointStride(surface, maxPoints);
  // This rank's points, each view's numbered as in the one-process scan, sent as
  // (view, point count, positions, colours).
  std::vector<std::byte> bytes;
  auto append = [&](const void* data, size_t size) {
    bytes.resize(bytes.size() + size);
    std::memcpy(bytes.data() + bytes.size() - size, data, size);
  };
  for (size_t k = 0; k < mine.size(); ++k) {
    int64_t counter = 0;
    for (size_t v = 0; v < index[k]; ++v) counter += counts[v];
    PointCloud points;
    addViewPoints(mine[k], stride, &counter, &points);
    const uint64_t header[2] = {index[k], points.positions.size()};
    append(header, sizeof header);
    append(points.positions.data(), points.positions.size() * sizeof(Vec3f));
    append(points.colors.data(), points.colors.size() * sizeof(Rgb));
  }
  const std::vector<std::vector<std::byte>> all = cluster::gatherToRoot(bytes);
  if (!cluster::isRoot()) return PointCloud();
  std::vector<PointCloud> perView(viewCount);
  for (const std::vector<std::byte>& part : all) {
    for (size_t at = 0; at < part.size();) {
      uint64_t header[2];
      std::memcpy(header, part.data() + at, sizeof header);
      at += sizeof header;
      GLINT_CHECK(header[0] < viewCount, "pointCloudFromDepthOverRanks: view out of range");
      PointCloud& points = perView[header[0]];
      points.positions.resize(header[1]);
      points.colors.resize(header[1]);
      std::memcpy(points.positions.data(), part.data() + at, header[1] * sizeof(Vec3f));
      at += header[1] * sizeof(Vec3f);
      std::memcpy(points.colors.data(), part.data() + at, header[1] * sizeof(Rgb));
      at += header[1] * sizeof(Rgb);
    }
  }
  PointCloud cloud;
  for (const PointCloud& points : perView) {  // in view order, as one process scans them
    cloud.positions.insert(cloud.positions.end(), points.positions.begin(), points.positions.end());
    cloud.colors.insert(cloud.colors.end(), points.colors.begin(), points.colors.end());
  }
  return cloud;
}

}  // namespace glint
