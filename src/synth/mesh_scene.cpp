// Texture lookups, material evaluation and checks of the generator's scene.
#include "synth/mesh_scene.h"

#include <cmath>
#include <limits>

#include "core/error.h"

namespace glint {

Rgb Texture::sampleRgb(Vec2f uv) const {
  if (image.empty()) return Rgb(1.0f);
  // Texel centres sit at half-integer positions; repeat wrapping on both axes.
  float x = uv.x * image.width - 0.5f;
  float y = uv.y * image.height - 0.5f;
  float fx = std::floor(x), fy = std::floor(y);
  float tx = x - fx, ty = y - fy;
  auto wrap = [](int i, int n) { return ((i % n) + n) % n; };
  int x0 = wrap(int(fx), image.width), x1 = wrap(int(fx) + 1, image.width);
  int y0 = wrap(int(fy), image.height), y1 = wrap(int(fy) + 1, image.height);
  Rgb a = lerp(image.rgb(x0, y0), image.rgb(x1, y0), tx);
  Rgb b = lerp(image.rgb(x0, y1), image.rgb(x1, y1), tx);
  return lerp(a, b, ty);
}

bool Environment::isBlack() const {
  if (intensity <= 0.0f) return true;
  return map.empty() && maxComponent(constant) <= 0.0f;
}

SurfaceMaterial mapMaterial(const Material& m, Rgb baseColor, float metallic, float roughness) {
  SurfaceMaterial s;
  s.baseColor = baseColor;
  s.metallic = std::clamp(metallic, 0.0f, 1.0f);
  s.roughness = std::clamp(roughness, 0.0f, 1.0f);
  // Disney's specular level maps to dielectric F0 = 0.08 * level (0.5 -> 0.04); metals
  // reflect their base colour (Burley 2012, "Physically-Based Shading at Disney").
  Rgb dielectricF0 = m.specularTint * (0.08f * m.specularLevel);
  s.F0 = dielectricF0 * (1.0f - s.metallic) + s.baseColor * s.metallic;
  s.F0 = min(max(s.F0, Rgb(0.0f)), Rgb(1.0f));
  s.diffuse = s.baseColor * (1.0f - s.metallic);
  s.emission = Rgb(0.0f);
  return s;
}

SurfaceMaterial materialFactors(const Material& m) { return mapMaterial(m, m.baseColor, m.metallic, m.roughness); }

SurfaceMaterial MeshScene::surfaceMaterial(int index, Vec2f uv) const {
  const Material& m = materials[index];
  Rgb baseColor = m.baseColor;
  if (m.baseColorTexture >= 0) baseColor *= textures[m.baseColorTexture].sampleRgb(uv);
  float metallic = m.metallic, roughness = m.roughness;
  if (m.metallicRoughnessTexture >= 0) {
    Rgb mr = textures[m.metallicRoughnessTexture].sampleRgb(uv);
    roughness *= mr.y;
    metallic *= mr.z;
  }
  SurfaceMaterial s = mapMaterial(m, baseColor, metallic, roughness);
  s.emission = emission(index, uv);
  return s;
}

Rgb MeshScene::emission(int index, Vec2f uv) const {
  const Material& m = materials[index];
  if (m.emissionTexture < 0) return m.emission;
  return m.emission * textures[m.emissionTexture].sampleRgb(uv);
}

void MeshScene::bounds(Vec3f* lower, Vec3f* upper) const {
  constexpr float inf = std::numeric_limits<float>::infinity();
  Vec3f lo(inf), hi(-inf);
  for (const TriangleMesh& mesh : meshes)
    for (const Vec3f& p : mesh.positions) lo = min(lo, p), hi = max(hi, p);
  for (const Sphere& s : spheres) {
    lo = min(lo, s.center - Vec3f(s.radius));
    hi = max(hi, s.center + Vec3f(s.radius));
  }
  *lower = lo;
  *upper = hi;
}

void MeshScene::validate(const std::string& source) const {
  if (meshes.empty() && spheres.empty()) throw Error(source, "the scene has no geometry");
  auto checkMaterial = [&](int material, const std::string& what) {
    if (material < 0 || material >= int(materials.size()))
      throw Error(source, what + " refers to material " + std::to_string(material) + " but the scene has " +
                              std::to_string(materials.size()));
  };
  for (const TriangleMesh& mesh : meshes) {
    std::string what = "mesh '" + mesh.name + "'";
    checkMaterial(mesh.material, what);
    if (mesh.indices.size() % 3 != 0) throw Error(source, what + " has an index count not divisible by 3");
    for (uint32_t i : mesh.indices)
      if (i >= mesh.positions.size()) throw Error(source, what + " has an index past its vertices");
    for (const Vec3f& p : mesh.positions)
      if (!isFinite(p)) throw Error(source, what + " has a non-finite vertex position");
    if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size())
      throw Error(source, what + " has a normal count different from its vertex count");
    if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size())
      throw Error(source, what + " has a texture-coordinate count different from its vertex count");
  }
  for (size_t i = 0; i < spheres.size(); ++i) {
    checkMaterial(spheres[i].material, "sphere " + std::to_string(i));
    if (!(spheres[i].radius > 0) || !isFinite(spheres[i].center))
      throw Error(source, "sphere " + std::to_string(i) + " has an invalid centre or radius");
  }
  for (const Material& m : materials) {
    for (int t : {m.baseColorTexture, m.metallicRoughnessTexture, m.emissionTexture})
      if (t >= int(textures.size()))
        throw Error(source, "material '" + m.name + "' refers to missing texture " + std::to_string(t));
  }
  if (!environment.map.empty() && environment.map.channels < 3)
    throw Error(source, "the environment map must have 3 channels");
}

}  // namespace glint
