// Dense initialisation: depth unprojection, voxel binning, point-cloud loading, and the
// initial attributes of every Gaussian.
#include "train/dense_init.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "core/error.h"
#include "core/parallel.h"
#include "io/point_cloud.h"
#include "scene/buffers.h"
#include "scene/capture_dataset.h"
#include "train/camera_volume_init.h"
#include "train/nearest_neighbours.h"
#include "train/scene_extent.h"

namespace glint {

namespace {

// Duplicate points have a neighbour distance of 0, whose log is -infinity; such scales
// are raised to this fraction of the fallback scale (about a voxel), tiny but finite.
constexpr float kMinScaleFraction = 1.0e-4f;

void checkSettings(const DenseInitSettings& s) {
  const char* where = "dense initialisation settings";
  if (s.pixelStride < 0) throw Error(where, "pixel stride must be >= 0 (0 = automatic)");
  if (s.maxPixelSamples < 1) throw Error(where, "the pixel sample budget must be positive");
  if (!(s.voxelFraction > 0.0f) || !std::isfinite(s.voxelFraction))
    throw Error(where, "the voxel size fraction must be a positive number");
  if (s.minSamplesPerVoxel < 1) throw Error(where, "the minimum samples per voxel must be >= 1");
  if (!(s.depthResidualVoxels >= 0.0f) || !std::isfinite(s.depthResidualVoxels))
    throw Error(where, "the voxel size in depth-fit residuals must be a number >= 0");
  if (s.neighbours < 1) throw Error(where, "the neighbour count for scales must be >= 1");
  if (!(s.opacity > 0.0f && s.opacity < 1.0f)) throw Error(where, "the initial opacity must lie in (0, 1)");
  if (!(s.roughness >= 0.0f && s.roughness <= 1.0f)) throw Error(where, "the initial roughness must lie in [0, 1]");
  if (!(s.f0 >= 0.0f && s.f0 <= 1.0f)) throw Error(where, "the initial F0 must lie in [0, 1]");
}

float boundsDiagonal(const std::vector<Vec3f>& points) {
  if (points.empty()) return 0.0f;
  Vec3f lower = points[0], upper = points[0];
  for (const Vec3f& p : points) {
    lower = min(lower, p);
    upper = max(upper, p);
  }
  return length(upper - lower);
}

// The length voxel sizes are measured against: the scene extent, or for a dataset whose
// cameras all sit at one point (extent 0), the size of the points' bounding box.
float referenceLength(float extent, const std::vector<Vec3f>& points) {
  if (extent > 0.0f) return extent;
  float diagonal = boundsDiagonal(points);
  return diagonal > 0.0f ? diagonal : 1.0f;
}

// The median over a capture's aligned views of their fits' median residual; 0 when no view
// of the dataset was aligned (metric depth, or not a capture).
float medianDepthFitResidual(const Dataset& dataset) {
  if (!dataset.capture()) return 0.0f;
  std::vector<double> residuals;
  for (const auto& [view, fit] : dataset.capture()->depthFits())
    if (fit.ok) residuals.push_back(fit.medianAbsResidualAfter);
  if (residuals.empty()) return 0.0f;
  std::nth_element(residuals.begin(), residuals.begin() + residuals.size() / 2, residuals.end());
  return float(residuals[residuals.size() / 2]);
}

}  // namespace

float srgbToLinear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

int automaticPixelStride(int64_t totalPixels, int64_t maxSamples) {
  GLINT_CHECK(maxSamples > 0, "automaticPixelStride: the sample budget must be positive");
  int stride = std::max(1, int(std::ceil(std::sqrt(double(totalPixels) / double(maxSamples)))));
  // Guard against the square root rounding just below the exact answer.
  auto samples = [&](int64_t s) { return ((totalPixels + s * s - 1) / (s * s)); };
  while (samples(stride) > maxSamples) ++stride;
  return stride;
}

ColouredPoints unprojectDepth(const Image& depth, const Image& diffuse, const Camera& camera, int stride,
                              const std::function<bool(size_t pixel)>& trusted, int64_t* untrusted) {
  GLINT_CHECK(stride >= 1, "unprojectDepth: stride must be positive");
  GLINT_CHECK(depth.width == diffuse.width && depth.height == diffuse.height,
              "unprojectDepth: depth and diffuse sizes differ");
  ColouredPoints out;
  int64_t refused = 0;
  for (int y = stride / 2; y < depth.height; y += stride)
    for (int x = stride / 2; x < depth.width; x += stride) {
      float d = depth.at(x, y);
      if (!hasSurface(d)) continue;
      if (trusted && !trusted(size_t(y) * size_t(depth.width) + size_t(x))) {
        ++refused;
        continue;
      }
      Ray ray = camera.generateRay(x + 0.5, y + 0.5);
      out.positions.push_back(Vec3f(ray.origin + ray.direction * double(d)));
      out.colours.push_back(diffuse.rgb(x, y));
    }
  if (untrusted) *untrusted = refused;
  return out;
}

ColouredPoints mergeInVoxels(const ColouredPoints& points, float voxelSize, int minSamples, int64_t* occupiedVoxels) {
  GLINT_CHECK(voxelSize > 0.0f, "mergeInVoxels: voxel size must be positive");
  GLINT_CHECK(points.positions.size() == points.colours.size(), "mergeInVoxels: one colour per point expected");
  // Sort the points by (voxel, index): each voxel's points become one run, visited in
  // input order, so the sums below do not depend on how the points were produced.
  struct Entry {
    int64_t x, y, z;
    size_t index;
  };
  std::vector<Entry> entries(points.positions.size());
  const double inverse = 1.0 / double(voxelSize);
  for (size_t i = 0; i < entries.size(); ++i) {
    const Vec3f& p = points.positions[i];
    entries[i] = {int64_t(std::floor(p.x * inverse)), int64_t(std::floor(p.y * inverse)),
                  int64_t(std::floor(p.z * inverse)), i};
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return std::tie(a.x, a.y, a.z, a.index) < std::tie(b.x, b.y, b.z, b.index);
  });

  ColouredPoints merged;
  int64_t occupied = 0;
  for (size_t begin = 0; begin < entries.size();) {
    size_t end = begin + 1;
    while (end < entries.size() && entries[end].x == entries[begin].x && entries[end].y == entries[begin].y &&
           entries[end].z == entries[begin].z)
      ++end;
    ++occupied;
    if (int64_t(end - begin) >= minSamples) {
      Vec3d position(0.0), colour(0.0);
      for (size_t e = begin; e < end; ++e) {
        position += Vec3d(points.positions[entries[e].index]);
        colour += Vec3d(points.colours[entries[e].index]);
      }
      double count = double(end - begin);
      merged.positions.push_back(Vec3f(position / count));
      merged.colours.push_back(Rgb(colour / count));
    }
    begin = end;
  }
  if (occupiedVoxels) *occupiedVoxels = occupied;
  return merged;
}

GaussianScene gaussiansAtPoints(const ColouredPoints& points, const DenseInitSettings& settings, float soloScale) {
  GLINT_CHECK(points.positions.size() == points.colours.size(), "gaussiansAtPoints: one colour per point expected");
  GLINT_CHECK(soloScale > 0.0f, "gaussiansAtPoints: the fallback scale must be positive");
  const size_t n = points.positions.size();
  std::vector<float> distances = meanNeighbourDistances(points.positions, settings.neighbours);
  const float minScale = kMinScaleFraction * soloScale;

  GaussianScene scene;
  scene.resize(n);
  for (size_t i = 0; i < n; ++i) {
    float scale = n == 1 ? soloScale : std::max(distances[i], minScale);
    scene.position[i] = points.positions[i];
    scene.rotation[i] = Quatf{};  // identity: the scale is isotropic anyway
    scene.logScale[i] = Vec3f(std::log(scale));
    scene.opacityLogit[i] = logit(settings.opacity);
    scene.diffuse[i] = points.colours[i];
    scene.normal[i] = Vec3f(0.0f);  // no normal yet: learned from the normal buffers
    scene.roughness[i] = settings.roughness;
    scene.f0[i] = Rgb(settings.f0);
  }
  return scene;
}

DenseInit initFromDepthBuffers(const Dataset& dataset, const DenseInitSettings& settings, const DepthTrust& trusted) {
  checkSettings(settings);
  const DatasetSplit& split = dataset.train();
  DenseInit result;
  result.stats.source = InitSource::DepthBuffers;
  result.stats.sceneExtent = sceneExtent(split);
  int64_t totalPixels = 0;
  for (size_t v = 0; v < split.views.size(); ++v)
    totalPixels += int64_t(split.camera(v).width) * int64_t(split.camera(v).height);
  // Colours come from the diffuse buffers, or the photographs when a capture has none.
  const Buffer colour = dataset.findBufferFile(split.views[0], Buffer::Diffuse) ? Buffer::Diffuse : Buffer::Render;
  const int stride =
      settings.pixelStride > 0 ? settings.pixelStride : automaticPixelStride(totalPixels, settings.maxPixelSamples);
  result.stats.pixelStride = stride;

  // Views are independent; concatenating them in view order keeps the sample order, and
  // so everything after it, independent of the thread count.
  std::vector<ColouredPoints> perView(split.views.size());
  std::vector<int64_t> untrusted(split.views.size(), 0);
  parallelFor(int64_t(split.views.size()), 1, [&](int64_t i) {
    Image depth = dataset.loadBuffer(split, size_t(i), Buffer::Depth);
    Image diffuse = dataset.loadBuffer(split, size_t(i), colour);
    std::function<bool(size_t)> viewTrusted;
    if (trusted) viewTrusted = [&trusted, i](size_t pixel) { return trusted(size_t(i), pixel); };
    perView[size_t(i)] =
        unprojectDepth(depth, diffuse, split.camera(size_t(i)), stride, viewTrusted, &untrusted[size_t(i)]);
  });
  for (int64_t n : untrusted) result.stats.samplesUntrusted += n;
  ColouredPoints samples;
  for (ColouredPoints& view : perView) {
    samples.positions.insert(samples.positions.end(), view.positions.begin(), view.positions.end());
    samples.colours.insert(samples.colours.end(), view.colours.begin(), view.colours.end());
    view = {};
  }
  result.stats.pointsUnprojected = int64_t(samples.positions.size());
  const std::string depthFolder = (dataset.root() / "train" / "depth").string();
  if (samples.positions.empty() && result.stats.samplesUntrusted > 0)
    throw Error(depthFolder, "the multi-view consistency check trusts none of the " +
                                 std::to_string(result.stats.samplesUntrusted) +
                                 " sampled surface pixels of the training depth buffers: nothing to initialise the "
                                 "scene from (raise loss.depth_consistency, or set init.consistent_depth_only false)");
  if (samples.positions.empty())
    throw Error(depthFolder, "no sampled pixel of the training depth buffers has a surface (depth 0 or >= 1e9 "
                             "everywhere): nothing to initialise the scene from");

  float voxelSize = settings.voxelFraction * referenceLength(result.stats.sceneExtent, samples.positions);
  // Loading the depth buffers aligned a capture's relative depth: its voxels are no finer
  // than the alignment is accurate.
  result.stats.depthResidual = medianDepthFitResidual(dataset);
  voxelSize = std::max(voxelSize, settings.depthResidualVoxels * result.stats.depthResidual);
  result.stats.voxelSize = voxelSize;
  ColouredPoints kept = mergeInVoxels(samples, voxelSize, settings.minSamplesPerVoxel, &result.stats.voxelsOccupied);
  result.stats.voxelsKept = int64_t(kept.positions.size());
  if (kept.positions.empty())
    throw Error(depthFolder, "no voxel of edge " + std::to_string(voxelSize) + " was hit by " +
                                 std::to_string(settings.minSamplesPerVoxel) + " or more of the " +
                                 std::to_string(samples.positions.size()) +
                                 " depth samples; use larger voxels or a lower threshold");
  result.scene = gaussiansAtPoints(kept, settings, voxelSize);
  return result;
}

// Gaussians at coloured points (a point cloud file, or a capture's sparse points).
DenseInit initFromPoints(const Dataset& dataset, ColouredPoints points, const DenseInitSettings& settings) {
  DenseInit result;
  result.stats.source = InitSource::PointCloud;
  result.stats.sceneExtent = sceneExtent(dataset.train());
  result.stats.pointsUnprojected = int64_t(points.positions.size());
  // The voxel size of the depth path: the scale of a point without neighbours and the
  // reference for the smallest scale.
  float soloScale = settings.voxelFraction * referenceLength(result.stats.sceneExtent, points.positions);
  result.scene = gaussiansAtPoints(points, settings, soloScale);
  return result;
}

DenseInit initFromPointCloud(const Dataset& dataset, const DenseInitSettings& settings) {
  checkSettings(settings);
  std::optional<std::filesystem::path> path = dataset.pointCloudPath();
  if (!path) throw Error((dataset.root() / "point_cloud_dense.ply").string(), "file not found");
  PointCloud cloud = readPointCloud(*path);
  if (cloud.positions.empty()) throw Error(path->string(), "has no points: nothing to initialise the scene from");
  if (cloud.colors.size() != cloud.positions.size())
    throw Error(path->string(), "has no red/green/blue colours; initialisation needs them (or use the depth buffers)");

  ColouredPoints points;
  points.positions = std::move(cloud.positions);
  points.colours.reserve(cloud.colors.size());
  for (size_t i = 0; i < points.positions.size(); ++i) {
    if (!isFinite(points.positions[i]))
      throw Error(path->string(), "vertex " + std::to_string(i) + " has a non-finite position");
    const Rgb& c = cloud.colors[i];
    points.colours.push_back({srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z)});
  }
  return initFromPoints(dataset, std::move(points), settings);
}

DenseInit initFromSparsePoints(const Dataset& dataset, const DenseInitSettings& settings) {
  checkSettings(settings);
  const CaptureSource* capture = dataset.capture();
  if (!capture || capture->points.empty())
    throw Error(dataset.root().string(), "has no depth buffers and no sparse points (points3D) to initialise from");
  ColouredPoints points;
  for (size_t i = 0; i < capture->points.size(); ++i) {
    points.positions.push_back(Vec3f(capture->points[i]));
    points.colours.push_back(capture->pointColours[i]);
  }
  DenseInit init = initFromPoints(dataset, std::move(points), settings);
  init.stats.source = InitSource::SparsePoints;
  return init;
}

DenseInit denseInitialisation(const Dataset& dataset, const DenseInitSettings& settings, const DepthTrust& trusted) {
  if (!settings.forceDepthBuffers && dataset.pointCloudPath()) return initFromPointCloud(dataset, settings);
  const bool hasDepth = dataset.findBufferFile(dataset.train().views.at(0), Buffer::Depth).has_value();
  if (!hasDepth && dataset.capture() && !dataset.capture()->points.empty())
    return initFromSparsePoints(dataset, settings);
  // --init depth on a dataset without depth goes on to the error naming the missing buffers.
  if (!hasDepth && !settings.forceDepthBuffers) return initInCameraVolume(dataset, settings);
  return initFromDepthBuffers(dataset, settings, trusted);
}

}  // namespace glint
