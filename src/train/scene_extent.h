// The scene's size as 3D Gaussian Splatting measures it from the training cameras
// (getNerfppNorm): it scales learning rates, voxel sizes and other lengths in training.
#pragma once

#include "math/vec.h"
#include "scene/dataset.h"

namespace glint {

// A sphere around the training cameras: centre = mean of the camera centres, radius =
// 1.1 x the largest distance of a camera centre from that mean (3DGS's "cameras_extent").
struct SceneSphere {
  Vec3d centre;
  float radius = 0.0f;
};

// Throws Error naming the split's transforms file when the split has no views. The radius
// is 0 when every camera sits at one point (a single view); callers needing a length must
// handle that case.
SceneSphere sceneSphere(const DatasetSplit& split);

// sceneSphere(split).radius.
float sceneExtent(const DatasetSplit& split);

}  // namespace glint
