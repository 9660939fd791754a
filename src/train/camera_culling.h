// Floater removal (paper appendix "Floater Removal"): a sphere around each training camera,
// of radius 0.8 x the nearest surface its depth buffer sees, inside which Gaussian means
// are culled: the camera sees nothing that close, so what lies there in its view floats.
#pragma once

#include <optional>
#include <vector>

#include "io/image.h"
#include "math/vec.h"
#include "scene/camera.h"
#include "scene/dataset.h"
#include "scene/gaussians.h"

namespace glint {

// The paper's ratio of sphere radius to the nearest input depth.
constexpr float kCameraSphereDepthFactor = 0.8f;

struct CameraSphere {
  Camera camera;  // the sphere is centred on camera.position()
  double radius = 0.0;

  Vec3d centre() const { return camera.position(); }
};

// Where a sphere culls. The paper culls the whole sphere, which suits cameras on a hemisphere
// around an object with nothing behind them. Inside a room (builtin:spheres) the walls
// behind a camera lie within its sphere though the camera never sees them: on its dense
// initialisation the whole-sphere rule removes 6% of the Gaussians, all real walls outside
// the culling camera's view. Limiting each sphere to its camera's view frustum keeps them
// and still removes what would float in front of that camera.
enum class CullRegion {
  SphereInView,  // inside the sphere and in front of the camera, projecting into its image
  WholeSphere,   // anywhere inside the sphere (the paper's rule)
};

// The sphere of one view: centred on the camera, radius = factor x the smallest depth
// over the view's surface pixels (depth is a distance from the camera centre, so every
// surface point lies outside). None when no pixel has a surface.
std::optional<CameraSphere> cameraSphere(const Image& depth, const Camera& camera,
                                         float factor = kCameraSphereDepthFactor);

// The distance from the camera centre to the nearest of `points` that lies in front of the
// camera and projects into its image; infinity when none does. Every such point is at
// least as far as the surface its pixel sees, so this undercuts the true nearest surface's
// depth by no more than the pixel grid does (the nearest surface lies between pixel
// centres), while a depth buffer aligned with the wrong scale can overstate it.
double nearestPointInView(const Camera& camera, const std::vector<Vec3d>& points);

// The spheres of every view of a split, in view order (views without surface pixels have
// none). Reads each view's depth buffer once. For a capture with sparse points the radius
// is factor x the nearer of the depth buffer's nearest surface and nearestPointInView: a
// relative depth aligned wrongly (a monocular predictor's: up to 5x too far, measured)
// would otherwise cull real surfaces near the camera.
std::vector<CameraSphere> cameraSpheres(const Dataset& dataset, const DatasetSplit& split,
                                        float factor = kCameraSphereDepthFactor);

// True when p lies strictly inside the sphere and, for SphereInView, in front of the camera
// with its projection inside the image.
bool insideCullRegion(const CameraSphere& sphere, const Vec3d& p, CullRegion region);

// keep[i] is false when Gaussian i's mean lies inside the cull region of any sphere; the
// mask suits GaussianScene::filter.
std::vector<bool> outsideCameraSpheres(const GaussianScene& scene, const std::vector<CameraSphere>& spheres,
                                       CullRegion region = CullRegion::SphereInView);

// Removes the Gaussians whose means lie inside any cull region; returns how many.
size_t cullInsideCameraSpheres(GaussianScene& scene, const std::vector<CameraSphere>& spheres,
                               CullRegion region = CullRegion::SphereInView);

}  // namespace glint
