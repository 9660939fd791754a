// Tests of the glTF 2.0 importer on small files written by hand: transforms, winding,
// attribute layouts, the three containers, materials, textures, lights and errors.
#include "synth/gltf_import.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "synth/gltf_test_files.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::GltfBuilder;
using test::addQuadMesh;
using test::kFloat;
using test::kUnsignedByte;
using test::kUnsignedShort;

const double kHalfSqrt2 = std::sqrt(0.5);

void expectNear(const Vec3f& actual, const Vec3f& expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// The face normal implied by a triangle's winding (counter-clockwise = front).
Vec3f windingNormal(const TriangleMesh& mesh, size_t triangle) {
  const uint32_t* i = &mesh.indices[3 * triangle];
  return normalize(cross(mesh.positions[i[1]] - mesh.positions[i[0]], mesh.positions[i[2]] - mesh.positions[i[0]]));
}

double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

class GltfImportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("glint_gltf_" + std::to_string(getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Loads `path` expecting an Error whose message names the file and contains `fragment`.
  void expectLoadError(const fs::path& path, const std::string& fragment) {
    try {
      loadGltfScene(path);
      ADD_FAILURE() << "expected an error containing '" << fragment << "'";
    } catch (const Error& e) {
      std::string message = e.what();
      EXPECT_NE(message.find(path.string()), std::string::npos) << message;
      EXPECT_NE(message.find(fragment), std::string::npos) << message;
    }
  }

  fs::path dir_;
};

TEST_F(GltfImportTest, EmbeddedBufferBakesNodeHierarchy) {
  GltfBuilder b;
  int mesh = addQuadMesh(b);
  // Child: rotate 90 degrees about +Y (x -> -z), scale 2; parent: translate (1, 2, 3).
  int child = b.add("nodes", {{"mesh", mesh}, {"rotation", {0, kHalfSqrt2, 0, kHalfSqrt2}}, {"scale", {2, 2, 2}}});
  b.add("cameras", {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}});
  int parent = b.add("nodes", {{"translation", {1, 2, 3}}, {"children", {child}}, {"camera", 0}});
  b.doc["scenes"] = {{{"nodes", {parent}}}};
  b.doc["scene"] = 0;
  fs::path path = dir_ / "quad.gltf";
  b.writeEmbedded(path);

  MeshScene scene = loadGltfScene(path);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const TriangleMesh& m = scene.meshes[0];
  EXPECT_EQ(m.name, "Quad#0");
  ASSERT_EQ(m.positions.size(), 4u);
  expectNear(m.positions[0], {1, 2, 3});
  expectNear(m.positions[1], {1, 2, 1});
  expectNear(m.positions[2], {1, 4, 1});
  expectNear(m.positions[3], {1, 4, 3});
  ASSERT_EQ(m.normals.size(), 4u);
  for (const Vec3f& n : m.normals) expectNear(n, {1, 0, 0});
  ASSERT_EQ(m.uvs.size(), 4u);
  EXPECT_EQ(m.uvs[1].x, 1.0f);
  EXPECT_EQ(m.uvs[1].y, 1.0f);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  expectNear(windingNormal(m, 0), {1, 0, 0});
  EXPECT_TRUE(scene.lights.empty());
  EXPECT_FALSE(scene.hasCameraRig);
}

TEST_F(GltfImportTest, ExternalBufferMatrixNodeMirrorsWinding) {
  GltfBuilder b;
  int mesh = addQuadMesh(b);
  // Column-major matrix: mirror x, then translate by (5, 0, 0).
  b.add("nodes", {{"mesh", mesh}, {"matrix", {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1}}});
  b.add("nodes", {{"mesh", mesh}});  // no "scenes": every root node is imported
  fs::path path = dir_ / "mirror.gltf";
  b.writeExternal(path, "mirror.bin");

  MeshScene scene = loadGltfScene(path);
  ASSERT_EQ(scene.meshes.size(), 2u);
  const TriangleMesh& mirrored = scene.meshes[0];
  expectNear(mirrored.positions[1], {4, 0, 0});
  expectNear(mirrored.positions[2], {4, 1, 0});
  EXPECT_EQ(mirrored.indices, (std::vector<uint32_t>{0, 2, 1, 0, 3, 2}));
  for (const TriangleMesh& m : scene.meshes) {
    for (const Vec3f& n : m.normals) expectNear(n, {0, 0, 1});
    for (size_t t = 0; t < m.triangleCount(); ++t) expectNear(windingNormal(m, t), {0, 0, 1});
  }
  EXPECT_EQ(scene.meshes[1].indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
}

TEST_F(GltfImportTest, GlbWithNonUniformScaleByteIndicesAndNormalizedUvs) {
  GltfBuilder b;
  // One triangle in the plane x + y = 0, facing (1, 1, 0) / sqrt(2).
  std::vector<float> positions = {0, 0, 0, 0, 0, 1, 1, -1, 0};
  float s = float(kHalfSqrt2);
  std::vector<float> normals = {s, s, 0, s, s, 0, s, s, 0};
  std::vector<uint16_t> uvs = {0, 65535, 65535, 0, 32768, 13107};
  std::vector<uint8_t> indices = {0, 1, 2};
  json attributes = {{"POSITION", b.addAccessor(b.addView(positions), kFloat, 3, "VEC3")},
                     {"NORMAL", b.addAccessor(b.addView(normals), kFloat, 3, "VEC3")},
                     {"TEXCOORD_0", b.addAccessor(b.addView(uvs), kUnsignedShort, 3, "VEC2", 0, true)}};
  json primitive = {{"attributes", attributes},
                    {"indices", b.addAccessor(b.addView(indices), kUnsignedByte, 3, "SCALAR")}};
  int mesh = b.add("meshes", {{"primitives", {primitive}}});
  b.add("nodes", {{"mesh", mesh}, {"scale", {2, 1, 1}}});
  b.doc["scenes"] = {{{"nodes", {0}}}};
  fs::path path = dir_ / "triangle.glb";
  b.writeGlb(path);

  MeshScene scene = loadGltfScene(path);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const TriangleMesh& m = scene.meshes[0];
  EXPECT_EQ(m.name, "mesh 0#0");
  expectNear(m.positions[2], {2, -1, 0});
  // Inverse transpose of diag(2, 1, 1) maps (1, 1, 0) to (0.5, 1, 0): still perpendicular
  // to the stretched surface, unlike the naive (2, 1, 0).
  Vec3f expected = normalize(Vec3f(0.5f, 1, 0));
  for (const Vec3f& n : m.normals) expectNear(n, expected);
  expectNear(windingNormal(m, 0), expected);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_FLOAT_EQ(m.uvs[0].y, 1.0f);
  EXPECT_FLOAT_EQ(m.uvs[2].x, 32768.0f / 65535.0f);
  EXPECT_FLOAT_EQ(m.uvs[2].y, 0.2f);
}

TEST_F(GltfImportTest, NonIndexedTrianglesKeptAndOtherModesSkipped) {
  GltfBuilder b;
  std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1};
  int accessor = b.addAccessor(b.addView(positions), kFloat, 6, "VEC3");
  json triangles = {{"attributes", {{"POSITION", accessor}}}};
  json lines = {{"attributes", {{"POSITION", accessor}}}, {"mode", 1}};
  json points = {{"attributes", {{"POSITION", accessor}}}, {"mode", 0}};
  b.add("meshes", {{"name", "Mixed"}, {"primitives", {lines, triangles, points}}});
  b.add("nodes", {{"mesh", 0}});
  fs::path path = dir_ / "mixed.gltf";
  b.writeEmbedded(path);

  ::testing::internal::CaptureStderr();
  MeshScene scene = loadGltfScene(path);
  std::string warnings = ::testing::internal::GetCapturedStderr();
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].name, "Mixed#1");
  EXPECT_EQ(scene.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_TRUE(scene.meshes[0].normals.empty());
  EXPECT_TRUE(scene.meshes[0].uvs.empty());
  EXPECT_NE(warnings.find("skipped 2 primitive(s)"), std::string::npos) << warnings;
}

TEST_F(GltfImportTest, MaterialFactorsSpecularIorAndEmission) {
  GltfBuilder b;
  b.add("materials", {{"name", "Plastic"},
                      {"pbrMetallicRoughness",
                       {{"baseColorFactor", {0.2, 0.4, 0.6, 0.5}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.3}}},
                      {"emissiveFactor", {1.0, 0.5, 0.0}},
                      {"alphaMode", "BLEND"},
                      {"extensions",
                       {{"KHR_materials_specular",
                         {{"specularFactor", 0.5}, {"specularColorFactor", {1.0, 0.5, 0.25}}}},
                        {"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}}});
  b.add("materials", {{"name", "Gem"},
                      {"pbrMetallicRoughness", {{"metallicFactor", 0.0}}},
                      {"extensions", {{"KHR_materials_ior", {{"ior", 2.0}}}}}});
  b.add("materials", {{"name", "NoPbrBlock"}});
  for (int material : {0, 1, 2, -1}) b.add("nodes", {{"mesh", addQuadMesh(b, material)}});
  b.doc["extensionsUsed"] = {"KHR_materials_specular", "KHR_materials_emissive_strength", "KHR_materials_ior"};
  fs::path path = dir_ / "materials.gltf";
  b.writeEmbedded(path);

  ::testing::internal::CaptureStderr();
  MeshScene scene = loadGltfScene(path);
  std::string warnings = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(warnings.find("BLEND"), std::string::npos) << warnings;
  ASSERT_EQ(scene.meshes.size(), 4u);
  ASSERT_EQ(scene.materials.size(), 4u);
  Vec2f uv(0.5f, 0.5f);

  const Material& plastic = scene.materials[scene.meshes[0].material];
  EXPECT_EQ(plastic.name, "Plastic");
  expectNear(plastic.baseColor, {0.2f, 0.4f, 0.6f});
  EXPECT_FLOAT_EQ(plastic.metallic, 0.0f);
  EXPECT_FLOAT_EQ(plastic.roughness, 0.3f);
  EXPECT_FLOAT_EQ(plastic.specularLevel, 0.25f);
  expectNear(plastic.emission, {4, 2, 0});
  // glTF: F0 = 0.04 * specularColorFactor * specularFactor at the default ior 1.5.
  expectNear(scene.surfaceMaterial(scene.meshes[0].material, uv).F0, Vec3f(0.02f, 0.01f, 0.005f), 1e-6f);

  // KHR_materials_ior: F0 = ((2 - 1) / (2 + 1))^2 = 1/9.
  SurfaceMaterial gem = scene.surfaceMaterial(scene.meshes[1].material, uv);
  expectNear(gem.F0, Vec3f(1.0f / 9.0f), 1e-6f);
  expectNear(gem.baseColor, Vec3f(1.0f));

  // Both a material without a pbrMetallicRoughness block and a primitive without a
  // material take glTF's defaults: white, metallic 1, roughness 1.
  for (int i : {2, 3}) {
    const Material& m = scene.materials[scene.meshes[i].material];
    expectNear(m.baseColor, Vec3f(1.0f));
    EXPECT_FLOAT_EQ(m.metallic, 1.0f);
    EXPECT_FLOAT_EQ(m.roughness, 1.0f);
    expectNear(m.emission, Vec3f(0.0f));
  }
  EXPECT_EQ(scene.materials[scene.meshes[2].material].name, "NoPbrBlock");
}

TEST_F(GltfImportTest, TexturesDecodedOncePerColourSpace) {
  GltfBuilder b;
  // 2x2 8-bit RGB: the first texel's 128 is in the sRGB power segment, the third's 10 in
  // the linear segment.
  std::vector<uint16_t> rgb = {0, 128, 255, 255, 0, 64, 10, 20, 30, 200, 100, 50};
  int colour = b.addPngTexture(test::encodePng(2, 2, 3, 8, rgb));
  // 2x2 16-bit grey emission texture, stored as an external file.
  std::vector<uint16_t> grey = {0, 65535, 32768, 1000};
  test::Bytes png = test::encodePng(2, 2, 1, 16, grey);
  test::writeBytes(dir_ / "glow.png", png.data(), png.size());
  int glow = b.add("textures", {{"source", b.add("images", {{"uri", "glow.png"}})}});
  b.add("materials", {{"pbrMetallicRoughness",
                       {{"baseColorTexture", {{"index", colour}}}, {"metallicRoughnessTexture", {{"index", colour}}}}},
                      {"emissiveTexture", {{"index", glow}}},
                      {"emissiveFactor", {1.0, 1.0, 1.0}}});
  b.add("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", colour}}}}}});
  b.add("nodes", {{"mesh", addQuadMesh(b, 0)}});
  b.add("nodes", {{"mesh", addQuadMesh(b, 1)}});
  fs::path path = dir_ / "textured.gltf";
  b.writeExternal(path, "textured.bin");

  MeshScene scene = loadGltfScene(path);
  // One image as sRGB colour, the same as linear data, and the emission map: shared by
  // both materials, so three textures in all.
  ASSERT_EQ(scene.textures.size(), 3u);
  const Material& m = scene.materials[scene.meshes[0].material];
  EXPECT_EQ(scene.materials[scene.meshes[1].material].baseColorTexture, m.baseColorTexture);
  const Image& base = scene.textures[m.baseColorTexture].image;
  const Image& data = scene.textures[m.metallicRoughnessTexture].image;
  const Image& emission = scene.textures[m.emissionTexture].image;
  ASSERT_EQ(base.channels, 3);
  ASSERT_EQ(emission.channels, 1);
  for (int i = 0; i < 12; ++i) {
    EXPECT_NEAR(base.pixels[i], srgbToLinear(rgb[i] / 255.0), 1e-6) << i;
    EXPECT_NEAR(data.pixels[i], rgb[i] / 255.0, 1e-6) << i;
  }
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(emission.pixels[i], srgbToLinear(grey[i] / 65535.0), 1e-6) << i;

  // At the top-left texel centre: G is roughness and B metallic, both linear.
  SurfaceMaterial s = scene.surfaceMaterial(scene.meshes[0].material, Vec2f(0.25f, 0.25f));
  EXPECT_NEAR(s.baseColor.y, srgbToLinear(128 / 255.0), 1e-6);
  EXPECT_NEAR(s.roughness, 128 / 255.0, 1e-6);
  EXPECT_NEAR(s.metallic, 1.0, 1e-6);
  EXPECT_NEAR(s.emission.x, 0.0, 1e-6);
}

TEST_F(GltfImportTest, UnsupportedTextureFeaturesAreIgnoredWithWarnings) {
  GltfBuilder b;
  int colour = b.addPngTexture(test::encodePng(1, 1, 4, 8, {255, 128, 0, 10}));
  json transform = {{"KHR_texture_transform", {{"scale", {2.0, 2.0}}}}};
  b.add("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", colour}, {"texCoord", 1}}}}},
                      {"emissiveTexture", {{"index", colour}, {"extensions", transform}}},
                      {"emissiveFactor", {1.0, 1.0, 1.0}},
                      {"normalTexture", {{"index", colour}}}});
  b.add("nodes", {{"mesh", addQuadMesh(b, 0)}});
  b.doc["extensionsUsed"] = {"KHR_texture_transform", "KHR_materials_clearcoat"};
  fs::path path = dir_ / "unsupported.gltf";
  b.writeEmbedded(path);

  ::testing::internal::CaptureStderr();
  MeshScene scene = loadGltfScene(path);
  std::string warnings = ::testing::internal::GetCapturedStderr();
  const Material& m = scene.materials[0];
  EXPECT_EQ(m.baseColorTexture, -1);  // on TEXCOORD_1: dropped
  ASSERT_GE(m.emissionTexture, 0);    // transform ignored, texture kept
  const Image& emission = scene.textures[m.emissionTexture].image;
  EXPECT_EQ(emission.channels, 3);  // alpha dropped
  EXPECT_NEAR(emission.pixels[1], srgbToLinear(128 / 255.0), 1e-6);
  for (const char* expected : {"TEXCOORD_1", "KHR_texture_transform is ignored", "normal and occlusion",
                               "ignoring extensions Glint does not support: KHR_materials_clearcoat"})
    EXPECT_NE(warnings.find(expected), std::string::npos) << expected << " in:\n" << warnings;
}

TEST_F(GltfImportTest, PunctualLightsFollowTheirNodes) {
  GltfBuilder b;
  b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 10.0}},
      {{"type", "spot"}, {"intensity", 100.0}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}},
      {{"type", "directional"}, {"intensity", 3.0}}};
  auto lightNode = [](int light) { return json{{"extensions", {{"KHR_lights_punctual", {{"light", light}}}}}}; };
  json point = lightNode(0), spot = lightNode(1), sun = lightNode(2);
  point["translation"] = {1, 2, 3};
  spot["translation"] = {0, 5, 0};
  spot["rotation"] = {-kHalfSqrt2, 0, 0, kHalfSqrt2};  // -90 degrees about X: -Z turns to -Y
  sun["rotation"] = {0, kHalfSqrt2, 0, kHalfSqrt2};    // 90 degrees about Y: -Z turns to -X
  int pointNode = b.add("nodes", point), spotNode = b.add("nodes", spot), sunNode = b.add("nodes", sun);
  int lifted = b.add("nodes", {{"translation", {0, 10, 0}}, {"children", {pointNode}}});
  int scaled = b.add("nodes", {{"scale", {3, 3, 3}}, {"children", {spotNode}}});
  int quad = b.add("nodes", {{"mesh", addQuadMesh(b)}});
  b.doc["scenes"] = {{{"nodes", {quad}}}, {{"nodes", {quad, lifted, scaled, sunNode}}}};
  b.doc["scene"] = 1;
  fs::path path = dir_ / "lights.gltf";
  b.writeEmbedded(path);

  MeshScene scene = loadGltfScene(path);
  ASSERT_EQ(scene.lights.size(), 3u);
  const PunctualLight& p = scene.lights[0];
  EXPECT_EQ(p.type, PunctualLight::Type::Point);
  expectNear(p.position, {1, 12, 3});
  expectNear(p.intensity, {10, 5, 2.5f});
  const PunctualLight& s = scene.lights[1];
  EXPECT_EQ(s.type, PunctualLight::Type::Spot);
  expectNear(s.position, {0, 15, 0});
  expectNear(s.direction, {0, -1, 0});  // unit length despite the parent's scale
  expectNear(s.intensity, Vec3f(100.0f));
  EXPECT_FLOAT_EQ(s.innerConeAngle, 0.2f);
  EXPECT_FLOAT_EQ(s.outerConeAngle, 0.5f);
  const PunctualLight& d = scene.lights[2];
  EXPECT_EQ(d.type, PunctualLight::Type::Directional);
  expectNear(d.direction, {-1, 0, 0});
  expectNear(d.intensity, Vec3f(3.0f));
}

TEST_F(GltfImportTest, ErrorsNameTheFile) {
  expectLoadError(dir_ / "missing.gltf", "not found");

  fs::path malformed = dir_ / "malformed.gltf";
  std::ofstream(malformed) << "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ {";
  expectLoadError(malformed, "could not be read as glTF 2.0");

  GltfBuilder draco;
  draco.add("nodes", {{"mesh", addQuadMesh(draco)}});
  draco.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  draco.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  fs::path dracoPath = dir_ / "draco.gltf";
  draco.writeEmbedded(dracoPath);
  expectLoadError(dracoPath, "requires extension KHR_draco_mesh_compression which Glint does not support");

  GltfBuilder overrun;
  overrun.add("nodes", {{"mesh", addQuadMesh(overrun)}});
  overrun.doc["accessors"][0]["count"] = 400;  // POSITION: 400 vertices of 32 bytes
  fs::path overrunPath = dir_ / "overrun.glb";
  overrun.writeGlb(overrunPath);
  expectLoadError(overrunPath, "reads past the end of buffer view 0");

  GltfBuilder sparse;
  sparse.add("nodes", {{"mesh", addQuadMesh(sparse)}});
  std::vector<uint8_t> sparseIndex = {1};
  std::vector<float> sparseValue = {0, 0, 5};
  sparse.doc["accessors"][0]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", sparse.addView(sparseIndex)}, {"componentType", kUnsignedByte}}},
      {"values", {{"bufferView", sparse.addView(sparseValue)}}}};
  fs::path sparsePath = dir_ / "sparse.gltf";
  sparse.writeEmbedded(sparsePath);
  expectLoadError(sparsePath, "Glint does not support sparse accessors");

  GltfBuilder noPosition;
  std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  int normalAccessor = noPosition.addAccessor(noPosition.addView(normals), kFloat, 3, "VEC3");
  json primitive = {{"attributes", {{"NORMAL", normalAccessor}}}};
  noPosition.add("nodes", {{"mesh", noPosition.add("meshes", {{"primitives", {primitive}}})}});
  fs::path noPositionPath = dir_ / "no_position.gltf";
  noPosition.writeEmbedded(noPositionPath);
  expectLoadError(noPositionPath, "has no POSITION attribute");

  GltfBuilder missingImage;
  int texture = missingImage.add("textures", {{"source", missingImage.add("images", {{"uri", "absent.png"}})}});
  missingImage.add("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}}}}}});
  missingImage.add("nodes", {{"mesh", addQuadMesh(missingImage, 0)}});
  fs::path missingImagePath = dir_ / "missing_image.gltf";
  missingImage.writeEmbedded(missingImagePath);
  ::testing::internal::CaptureStderr();  // tinygltf's own warning about the file
  expectLoadError(missingImagePath, "image 0 (absent.png) could not be decoded: File not found");
  EXPECT_NE(::testing::internal::GetCapturedStderr().find("absent.png"), std::string::npos);
}

// Issue 19: sizes a file states must be checked without overflow, and against the bytes
// present, before anything is allocated. Each case crashed or allocated gigabytes before.
TEST_F(GltfImportTest, HostileSizesAreRefusedBeforeAllocating) {
  const uint64_t kNear2Pow64 = ~uint64_t(0) - (uint64_t(1) << 40) + 1;  // 2^64 - 2^40

  // byteOffset + byteLength wrapped around 2^64 and passed the bound check: a segfault.
  GltfBuilder viewOffset;
  viewOffset.add("nodes", {{"mesh", addQuadMesh(viewOffset)}});
  viewOffset.doc["bufferViews"][0]["byteOffset"] = kNear2Pow64;
  viewOffset.doc["bufferViews"][0]["byteLength"] = (uint64_t(1) << 40) + 128;
  fs::path viewOffsetPath = dir_ / "view_offset.gltf";
  viewOffset.writeEmbedded(viewOffsetPath);
  expectLoadError(viewOffsetPath, "buffer view 0 (1099511627904 bytes from byte 18446742974197923840) extends past "
                                  "the end of buffer 0");

  // The accessor's own offset wrapped the same way (reading before the buffer).
  GltfBuilder accessorOffset;
  accessorOffset.add("nodes", {{"mesh", addQuadMesh(accessorOffset)}});
  accessorOffset.doc["accessors"][0]["byteOffset"] = ~uint64_t(0) - 15;
  fs::path accessorOffsetPath = dir_ / "accessor_offset.gltf";
  accessorOffset.writeEmbedded(accessorOffsetPath);
  expectLoadError(accessorOffsetPath, "accessor 0 (primitive 'Quad#0' POSITION) reads past the end of buffer view 0");

  // count * stride wrapped to 0 for an index accessor: a length_error from resize.
  GltfBuilder indexCount;
  indexCount.add("nodes", {{"mesh", addQuadMesh(indexCount)}});
  indexCount.doc["accessors"][3]["count"] = (uint64_t(1) << 63) + 1;  // 2-byte indices
  fs::path indexCountPath = dir_ / "index_count.gltf";
  indexCount.writeEmbedded(indexCountPath);
  expectLoadError(indexCountPath, "accessor 3 (primitive 'Quad#0' indices) reads past the end of buffer view 1");

  // Accessors without a buffer view (all zeros) declaring 2^27 elements allocated 3.1 GB
  // from a file of a few hundred bytes; 2^40 ended in a bare std::bad_alloc.
  for (int power : {27, 40}) {
    GltfBuilder zeros;
    int positions =
        zeros.add("accessors", {{"componentType", kFloat}, {"count", uint64_t(1) << power}, {"type", "VEC3"}});
    json primitive = {{"attributes", {{"POSITION", positions}}}};
    zeros.add("nodes", {{"mesh", zeros.add("meshes", {{"primitives", {primitive}}})}});
    fs::path zerosPath = dir_ / ("zeros_2pow" + std::to_string(power) + ".gltf");
    std::ofstream(zerosPath) << zeros.doc.dump();  // no buffers at all, as in the file
    expectLoadError(zerosPath, "accessor 0 (primitive 'mesh 0#0' POSITION) has no buffer view (all zeros) and " +
                                   std::to_string(uint64_t(1) << power) + " elements, more than the 0 of the "
                                   "largest accessor with data in its primitive");
  }
}

// All-zero accessors as large as the primitive's accessors with data are still read.
TEST_F(GltfImportTest, ZeroAccessorsUpToTheDataCountAreRead) {
  GltfBuilder b;
  int quad = addQuadMesh(b);
  b.doc["accessors"][2].erase("bufferView");  // TEXCOORD_0: 4 elements of zeros
  b.doc["accessors"][2].erase("byteOffset");
  b.add("nodes", {{"mesh", quad}});
  fs::path path = dir_ / "zero_uvs.gltf";
  b.writeEmbedded(path);
  MeshScene scene = loadGltfScene(path);
  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_EQ(scene.meshes[0].uvs.size(), 4u);
  for (const Vec2f& uv : scene.meshes[0].uvs) {
    EXPECT_EQ(uv.x, 0.0f);
    EXPECT_EQ(uv.y, 0.0f);
  }
}

// Node trees are walked without recursion: a chain of 100000 nodes (a 5 MB file) overflowed
// the stack. A node reached twice, by a cycle or from two parents (which made the walk
// exponential: 40 nodes each listing the next twice), is refused.
TEST_F(GltfImportTest, NodeHierarchiesAreWalkedWithoutRecursionAndMustBeTrees) {
  constexpr int kChain = 100000;
  GltfBuilder chain;
  int quad = addQuadMesh(chain);
  for (int i = 0; i < kChain; ++i)
    chain.add("nodes", i + 1 < kChain ? json{{"children", {i + 1}}, {"translation", {0.0, 1e-6, 0.0}}}
                                      : json{{"mesh", quad}});
  chain.doc["scenes"] = {{{"nodes", {0}}}};
  fs::path chainPath = dir_ / "chain.gltf";
  chain.writeEmbedded(chainPath);
  MeshScene scene = loadGltfScene(chainPath);
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_NEAR(scene.meshes[0].positions[0].y, (kChain - 1) * 1e-6, 1e-4);

  GltfBuilder shared;
  int mesh = addQuadMesh(shared);
  for (int i = 0; i < 40; ++i)
    shared.add("nodes", i + 1 < 40 ? json{{"children", {i + 1, i + 1}}} : json{{"mesh", mesh}});
  shared.doc["scenes"] = {{{"nodes", {0}}}};
  fs::path sharedPath = dir_ / "shared.gltf";
  shared.writeEmbedded(sharedPath);
  expectLoadError(sharedPath, "node 39 is reached twice (through a cycle or two parents)");

  GltfBuilder cycle;
  cycle.add("nodes", {{"children", {1}}, {"mesh", addQuadMesh(cycle)}});
  cycle.add("nodes", {{"children", {0}}});
  cycle.doc["scenes"] = {{{"nodes", {0}}}};
  fs::path cyclePath = dir_ / "cycle.gltf";
  cycle.writeEmbedded(cyclePath);
  expectLoadError(cyclePath, "node 0 is reached twice");
}

// Found by fuzzing: a buffer URI naming a folder ("%%" decodes to the glTF's own folder)
// made tinygltf size its read by seeking a directory, 2^63 - 1 bytes: std::bad_alloc.
TEST_F(GltfImportTest, BufferUriNamingAFolderIsAnError) {
  GltfBuilder b;
  b.add("nodes", {{"mesh", addQuadMesh(b)}});
  fs::path path = dir_ / "folder_uri.gltf";
  b.writeExternal(path, "quad.bin");
  json doc = json::parse(std::ifstream(path));
  doc["buffers"][0]["uri"] = ".";
  std::ofstream(path) << doc.dump();
  expectLoadError(path, "not a regular non-empty file");
}

}  // namespace
}  // namespace glint
