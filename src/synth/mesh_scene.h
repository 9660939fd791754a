// The ground-truth generator's scene: triangle meshes and analytic spheres with glTF 2.0
// metallic-roughness materials, punctual lights, emitters and an environment.
// Everything is in world space, Y up (the glTF convention), metres.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/image.h"
#include "math/vec.h"

namespace glint {

// A texture with bilinear filtering and repeat wrapping. Colour textures are stored
// linear (sRGB decoded once at load time).
struct Texture {
  std::string name;
  Image image;  // 1 to 4 channels

  // Bilinear lookup at uv (glTF convention: v grows downwards, (0,0) is the top-left corner).
  Rgb sampleRgb(Vec2f uv) const;
};

// glTF 2.0 metallic-roughness material, plus KHR_materials_specular and emission.
// The BRDF is Lambert diffuse + Cook-Torrance GGX specular (the paper's Disney subset).
struct Material {
  std::string name;
  Rgb baseColor{0.8f};
  int baseColorTexture = -1;  // index into MeshScene::textures, -1 = none
  float metallic = 0.0f;
  float roughness = 0.5f;            // perceptual roughness; GGX alpha = roughness^2
  int metallicRoughnessTexture = -1;  // glTF: G = roughness, B = metallic (multiplied)
  // Disney/Principled specular level (0.5 = F0 of 0.04 for dielectrics), and a tint from
  // KHR_materials_specular's specularColorFactor.
  float specularLevel = 0.5f;
  Rgb specularTint{1.0f};
  Rgb emission{0.0f};  // emitted radiance (emissiveFactor x strength)
  int emissionTexture = -1;
};

// Material values at one surface point, after textures.
struct SurfaceMaterial {
  Rgb baseColor;
  float metallic;
  float roughness;
  Rgb F0;        // (1 - m) * 0.08 * specular * tint + m * baseColor
  Rgb diffuse;   // (1 - m) * baseColor: the Lambert albedo
  Rgb emission;
};

// The glTF / Disney mapping from a material's factors to F0 and diffuse, at a surface point's
// base colour, metallic and roughness (textures already applied). Emission is left black.
SurfaceMaterial mapMaterial(const Material& material, Rgb baseColor, float metallic, float roughness);
// The material at its factors alone, textures ignored (edit filters and colour edits work
// on factors).
SurfaceMaterial materialFactors(const Material& material);

struct TriangleMesh {
  std::string name;
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;  // per vertex; empty = flat shading from the geometric normal
  std::vector<Vec2f> uvs;      // per vertex; may be empty
  std::vector<uint32_t> indices;  // three per triangle
  int material = 0;

  size_t triangleCount() const { return indices.size() / 3; }
};

// An exact sphere (not tessellated): exact depth and normals for tests and built-in scenes.
struct Sphere {
  Vec3f center;
  float radius = 1.0f;
  int material = 0;
};

// KHR_lights_punctual. Intensities are radiometric: point and spot in W/sr (radiant
// intensity), directional in W/m^2 (irradiance at normal incidence).
struct PunctualLight {
  enum class Type { Point, Spot, Directional };
  Type type = Type::Point;
  Vec3f position;
  Vec3f direction{0, -1, 0};  // direction the light travels (spot axis, sun direction)
  Rgb intensity{1.0f};
  float innerConeAngle = 0.0f;        // spot: full intensity inside this half-angle
  float outerConeAngle = 0.785398f;   // spot: zero outside this half-angle
};

// Light arriving from infinity: constant radiance, or an equirectangular (lat-long) map.
struct Environment {
  Rgb constant{0.0f};  // used when map is empty
  Image map;            // RGB, linear; u = azimuth, v = polar angle from +Y (top row = up)
  float intensity = 1.0f;
  float rotationY = 0.0f;  // radians, rotates the map about +Y

  bool isBlack() const;
};

// Where the generator places its cameras: two different paths (train, test) around a
// target, each a looping orbit whose height oscillates.
struct OrbitPath {
  Vec3f center{0.0f};  // orbit centre
  Vec3f target{0.0f};  // point the cameras look at
  float radius = 3.0f;
  float heightLow = 0.5f;   // camera height above center: oscillates between low and high
  float heightHigh = 1.5f;
  float phase = 0.0f;       // start angle, radians
  float turns = 1.0f;       // full turns over the path
  float heightWaves = 2.0f;  // oscillations of the height over the path
};

struct CameraRig {
  float fovX = 1.0471976f;  // 60 degrees
  OrbitPath train;
  OrbitPath test;
};

struct MeshScene {
  std::vector<TriangleMesh> meshes;
  std::vector<Sphere> spheres;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<PunctualLight> lights;
  Environment environment;
  CameraRig cameras;
  bool hasCameraRig = false;  // false: `glint synth` derives one from the bounds

  // Evaluates textures and the F0 mapping at a surface point.
  SurfaceMaterial surfaceMaterial(int material, Vec2f uv) const;
  // Only the emitted radiance at a surface point (light sampling needs nothing else).
  Rgb emission(int material, Vec2f uv) const;
  // World-space bounds of all geometry.
  void bounds(Vec3f* lower, Vec3f* upper) const;
  // Throws Error (naming `source`) for out-of-range material/texture indices, NaN
  // positions, or indices past the vertex arrays.
  void validate(const std::string& source) const;
};

}  // namespace glint
