// Multi-view agreement of per-view depth targets: a pixel's depth is trusted when enough of
// its view's neighbours see the point it puts in space at the depth they record themselves.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "scene/camera.h"

namespace glint {

constexpr int kDepthConsistencyNeighbours = 8;

struct DepthConsistencyOptions {
  // A point X agrees with view u when |t_u(X) - D_u| <= tolerance * D_u, t_u(X) the distance
  // from u's centre and D_u u's depth (ray distance) where X projects, interpolated.
  double tolerance = 0.02;
  int minAgreeing = 2;  // neighbours that must agree for a pixel's depth to be trusted
  int neighbours = kDepthConsistencyNeighbours;  // views each view is checked against: those that see most of it
};

// A view's depth (distance along the pixel's ray) at a row-major pixel, 0 where it has none.
using DepthLookup = std::function<float(size_t view, size_t pixel)>;

struct DepthConsistency {
  // Per view, per row-major pixel: how many neighbours agree with its depth (0 without one).
  std::vector<std::vector<uint8_t>> agreeing;
  // Per view, the views it was checked against, most overlapping first.
  std::vector<std::vector<uint32_t>> neighbours;
  int64_t depthPixels = 0;    // pixels with a depth, over all views
  int64_t trustedPixels = 0;  // of those, the ones with minAgreeing or more agreeing neighbours
};

// The views that see most of view v's depth: a grid of about 256 of its depth pixels is put
// in space, and each other view counts those that land in its image within kOverlapGap of
// its own depth there (not hidden behind another surface). The `count` views with the most,
// none with zero, most first (ties by index).
constexpr double kOverlapGap = 0.25;
std::vector<uint32_t> overlappingViews(std::span<const Camera> cameras, const DepthLookup& depth, size_t v,
                                       int count);

// Every view's depth pixels against their neighbours' (overlappingViews), in parallel. A
// pixel whose point falls outside a neighbour's image, or where the neighbour has no depth,
// counts for neither side: depth seen by fewer than minAgreeing neighbours is not trusted,
// since nothing confirms it.
DepthConsistency checkDepthConsistency(std::span<const Camera> cameras, const DepthLookup& depth,
                                       const DepthConsistencyOptions& options);

}  // namespace glint
