// Dense initialisation (paper appendix "Dense Initialization", after EDGS): the starting
// GaussianScene of training, built from the training depth buffers binned in a voxel grid,
// or from the dataset's point_cloud_dense.ply when it has one.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "io/image.h"
#include "math/vec.h"
#include "scene/camera.h"
#include "scene/dataset.h"
#include "scene/gaussians.h"

namespace glint {

// The most depth samples the dense initialisation may take (init.max_pixel_samples): 100x
// the default, about 4 GB of samples before voxelisation.
inline constexpr int64_t kMaxInitialSamples = 100'000'000;

struct DenseInitSettings {
  // Unproject every pixelStride-th pixel along x and y (a reduced resolution). 0 picks the
  // smallest stride that keeps at most maxPixelSamples pixels over all training views:
  // stride 2 for 100 views of 160x120 (480k samples), 12 for 200 views of 800x800.
  int pixelStride = 0;
  int64_t maxPixelSamples = 1000000;
  // Voxel edge as a fraction of the scene extent (3DGS camera radius). On builtin:spheres
  // at 160x120 (extent 3.39 m) 1/256 makes 1.3 cm voxels, about the spacing of stride-2
  // samples on the nearer surfaces, and keeps 95.7k of 284k occupied voxels from 480k
  // samples: near the most any edge gives there (1/128: 83.9k, 1/384: 81.6k, 1/512: 63.0k;
  // larger voxels merge more, smaller ones fall below two samples).
  float voxelFraction = 1.0f / 256.0f;
  int minSamplesPerVoxel = 2;  // voxels hit fewer times are dropped as unreliable
  // For a capture whose relative depth was aligned to its sparse points, the voxel edge is
  // at least this many times the median of the views' fit residuals (median |z' - z| at
  // the points): two views' depths of one surface disagree by about that much, and voxels
  // much smaller than the disagreement catch one sample each and are dropped as
  // unreliable, which left 2,271 of 434,485 voxels of a monocular-like capture (docs/
  // captures.md). 0 keeps voxelFraction alone.
  float depthResidualVoxels = 2.0f;
  int neighbours = 3;          // the initial scale is the mean distance to this many neighbours
  float opacity = 0.1f;
  float roughness = 0.1f;
  float f0 = 0.04f;
  bool forceDepthBuffers = false;  // ignore point_cloud_dense.ply even when present
};

// CameraVolume: random points where the cameras look (train/camera_volume_init.h).
// SparsePoints: a capture's points3D, for captures without depth.
enum class InitSource { DepthBuffers, PointCloud, SparsePoints, CameraVolume };

struct DenseInitStats {
  InitSource source = InitSource::DepthBuffers;
  int pixelStride = 0;            // depth buffers only
  int64_t pointsUnprojected = 0;  // surface samples taken from the depth buffers, or points in the cloud
  int64_t voxelsOccupied = 0;     // depth buffers only
  int64_t voxelsKept = 0;         // depth buffers only: voxels with enough samples, one Gaussian each
  float voxelSize = 0.0f;         // depth buffers only
  float depthResidual = 0.0f;     // depth buffers of a capture: the fits' median residual (0: none)
  float sceneExtent = 0.0f;
  int64_t shellGaussians = 0;     // camera volume only: the background shell
  int64_t samplesUntrusted = 0;   // depth buffers only: sampled surface pixels the DepthTrust left out
};

struct DenseInit {
  GaussianScene scene;
  DenseInitStats stats;
};

// Points with a linear colour each.
struct ColouredPoints {
  std::vector<Vec3f> positions;
  std::vector<Rgb> colours;
};

// Whether a training view's depth at a row-major pixel may be unprojected: the multi-view
// consistency check's verdict (TrainingViews::depthTrusted, TrainConfig::initConsistentDepthOnly).
// Empty: every surface pixel may.
using DepthTrust = std::function<bool(size_t view, size_t pixel)>;

// Uses point_cloud_dense.ply when present (unless settings.forceDepthBuffers), else the
// training depth buffers, else (a capture without depth) the sparse points, else (final
// images only) random points in the cameras' view volume.
// `trusted` applies to the depth buffers only.
DenseInit denseInitialisation(const Dataset& dataset, const DenseInitSettings& settings = {},
                              const DepthTrust& trusted = {});
// The two sources on their own. Throw Error naming the file for unusable input (no
// surface pixels at all, an empty or colourless or non-finite point cloud).
// initFromDepthBuffers unprojects only the pixels `trusted` allows (all when it is empty).
DenseInit initFromDepthBuffers(const Dataset& dataset, const DenseInitSettings& settings = {},
                               const DepthTrust& trusted = {});
DenseInit initFromPointCloud(const Dataset& dataset, const DenseInitSettings& settings = {});
// A capture's sparse points (COLMAP's points3D), for captures without depth buffers.
DenseInit initFromSparsePoints(const Dataset& dataset, const DenseInitSettings& settings = {});

// Building blocks, exposed for tests and tools.
// The stride that keeps at most maxSamples of totalPixels (a square sub-grid), at least 1.
int automaticPixelStride(int64_t totalPixels, int64_t maxSamples);
// Surface points of the pixels (x, y) with x % stride == y % stride == stride / 2: along
// the pixel-centre ray at the stored depth (a distance along the ray), coloured by the
// diffuse buffer. No-surface pixels are skipped, and so are those `trusted` (given the
// row-major pixel) refuses; `untrusted`, if given, receives how many it refused.
ColouredPoints unprojectDepth(const Image& depth, const Image& diffuse, const Camera& camera, int stride,
                              const std::function<bool(size_t pixel)>& trusted = {}, int64_t* untrusted = nullptr);
// Bins points in a world-aligned voxel grid of edge voxelSize and returns, for each voxel
// holding at least minSamples points, the mean position and mean colour of its points
// (ordered by voxel coordinates). occupiedVoxels, if given, receives the number of
// non-empty voxels.
ColouredPoints mergeInVoxels(const ColouredPoints& points, float voxelSize, int minSamples,
                             int64_t* occupiedVoxels = nullptr);
// One isotropic Gaussian per point with the settings' attributes; scale = mean distance to
// the settings.neighbours nearest points (soloScale when there is a single point).
GaussianScene gaussiansAtPoints(const ColouredPoints& points, const DenseInitSettings& settings, float soloScale);

// IEC 61966-2-1 sRGB decoding (the piecewise curve, not a 2.2 power); the point cloud's
// 8-bit colours are sRGB-encoded (glint synth writes them so, like COLMAP's).
float srgbToLinear(float encoded);

}  // namespace glint
