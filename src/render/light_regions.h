// Where a Gaussian scene's light comes from: clusters of its brightest Gaussians (emitters,
// which a trained scene holds as Gaussians of high diffuse radiance), each bounded by a
// sphere, so that an irradiance estimate can aim some of its rays at them.
#pragma once

#include <vector>

#include "math/vec.h"
#include "scene/gaussians.h"

namespace glint {

struct LightRegion {
  Vec3f centre;
  float radius = 0;
  float power = 0;  // sum over its Gaussians of luminance x opacity x footprint area
};

struct LightRegionSettings {
  // A Gaussian is a light when its diffuse luminance reaches `factor` times the 90th
  // percentile of the surfaces' (Gaussians at least minOpacity opaque with a normal at least
  // minNormalLength long), it is itself at least minOpacity opaque (with or without a
  // normal: trained emitters often have none), and its largest standard deviation is within
  // the surfaces' 99th percentile (a few huge Gaussians far outside a room, seen only in its
  // mirrors, are no light of its floor). HDR emitters are tens of times brighter than what
  // they light; a white wall in full light is not.
  float factor = 4.0f;
  float minOpacity = 0.3f;
  float minNormalLength = 0.5f;
  // Two lights belong to one region when their means are within linkSigmas x 2 x the
  // smaller of their largest standard deviations (their footprints touch; a large Gaussian
  // does not bridge two emitters).
  float linkSigmas = 2.0f;
  // A region's sphere holds each of its Gaussians' means widened by this many of its largest
  // standard deviations.
  float boundSigmas = 2.0f;
  // A region's sphere and power count only its Gaussians at least this fraction as bright as
  // its brightest: an emitter's own radiance is uniform, and dimmer Gaussians linked to it
  // (blends, floaters beyond the ceiling it hangs from) would stretch its sphere.
  float coreFraction = 0.8f;
  // Only the most powerful regions are kept.
  int maxRegions = 16;
};

// The light regions of a scene, most powerful first; none when no Gaussian is bright enough
// (a scene lit evenly) or factor is 0. Deterministic.
std::vector<LightRegion> lightRegionsOf(const GaussianScene& scene, const LightRegionSettings& settings = {});

}  // namespace glint
