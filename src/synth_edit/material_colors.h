// Re-expresses a glTF metallic-roughness material so that its factors give a requested
// Lambert diffuse albedo and F0 (the two colours edit files change), for `glint synth --edits`.
#pragma once

#include "synth/mesh_scene.h"

namespace glint {

// Changes baseColor, metallic, specularLevel and specularTint so that materialFactors(m)
// returns `diffuse` and `F0` (F0 in [0, 1], diffuse >= 0); roughness, emission and textures
// stay. The mapping (docs/edit-files.md, "Meshes"):
// - a pure metal asked for no diffuse stays a metal: baseColor = F0;
// - otherwise, with metallic m < 1: baseColor = diffuse / (1 - m), and the dielectric
//   specular gives the rest, specularLevel x specularTint = (F0 - m baseColor) / (0.08 (1 - m))
//   (for a dielectric, m = 0: F0 / 0.08);
// - when that rest would be negative (a partial metal whose metal part already reflects
//   more than F0), or the material is a pure metal asked for a diffuse colour, it becomes a
//   dielectric (m = 0) with the same diffuse and F0. The path tracer's BRDF depends only on
//   diffuse, F0 and roughness, so the rendered surface is exactly the requested one.
// The level takes the magnitude and the tint the hue: tint = rest / max(rest), so the tint
// stays in [0, 1] and the level may exceed 1 (up to 12.5 for F0 = 1).
void setDiffuseAndF0(Material& material, const Rgb& diffuse, const Rgb& F0);

}  // namespace glint
