// Far-field Gaussians (paper section 3.3 and appendix B): a cloud of coarse Gaussians added
// when reflections start, so that reflected rays find something to reconstruct the parts
// of the environment no training camera sees directly (the ceiling light, walls behind
// the cameras, the sky).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "math/mat4.h"
#include "math/vec.h"
#include "raytrace/trace_settings.h"
#include "scene/gaussians.h"

namespace glint {

// A box of extra far-field Gaussians spread uniformly inside it. The cloud is thin near any
// one spot (about 30 per cubic metre around builtin:room), too thin for an object seen only
// in reflections; the paper seeds 5000 small Gaussians around such an object by hand.
struct FarFieldBox {
  Vec3f min{0.0f}, max{0.0f};  // world-space corners
  int count = 0;
};

// The most far-field Gaussians a run may add, in the cloud and in each box: far more than
// any scene needs (the default is 75,000), and a bound on what a config file can allocate.
inline constexpr int kMaxFarFieldCount = 10'000'000;

struct FarFieldSettings {
  int count = 75000;          // M; 0 adds none
  float sigmaFactor = 4.0f;   // positions ~ N(centre, (sigmaFactor x S)^2) per axis
  float truncation = 3.0f;    // ... truncated at this many sigma from the centre
  float opacity = 0.1f;
  float diffuse = 0.2f;
  int neighbours = 3;         // initial scale = mean distance to this many nearest far-field points
  std::vector<FarFieldBox> boxes;  // added to the cloud, with the same attributes
  // Gaussians seeded along unexplained mirror reflections in unobserved space
  // (train/reflection_seeds.h), and the roughness below which a pixel counts as a mirror.
  // Off by default: placed by photo-consistency, 20,000 seeds lowered the Blender
  // mirror_room's vase (seen only in the mirror) from 19.4 to 14.8 dB final and the whole
  // test views from 26.7 to 24.8 dB (README): uniform walls are consistent at every depth,
  // so seeds float in front of them.
  int reflectionSeeds = 0;
  float reflectionSeedRoughness = 0.2f;
};

// Throws Error(where, ...) for settings out of range.
void checkFarFieldSettings(const FarFieldSettings& s, const std::string& where);

// M Gaussians around `centre` at the scale S = `sceneRadius` (3DGS's camera-sphere radius):
// positions from a normal distribution truncated by rejection to `truncation` sigma, then
// those of the boxes, uniform in each;
// isotropic scales from the nearest-neighbour distances of the cloud (as the dense
// initialisation sizes its points); normal 0, so paths reaching them end; roughness 0
// and F0 0.04 as the other initial Gaussians. Deterministic in `seed`.
GaussianScene farFieldGaussians(const FarFieldSettings& s, const Vec3f& centre, float sceneRadius, uint64_t seed);
// Far-field Gaussians at the given points, with the attributes and sizing above.
GaussianScene farFieldAtPoints(const std::vector<Vec3f>& points, const FarFieldSettings& s, float sceneRadius);

class TrainingViews;

// Appendix B culls far-field Gaussians near the cameras only. Glint also removes those a
// training view sees to lie in empty space (closer than the surface its pixel records),
// and shrinks the others so that their support (the proxy radius of `trace`) stays behind
// every surface a view records in their direction. Far-field Gaussians stand for what no
// camera sees directly; on builtin:spheres, without this, the ones floating inside the
// room raised the depth error 27-fold when they were added and hid the warm-up's work.
// Pixels without a surface (the sky) carve nothing, nor do views without depth buffers.
// Returns how many were removed.
size_t carveObservedFreeSpace(GaussianScene* farField, const TrainingViews& views, const TraceSettings& trace);

// The world-to-camera matrices of the views, for gapBehindObservedSurfaces.
std::vector<Mat4> worldToCameras(const TrainingViews& views);
// The smallest distance, over the views, by which p lies behind the surface each records in
// its direction: negative or zero when some view sees p in empty space, infinite when no
// view records a surface toward p.
double gapBehindObservedSurfaces(const Vec3d& p, const TrainingViews& views, std::span<const Mat4> worldToCamera);

}  // namespace glint
