// The cones of directions from a receiver toward the changed regions and the light regions
// of differential relighting, and the mixture of them its change rays are drawn from.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>

#include "math/frame.h"
#include "math/sampling.h"
#include "render/differential_relight.h"
#include "render/light_regions.h"

namespace glint {

// The cone of directions from a receiver toward one changed region or light region.
struct RelightCone {
  Framef frame;          // around the direction to the region's centre
  float cosThetaMax = 1;  // -1: the receiver is inside the region (every direction)
  float solidAngle = 0;
  float weight = 1;       // the probability a mixture of cones picks this one

  bool contains(const Vec3f& w) const { return dot(w, frame.n) >= cosThetaMax; }
  float pdf() const { return uniformConePdf(cosThetaMax); }
};

// The cone from p toward a sphere, if it rises above the horizon of normal n; a receiver
// inside the sphere gets every direction (cosThetaMax -1, framed on n).
inline bool coneToward(const Vec3f& p, const Vec3f& n, const Vec3f& centre, float radius, RelightCone* cone) {
  if (!(radius > 0)) return false;
  Vec3f toCentre = centre - p;
  float d = length(toCentre);
  if (d <= radius) {
    cone->frame = Framef::fromNormal(n);
    cone->cosThetaMax = -1.0f;
  } else {
    Vec3f axis = toCentre / d;
    float sinThetaMax = radius / d;
    // The whole cone lies below the horizon when its axis is more than 90 degrees plus its
    // half-angle away from the normal.
    if (dot(axis, n) < -sinThetaMax) return false;
    cone->frame = Framef::fromNormal(axis);
    cone->cosThetaMax = std::sqrt(std::max(0.0f, 1.0f - sinThetaMax * sinThetaMax));
  }
  cone->solidAngle = 2.0f * kPi * (1.0f - cone->cosThetaMax);
  return true;
}

// Cones toward the regions that rise above the receiver's horizon, picked uniformly.
inline int conesToward(const Vec3f& p, const Vec3f& n, std::span<const ChangedRegion> regions, RelightCone* cones) {
  int count = 0;
  for (const ChangedRegion& region : regions)
    if (coneToward(p, n, region.centre, region.radius, &cones[count])) ++count;
  for (int c = 0; c < count; ++c) cones[c].weight = 1.0f / float(count);
  return count;
}

// Whether two cones share a direction: their axes are closer than the sum of half-angles.
inline bool conesOverlap(const RelightCone& a, const RelightCone& b) {
  if (a.cosThetaMax <= -1.0f || b.cosThetaMax <= -1.0f) return true;
  const float between = std::acos(std::clamp(dot(a.frame.n, b.frame.n), -1.0f, 1.0f));
  return between <= std::acos(a.cosThetaMax) + std::acos(b.cosThetaMax);
}

// Cones toward the light regions above the receiver's horizon, outside them (a receiver
// inside a light's sphere gains nothing from aiming at it) and sharing directions with one
// of the `within` cones (a light behind or beside a changed region). Each is picked in proportion to the
// irradiance its light could bring, power x cosine / distance^2, and only the maxCones
// likeliest are kept.
inline int lightConesToward(const Vec3f& p, const Vec3f& n, std::span<const LightRegion> lights, std::span<const RelightCone> within,
                     RelightCone* cones, int maxCones) {
  int count = 0;
  for (const LightRegion& light : lights) {
    RelightCone cone;
    if (!coneToward(p, n, light.centre, light.radius, &cone) || cone.cosThetaMax <= -1.0f) continue;
    if (std::none_of(within.begin(), within.end(), [&](const RelightCone& c) { return conesOverlap(cone, c); })) continue;
    const Vec3f toLight = light.centre - p;
    // A light whose centre sits below the horizon can still rise above it: a floor of 5%.
    cone.weight = light.power * std::max(dot(cone.frame.n, n), 0.05f) /
                  std::max(dot(toLight, toLight), light.radius * light.radius);
    if (!(cone.weight > 0)) continue;
    if (count < maxCones) {
      cones[count++] = cone;
    } else {  // replace the unlikeliest kept
      RelightCone* weakest = std::min_element(cones, cones + count, [](const RelightCone& a, const RelightCone& b) { return a.weight < b.weight; });
      if (weakest->weight < cone.weight) *weakest = cone;
    }
  }
  float total = 0;
  for (int c = 0; c < count; ++c) total += cones[c].weight;
  for (int c = 0; c < count; ++c) cones[c].weight /= total;
  return count;
}

// The density, at w, of the mixture that picks cone c with probability cones[c].weight and
// then a direction uniformly within it.
inline float coneMixturePdf(const RelightCone* cones, int count, const Vec3f& w) {
  float pdf = 0;
  for (int c = 0; c < count; ++c)
    if (cones[c].contains(w)) pdf += cones[c].weight * cones[c].pdf();
  return pdf;
}

// A direction from that mixture; u.x picks the cone and is stretched back to [0, 1) for the
// direction.
inline Vec3f sampleConeMixture(const RelightCone* cones, int count, Vec2f u) {
  int pick = 0;
  float below = 0;  // the weights of the cones before `pick`
  while (pick < count - 1 && u.x >= below + cones[pick].weight) below += cones[pick++].weight;
  u.x = std::clamp((u.x - below) / cones[pick].weight, 0.0f, 0x1.fffffep-1f);
  return normalize(cones[pick].frame.toWorld(sampleUniformCone(u, cones[pick].cosThetaMax)));
}

inline constexpr int kMaxRegions = 8;
inline constexpr int kMaxLights = 8;  // light cones per receiver

// A receiver's place and cones: p and unit normal n of Gaussian g of the edited scene, and
// the cones toward the changed regions above its horizon, with their total solid angle.
// Returns the number of cones, or 0 when the edit cannot reach the receiver (no normal of
// RelightSettings::minNormalLength, or every cone under minSolidAngle).
inline int receiverCones(const GaussianScene& scene, uint32_t g, std::span<const ChangedRegion> regions,
                         const RelightSettings& settings, Vec3f* p, Vec3f* n, RelightCone* cones, float* solidAngle) {
  const float normalLength = length(scene.normal[g]);
  if (!(normalLength >= settings.minNormalLength)) return 0;
  *n = scene.normal[g] / normalLength, *p = scene.position[g];
  const int coneCount = conesToward(*p, *n, regions, cones);
  float largest = 0;
  *solidAngle = 0;
  for (int c = 0; c < coneCount; ++c) *solidAngle += cones[c].solidAngle, largest = std::max(largest, cones[c].solidAngle);
  return largest < settings.minSolidAngle ? 0 : coneCount;
}

}  // namespace glint
