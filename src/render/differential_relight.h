// Differential relighting of the diffuse layer after an edit: each Gaussian the edit left in
// place has its diffuse colour scaled by E_after / E_before, the ratio of the irradiance
// arriving at it in the edited and the unedited scene (the ratio form of differential
// rendering), so that a moved object takes its shadow along and unaffected regions stay
// exactly as trained.
#pragma once

#include <atomic>
#include <cstddef>
#include <exception>
#include <cstdint>
#include <span>
#include <vector>

#include "math/frame.h"
#include "math/vec.h"
#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_path.h"
#include "render/light_regions.h"
#include "scene/gaussians.h"

namespace glint {

// A sphere bounding Gaussians that an edit changed: where they were (removed or moved
// away) or where they are now (moved there or added).
struct ChangedRegion {
  Vec3f centre;
  float radius = 0;
};

// The region of the listed Gaussians of a scene: a sphere around their means, widened by
// three of each one's largest standard deviations. Radius 0 for an empty list.
ChangedRegion changedRegionOf(const GaussianScene& scene, std::span<const uint32_t> indices);

struct RelightSettings {
  // Rays from a receiver toward the changed regions, where the radiance can differ, for a
  // receiver that sees them under a large solid angle (kFullRaysSolidAngle and more);
  // receivers farther away use fewer, down to minRays, in proportion to the solid angle.
  int rays = 64;
  int minRays = 4;
  // Cosine-distributed rays over the whole hemisphere for E_before (only at receivers
  // whose irradiance changes): first quickRays of them, and the rest only where the change
  // is at least minRelativeChange of that first estimate; elsewhere the colour is kept (a
  // change of 0.5% is below one level of an 8-bit image for all but the brightest colours).
  int hemisphereRays = 64;
  int quickRays = 16;
  float minRelativeChange = 0.005f;
  // Where the ratio's luminance leaves [1 / refineBeyond, refineBeyond], dE and E_before
  // continue along their sequences to refineFactor times their rays (1: never): a ratio far
  // from 1 multiplies E_before's relative error, and divides dE's by a small E_before. On
  // the Blender spheres_room (16 spp) 4 raised the diffuse pass of a move, a duplication and
  // a deletion by 0.11, 0.24 and 0.31 dB for 9% to 20% more rays (README, "Edits that move
  // shadows").
  float refineBeyond = 2.0f;
  int refineFactor = 4;
  // The ratio per channel is clamped to [1 / maxRatio, maxRatio]: a receiver whose few rays
  // all met the edited object cannot turn black or blaze. A contact shadow that an edit
  // uncovers needs more than 4: on builtin:spheres 16 lowered the final-image drop of a
  // move from 1.48 to 1.18 dB and of a deletion from 2.09 to 1.21 (with healing), and 64
  // did no better (1.19, 1.23; README, "Edits that move shadows").
  float maxRatio = 16.0f;
  // Receivers that see every changed region under less solid angle than this (steradians)
  // keep their colour: an object 56 radii away changes their irradiance by < 0.03%.
  float minSolidAngle = 1e-3f;
  // Receivers need a normal at least this long (far-field Gaussians have none).
  float minNormalLength = 0.5f;
  // The filter across neighbouring Gaussians: each receiver's ratio becomes the mean of the
  // ratios of the receivers within filterRadius of its largest standard deviations that face
  // the same way (normals within filterCosine), weighted by a Gaussian of distance times the
  // receiver's trained luminance (a ratio of sums, so a receiver in deep shadow, whose small
  // E_before makes its ratio noisy, counts for as little as its light); 0 = none.
  // Only receivers within reach of a changed region take part, so the rest stay as trained.
  // On builtin:spheres a radius of 1 lowered the final-image drop of a move from 1.18 to
  // 0.86 dB and of a deletion from 1.21 to 0.75 (a duplication: 1.19 to 1.17); 0.5, 1.5, 2, 3,
  // 4 and 6 did less (README, "Edits that move shadows").
  float filterRadius = 1.0f;
  float filterCosine = 0.8f;
  // At most this many receivers within reach are traced (0: all of them): a cover of them,
  // every receiver having a traced one within a spacing that faces the same way (the smallest
  // spacing within the budget), whose ratios the others take by the filter's weights over a
  // radius of at least that spacing. The viewer's first look at an edit's shadows, before the
  // full relighting.
  size_t tracedBudget = 0;
  uint64_t seed = 0;
  // When set and true, relightRatios stops tracing and throws RelightCancelled (the viewer
  // cancels a relighting that a newer edit made stale).
  const std::atomic<bool>* cancel = nullptr;
  // Sets every ray count from one, in the proportions of the defaults (64, 64, 16): n rays
  // toward the changed regions, n over the hemisphere, n / 4 of them first.
  void setRays(int n) {
    rays = hemisphereRays = n;
    quickRays = n / 4 > 1 ? n / 4 : 1;
  }
  // How each ray from a receiver continues where it meets a surface, as the renderer's
  // reflected segments do (the run's normal offset, back-face skip, invalid-normal length
  // and roughness floor): the radiance a ray brings is the blended diffuse colour it meets
  // plus the light of up to path.bounces reflected segments from there (0: the diffuse
  // colour alone). A mirror's diffuse colour is nearly black; the light it sends onto the
  // floor is its reflection, and the trained floor under it holds that light. Off by
  // default: one segment lowered the diffuse drop of a move on builtin:spheres by 0.14 dB
  // but raised a deletion's on the Blender spheres_room by 0.49 dB and a duplication's by
  // 0.33 (the noise of a chrome sphere's reflected lamps outweighs the light it adds; README,
  // "Edits that move shadows").
  PathSettings path;
  // The scene's light regions (clusters of its brightest Gaussians: emitters). Where one
  // shares directions with a changed region, half of the rays for dE aim at it (one-sample
  // multiple importance sampling with the changed regions' cones): the light an object
  // blocks or uncovers is most of the change, and rays spread over a large object rarely
  // meet a small lamp behind it. lights.factor 0 = the changed regions' cones alone. On the
  // Blender spheres_room it lowered the diffuse drop of a duplication from 2.27 to 0.78 dB,
  // of a move from 3.20 to 2.24 and of a deletion from 4.92 to 3.91 (README, "Edits that
  // move shadows").
  LightRegionSettings lights;
  // A reflected segment is traced only from surfaces whose blended F0 reaches this in some
  // channel (metals, mirrors; PathSettings::minReflectance): a dielectric reflects a few
  // percent, and most rays meet one.
  float minReflectance = 0.1f;
};

// The keys of one ray's random numbers (tracePath's seed, view, pixel and sample): the same
// keys give the same reflected directions in the scene before and after an edit.
struct RadianceKeys {
  uint64_t seed = 0, receiver = 0, sequence = 0;
  uint32_t sample = 0;
};

// The ray relighting traces from a receiver at p (unit normal n) toward w: offset along n
// and skipping back faces as the renderer's reflected segments do (path's settings).
inline TraceRay radianceRay(const Vec3f& p, const Vec3f& n, const Vec3f& w, const PathSettings& path) {
  return TraceRay{p + n * path.normalOffset, w, 0.0f, path.backfaceSkip};
}

// Direction k of the stratified stream `stream`, cosine-distributed about frame's normal.
Vec3f cosineDirection(const Framef& frame, uint64_t stream, int k);

// The radiance arriving at p (unit normal n) from direction w as relighting counts it: the
// blended diffuse colour the ray meets, plus the light of path.bounces reflected segments
// from there. Adds the segments traced to *segments.
Rgb incomingRadiance(const GaussianTracer& tracer, const Vec3f& p, const Vec3f& n, const Vec3f& w,
                     const PathSettings& path, const RadianceKeys& keys, uint64_t* segments);

// Adds to *sum the incomingRadiance of directions begin..end-1 of the stratified stream
// `stream`, cosine-distributed about the unit normal n (ray k's keys: `keys` with sample k),
// and the segments traced to *segments. pi / count times the sum over 0..count is the
// irradiance at p.
void addCosineRadiance(const GaussianTracer& tracer, const Vec3f& p, const Vec3f& n, const PathSettings& path,
                       uint64_t stream, RadianceKeys keys, int begin, int end, Rgb* sum, uint64_t* segments);

// Thrown by relightRatios when RelightSettings::cancel turned true.
struct RelightCancelled : std::exception {
  const char* what() const noexcept override { return "relighting cancelled"; }
};

// A receiver that sees changed regions with this solid angle or more gets settings.rays.
constexpr float kFullRaysSolidAngle = 0.5f;

struct RelightReport {
  size_t receivers = 0;  // Gaussians considered
  size_t reached = 0;    // ... within reach of a changed region
  size_t traced = 0;     // ... of which rays were traced from (all, without tracedBudget)
  size_t changed = 0;    // ... whose diffuse colour changed
  size_t clamped = 0;    // ... whose ratio hit the clamp in some channel
  uint64_t rays = 0;     // rays traced, both scenes together
  size_t lights = 0;     // light regions of the scene (RelightSettings::lights)
};

// The per-receiver ratios E_after / E_before (RGB), 1 where nothing changes. `before` and
// `after` trace the unedited and the edited scene (built; after's scene is `afterScene`);
// `receivers` are indices into afterScene of Gaussians the edit did not move, and `regions`
// the changed regions of both scenes.
//
// E_before = pi mean L_before(w) over cosine-distributed directions; the change
// dE = integral over the regions' cones of (L_after(w) - L_before(w)) max(0, n.w) dw, by
// one-sample multiple importance sampling of the cones (balance heuristic), with the same
// directions in both scenes. Directions outside every cone meet no changed Gaussian, so
// their radiance is the same before and after: leaving them out loses nothing and leaves
// no noise where nothing changed. L is the blended diffuse colour the ray meets (the cached
// radiance of the paper's equation 3), emitters included; indirect effects beyond it (light
// that a changed Gaussian used to bounce onto the surface that lights this one) are not
// modelled.
std::vector<Rgb> relightRatios(const GaussianTracer& before, const GaussianTracer& after,
                               const GaussianScene& afterScene, std::span<const uint32_t> receivers,
                               std::span<const ChangedRegion> regions, const RelightSettings& settings,
                               RelightReport* report = nullptr);

// relightRatios, then diffuse[receivers[i]] *= ratio[i]. Trace `after` again only after a
// refit: tracers may keep copies of the colours.
RelightReport relightDiffuse(const GaussianTracer& before, const GaussianTracer& after, GaussianScene& afterScene,
                             std::span<const uint32_t> receivers, std::span<const ChangedRegion> regions,
                             const RelightSettings& settings);

}  // namespace glint
