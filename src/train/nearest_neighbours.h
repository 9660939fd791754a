// Exact k-nearest-neighbour distances (a k-d tree), used to size the initial Gaussians by
// how densely their points sample the surface.
#pragma once

#include <vector>

#include "math/vec.h"

namespace glint {

// For each point, the mean Euclidean distance to its k nearest other points (a point is
// never its own neighbour; duplicates count, at distance 0). With fewer than k + 1 points
// the mean runs over all other points; a lone point gets 0. Exact, deterministic and
// independent of the thread count.
std::vector<float> meanNeighbourDistances(const std::vector<Vec3f>& points, int k);

}  // namespace glint
