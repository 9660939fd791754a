// Scene extent from the camera centres, as in 3DGS's getNerfppNorm.
#include "train/scene_extent.h"

#include <algorithm>

#include "core/error.h"

namespace glint {

// 3DGS enlarges the cameras' spread by 10% so that the scene's content, which lies
// mostly inside the ring of cameras, is covered with a margin.
constexpr double kExtentMargin = 1.1;

SceneSphere sceneSphere(const DatasetSplit& split) {
  if (split.views.empty())
    throw Error("transforms_" + split.name + ".json", "has no views: the scene extent needs at least one camera");
  Vec3d sum(0.0);
  for (const DatasetView& view : split.views) sum += view.camera.position();
  SceneSphere sphere;
  sphere.centre = sum / double(split.views.size());
  double farthest = 0.0;
  for (const DatasetView& view : split.views)
    farthest = std::max(farthest, length(view.camera.position() - sphere.centre));
  sphere.radius = float(kExtentMargin * farthest);
  return sphere;
}

float sceneExtent(const DatasetSplit& split) { return sceneSphere(split).radius; }

}  // namespace glint
