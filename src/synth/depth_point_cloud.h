// The point cloud of a synthesized dataset: the training views' depth buffers unprojected and
// thinned to at most a given number of points, in one process or from the views every rank
// of an MPI job rendered (the same points either way).
#pragma once

#include <cstdint>
#include <vector>

#include "io/image.h"
#include "io/point_cloud.h"
#include "scene/camera.h"

namespace glint {

// A view's depth and diffuse buffers, and its camera.
struct DepthView {
  Image depth;
  Image diffuse;
  Camera camera;
};

// Unprojects the depth buffers of views into points coloured by their diffuse buffer
// (sRGB-encoded), keeping every k-th surface pixel (in scan order across the views) so that
// at most maxPoints remain.
PointCloud pointCloudFromDepth(const std::vector<DepthView>& views, int maxPoints);

// The same cloud when the views are spread over the ranks: `mine` are this rank's, `index`
// their places in the list of all `viewCount` views (ascending). The cloud arrives on rank 0;
// the other ranks get an empty one. Collective.
PointCloud pointCloudFromDepthOverRanks(const std::vector<DepthView>& mine, const std::vector<size_t>& index,
                                        size_t viewCount, int maxPoints);

}  // namespace glint
