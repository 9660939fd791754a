// Solving the metallic-roughness mapping of synth/mesh_scene for a requested diffuse and F0.
#include "synth_edit/material_colors.h"

#include <algorithm>

namespace glint {

namespace {

// F0 = 0.08 x level for a dielectric (Burley 2012), the constant of mapMaterial.
constexpr float kF0PerSpecularLevel = 0.08f;

float minComponent(const Rgb& c) { return std::min({c.x, c.y, c.z}); }

// Sets level and tint so that tint x 0.08 x level = dielectricF0.
void setDielectricF0(Material& material, const Rgb& dielectricF0) {
  float largest = maxComponent(dielectricF0);
  material.specularLevel = largest / kF0PerSpecularLevel;
  material.specularTint = largest > 0.0f ? dielectricF0 / largest : Rgb(1.0f);
}

}  // namespace

void setDiffuseAndF0(Material& material, const Rgb& diffuse, const Rgb& F0) {
  float metallic = std::clamp(material.metallic, 0.0f, 1.0f);
  if (metallic >= 1.0f && maxComponent(diffuse) <= 0.0f) {
    material.metallic = 1.0f;
    material.baseColor = F0;
    return;
  }
  if (metallic < 1.0f) {
    Rgb baseColor = diffuse / (1.0f - metallic);
    Rgb rest = F0 - baseColor * metallic;  // what the dielectric specular must add
    if (minComponent(rest) >= 0.0f) {
      material.metallic = metallic;
      material.baseColor = baseColor;
      setDielectricF0(material, rest / (1.0f - metallic));
      return;
    }
  }
  material.metallic = 0.0f;
  material.baseColor = diffuse;
  setDielectricF0(material, F0);
}

}  // namespace glint
