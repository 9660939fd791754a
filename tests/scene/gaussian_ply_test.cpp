// Gaussian scene PLY files: bit-exact Glint round trips, 3DGS export and auto-detection,
// lookup by name in any order and type, and clear errors naming the file.
#include "scene/gaussian_ply.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "common/expect_error.h"
#include "core/error.h"
#include "io/temp_folder.h"
#include "math/rng.h"

namespace glint {
namespace {

using test::expectErrorNaming;

namespace fs = std::filesystem;
using test::TempFolder;

// A deterministic scene with awkward values: negative zero, a subnormal, large and tiny
// magnitudes, and unnormalised quaternions (stored as is; normalised only on use).
GaussianScene randomScene(size_t n, uint64_t seed) {
  Rng rng(seed);
  auto symmetric = [&](float range) { return (2.0f * rng.uniform() - 1.0f) * range; };
  GaussianScene scene;
  scene.resize(n);
  for (size_t i = 0; i < n; ++i) {
    scene.position[i] = {symmetric(10.0f), symmetric(10.0f), symmetric(1000.0f)};
    scene.rotation[i] = {symmetric(2.0f), symmetric(2.0f), symmetric(2.0f), symmetric(2.0f)};
    scene.logScale[i] = {symmetric(8.0f), symmetric(8.0f), symmetric(8.0f)};
    scene.opacityLogit[i] = symmetric(12.0f);
    scene.diffuse[i] = {rng.uniform(), rng.uniform(), rng.uniform() * 4.0f};
    scene.normal[i] = {symmetric(1.0f), symmetric(1.0f), symmetric(1.0f)};
    scene.roughness[i] = rng.uniform();
    scene.f0[i] = {rng.uniform(), rng.uniform(), rng.uniform()};
  }
  scene.position[0] = {-0.0f, 1.0e-40f, 3.0e38f};
  scene.rotation[0] = {1.0f, 0.0f, -0.0f, 0.0f};
  scene.diffuse[1] = {-0.0f, 0.0f, 1.0f};
  scene.roughness[1] = 1.0e-42f;
  return scene;
}

bool sameBits(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }
bool sameBits(const Vec3f& a, const Vec3f& b) { return sameBits(a.x, b.x) && sameBits(a.y, b.y) && sameBits(a.z, b.z); }
bool sameBits(const Quatf& a, const Quatf& b) {
  return sameBits(a.w, b.w) && sameBits(a.x, b.x) && sameBits(a.y, b.y) && sameBits(a.z, b.z);
}

// Position, rotation, scale and opacity: the geometry both layouts store unchanged.
void expectSameGeometry(const GaussianScene& a, const GaussianScene& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(sameBits(a.position[i], b.position[i])) << "position " << i;
    EXPECT_TRUE(sameBits(a.rotation[i], b.rotation[i])) << "rotation " << i;
    EXPECT_TRUE(sameBits(a.logScale[i], b.logScale[i])) << "logScale " << i;
    EXPECT_TRUE(sameBits(a.opacityLogit[i], b.opacityLogit[i])) << "opacity " << i;
  }
}


// A minimal Glint-layout table of n Gaussians (all required properties, no optional ones).
PlyTable minimalTable(size_t n) {
  PlyTable table;
  for (const char* name : {"x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2", "opacity", "scale_0", "scale_1", "scale_2",
                           "rot_1", "rot_2", "rot_3"}) {
    table.add(name, std::vector<float>(n, 0.25f));
  }
  table.add("rot_0", std::vector<float>(n, 1.0f));
  return table;
}

TEST(GaussianPly, GlintLayoutRoundTripsBitForBit) {
  TempFolder folder;
  GaussianScene scene = randomScene(300, 7);
  fs::path path = folder / "scene.ply";
  writeGaussianPly(path, scene);

  // The header holds the paper's properties in the paper's order, all float32.
  PlyTable table = readPly(path);
  std::vector<std::string> expected = {"x",       "y",       "z",       "f_dc_0",   "f_dc_1",   "f_dc_2",
                                       "opacity", "scale_0", "scale_1", "scale_2",  "rot_0",    "rot_1",
                                       "rot_2",   "rot_3",   "normal_0", "normal_1", "normal_2", "roughness",
                                       "f0_0",    "f0_1",    "f0_2"};
  EXPECT_EQ(table.names, expected);
  for (PlyType type : table.types) EXPECT_EQ(type, PlyType::Float32);
  EXPECT_EQ(detectGaussianPlyLayout(table), PlyLayout::Glint);

  PlyLayout detected = PlyLayout::Auto;
  GaussianScene read = readGaussianPly(path, PlyLayout::Auto, &detected);
  EXPECT_EQ(detected, PlyLayout::Glint);
  ASSERT_TRUE(read.consistent());
  expectSameGeometry(scene, read);
  for (size_t i = 0; i < scene.size(); ++i) {
    EXPECT_TRUE(sameBits(scene.diffuse[i], read.diffuse[i])) << i;
    EXPECT_TRUE(sameBits(scene.normal[i], read.normal[i])) << i;
    EXPECT_TRUE(sameBits(scene.roughness[i], read.roughness[i])) << i;
    EXPECT_TRUE(sameBits(scene.f0[i], read.f0[i])) << i;
  }
}

TEST(GaussianPly, EmptySceneRoundTrips) {
  TempFolder folder;
  fs::path path = folder / "empty.ply";
  writeGaussianPly(path, GaussianScene{});
  EXPECT_TRUE(readGaussianPly(path).empty());
  exportGaussianPly3dgs(path, GaussianScene{});
  EXPECT_TRUE(readGaussianPly(path).empty());
}

// A scene written before the parameter table (scene/gaussian_parameters.h) chose the
// columns (tests/data/README.md) loads with every value in its place, and is written again
// byte for byte.
TEST(GaussianPly, SceneWrittenBeforeTheParameterTableLoadsAndRewritesIdentically) {
  const fs::path fixture = fs::path(GLINT_TEST_DATA) / "version1_run" / "scene.ply";
  GaussianScene scene = readGaussianPly(fixture);
  ASSERT_EQ(scene.size(), 2u);
  // Gaussian 1 as the file stores it, x to f0_2.
  EXPECT_EQ(scene.position[1], Vec3f(1.8507344722747803f, 0.7678765058517456f, 0.29158538579940796f));
  EXPECT_EQ(scene.diffuse[1], Rgb(0.0007831563707441092f, 0.0008220239542424679f, 0.0008220239542424679f));
  EXPECT_EQ(scene.opacityLogit[1], -1.89443039894104f);
  EXPECT_EQ(scene.logScale[1], Vec3f(-0.9734911322593689f, -0.9294913411140442f, -0.9274319410324097f));
  EXPECT_TRUE(sameBits(scene.rotation[1], Quatf{1.0069531202316284f, -0.0024051975924521685f,
                                                -0.0017471248283982277f, 0.0007140557281672955f}));
  EXPECT_EQ(scene.normal[1], Vec3f(0.02996869571506977f, 0.012363441288471222f, -0.001348507939837873f));
  EXPECT_EQ(scene.roughness[1], 0.1303783655166626f);
  EXPECT_EQ(scene.f0[1], Rgb(0.0703783705830574f));

  TempFolder folder;
  writeGaussianPly(folder / "again.ply", scene);
  EXPECT_EQ(test::readBytes(folder / "again.ply"), test::readBytes(fixture));
}

TEST(GaussianPly, ThreeDgsExportIsStandardAndLoadsBack) {
  TempFolder folder;
  GaussianScene scene = randomScene(300, 11);
  fs::path path = folder / "splat.ply";
  exportGaussianPly3dgs(path, scene);

  PlyTable table = readPly(path);
  std::vector<std::string> expected = {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"};
  for (int k = 0; k < 45; ++k) expected.push_back("f_rest_" + std::to_string(k));
  for (const char* name : {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"})
    expected.push_back(name);
  EXPECT_EQ(table.names, expected);
  for (PlyType type : table.types) EXPECT_EQ(type, PlyType::Float32);
  for (const std::string& name : expected) {
    if (name.rfind("f_rest_", 0) == 0 || name == "nx" || name == "ny" || name == "nz") {
      for (float v : table.column(name)) ASSERT_EQ(v, 0.0f) << name;
    }
  }
  // f_dc is the SH DC coefficient: colour = 0.5 + C0 * f_dc.
  EXPECT_NEAR(0.5 + kShC0 * table.column("f_dc_0")[2], scene.diffuse[2].x, 1e-6);

  PlyLayout detected = PlyLayout::Auto;
  GaussianScene read = readGaussianPly(path, PlyLayout::Auto, &detected);
  EXPECT_EQ(detected, PlyLayout::ThreeDgs);
  expectSameGeometry(scene, read);
  for (size_t i = 0; i < scene.size(); ++i) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(read.diffuse[i][k], scene.diffuse[i][k], 1e-6) << i;
    // 3DGS has no materials: the defaults come back.
    EXPECT_EQ(read.normal[i], Vec3f(0.0f));
    EXPECT_EQ(read.roughness[i], 0.0f);
    EXPECT_EQ(read.f0[i], Rgb(0.04f));
  }
}

TEST(GaussianPly, LayoutDetectionRuleAndExplicitOverride) {
  PlyTable plain = minimalTable(1);
  EXPECT_EQ(detectGaussianPlyLayout(plain), PlyLayout::Glint);
  PlyTable withRest = minimalTable(1);
  withRest.add("f_rest_0", {0.0f});
  EXPECT_EQ(detectGaussianPlyLayout(withRest), PlyLayout::ThreeDgs);
  PlyTable withNormals = minimalTable(1);
  withNormals.add("nx", {0.0f});
  EXPECT_EQ(detectGaussianPlyLayout(withNormals), PlyLayout::ThreeDgs);
  // Any Glint-only property wins: the file is Glint's even with 3DGS extras.
  for (const char* glintOnly : {"normal_0", "roughness", "f0_0"}) {
    PlyTable mixed = minimalTable(1);
    mixed.add("f_rest_0", {0.0f});
    mixed.add("nx", {0.0f});
    mixed.add(glintOnly, {0.0f});
    EXPECT_EQ(detectGaussianPlyLayout(mixed), PlyLayout::Glint) << glintOnly;
  }

  // The explicit layout overrides detection in both directions.
  TempFolder folder;
  GaussianScene scene = randomScene(4, 3);
  fs::path glintPath = folder / "glint.ply", splatPath = folder / "splat.ply";
  writeGaussianPly(glintPath, scene);
  exportGaussianPly3dgs(splatPath, scene);
  GaussianScene asSh = readGaussianPly(glintPath, PlyLayout::ThreeDgs);
  EXPECT_FLOAT_EQ(asSh.diffuse[2].y, float(0.5 + kShC0 * scene.diffuse[2].y));
  EXPECT_EQ(asSh.roughness[2], scene.roughness[2]);  // materials are still read
  GaussianScene raw = readGaussianPly(splatPath, PlyLayout::Glint);
  EXPECT_FLOAT_EQ(raw.diffuse[2].y, float((scene.diffuse[2].y - 0.5) / kShC0));
  EXPECT_STREQ(plyLayoutName(PlyLayout::ThreeDgs), "3dgs");
}

TEST(GaussianPly, UnusualOrderMixedTypesAndUnknownPropertiesLoad) {
  TempFolder folder;
  // Reversed order, a double x, integer rotation and extra properties of several types.
  PlyTable table;
  table.add("confidence", {200.0f, 3.0f}, PlyType::UInt8);
  table.add("f0_2", {0.5f, 0.25f});
  table.add("f0_1", {0.5f, 0.25f});
  table.add("f0_0", {0.5f, 0.25f});
  table.add("roughness", {0.75f, 0.125f}, PlyType::Float64);
  table.add("rot_3", {0.0f, 1.0f}, PlyType::Int8);
  table.add("rot_2", {0.0f, 0.0f}, PlyType::Int8);
  table.add("rot_1", {0.0f, 0.0f}, PlyType::Int8);
  table.add("rot_0", {2.0f, 0.0f}, PlyType::Int8);
  table.add("label", {-7.0f, 100000.0f}, PlyType::Int32);
  table.add("scale_2", {-1.0f, -2.0f});
  table.add("scale_1", {-1.5f, -2.5f});
  table.add("scale_0", {-3.0f, -4.0f});
  table.add("opacity", {0.5f, -0.5f}, PlyType::Float64);
  table.add("f_dc_2", {0.3f, 0.6f});
  table.add("f_dc_1", {0.2f, 0.5f});
  table.add("f_dc_0", {0.1f, 0.4f});
  table.add("z", {3.0f, 6.0f}, PlyType::Int16);
  table.add("y", {2.0f, 5.0f});
  table.add("x", {1.0f, 0.1f}, PlyType::Float64);
  table.add("f_rest_0", {9.0f, 9.0f});  // a 3DGS property, ignored (and roughness keeps this Glint)
  fs::path path = folder / "odd.ply";
  writePly(path, table);

  GaussianScene scene = readGaussianPly(path);
  ASSERT_EQ(scene.size(), 2u);
  EXPECT_EQ(scene.position[0], Vec3f(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(scene.position[1], Vec3f(0.1f, 5.0f, 6.0f));  // double 0.1f read back as float 0.1f
  EXPECT_TRUE(sameBits(scene.rotation[0], Quatf{2.0f, 0.0f, 0.0f, 0.0f}));
  EXPECT_TRUE(sameBits(scene.rotation[1], Quatf{0.0f, 0.0f, 0.0f, 1.0f}));
  EXPECT_EQ(scene.logScale[1], Vec3f(-4.0f, -2.5f, -2.0f));
  EXPECT_EQ(scene.opacityLogit[1], -0.5f);
  EXPECT_EQ(scene.diffuse[0], Rgb(0.1f, 0.2f, 0.3f));  // Glint layout: colour as is
  EXPECT_EQ(scene.roughness[0], 0.75f);
  EXPECT_EQ(scene.f0[1], Rgb(0.25f));
  EXPECT_EQ(scene.normal[0], Vec3f(0.0f));  // absent: default
}

TEST(GaussianPly, MissingRequiredPropertyIsNamed) {
  TempFolder folder;
  const char* requiredNames[] = {"x",       "y",       "z",       "f_dc_0", "f_dc_1", "f_dc_2", "opacity",
                                 "scale_0", "scale_1", "scale_2", "rot_0",  "rot_1",  "rot_2",  "rot_3"};
  for (const char* missing : requiredNames) {
    PlyTable full = minimalTable(3), table;
    for (size_t c = 0; c < full.names.size(); ++c) {
      if (full.names[c] != missing) table.add(full.names[c], full.columns[c]);
    }
    fs::path path = folder / (std::string("without_") + missing + ".ply");
    writePly(path, table);
    expectErrorNaming([&] { readGaussianPly(path); }, path, {"'" + std::string(missing) + "'"});
  }
  // An optional group is all or nothing.
  PlyTable partial = minimalTable(3);
  partial.add("normal_0", {0.0f, 0.0f, 1.0f});
  partial.add("normal_2", {0.0f, 0.0f, 1.0f});
  fs::path path = folder / "partial_normal.ply";
  writePly(path, partial);
  expectErrorNaming([&] { readGaussianPly(path); }, path, {"'normal_0'", "'normal_1'"});
}

TEST(GaussianPly, ZeroQuaternionIsAnErrorNamingTheVertex) {
  TempFolder folder;
  GaussianScene scene = randomScene(10, 5);
  scene.rotation[6] = {0.0f, -0.0f, 0.0f, 0.0f};
  fs::path path = folder / "zero_rotation.ply";
  writeGaussianPly(path, scene);
  expectErrorNaming([&] { readGaussianPly(path); }, path, {"vertex 6", "zero rotation quaternion"});
}

TEST(GaussianPly, DamagedAndForeignFilesAreRejectedNamingTheFile) {
  TempFolder folder;
  GaussianScene scene = randomScene(50, 9);

  fs::path truncated = folder / "truncated.ply";
  writeGaussianPly(truncated, scene);
  test::truncateToHalf(truncated);
  expectErrorNaming([&] { readGaussianPly(truncated); }, truncated, {"truncated"});

  fs::path bigEndian = folder / "big_endian.ply";
  writeGaussianPly(bigEndian, scene);
  std::string bytes = test::readBytes(bigEndian);
  bytes.replace(bytes.find("binary_little_endian"), 20, "binary_big_endian");
  test::writeBytes(bigEndian, bytes);
  expectErrorNaming([&] { readGaussianPly(bigEndian); }, bigEndian, {"big-endian"});

  fs::path ascii = folder / "ascii.ply";
  test::writeBytes(ascii,
                   "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                   "end_header\n0 0 0\n");
  expectErrorNaming([&] { readGaussianPly(ascii); }, ascii, {"ASCII"});

  // Overwrite the opacity of vertex 3 (column 6 of 21 float32 columns) with a NaN.
  fs::path nan = folder / "nan.ply";
  writeGaussianPly(nan, scene);
  bytes = test::readBytes(nan);
  size_t data = bytes.find("end_header\n") + 11;
  float quietNan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&bytes[data + (3 * 21 + 6) * 4], &quietNan, 4);
  test::writeBytes(nan, bytes);
  expectErrorNaming([&] { readGaussianPly(nan); }, nan, {"'opacity'", "vertex 3", "NaN"});

  expectErrorNaming([&] { readGaussianPly(folder / "missing.ply"); }, folder / "missing.ply", {"not found"});
}

TEST(GaussianPly, WritingANanFailsAndLeavesTheOldFileIntact) {
  TempFolder folder;
  GaussianScene scene = randomScene(20, 13);
  fs::path path = folder / "scene.ply";
  writeGaussianPly(path, scene);
  GaussianScene bad = scene;
  bad.logScale[4].y = std::numeric_limits<float>::quiet_NaN();
  expectErrorNaming([&] { writeGaussianPly(path, bad); }, path, {"scale_1", "NaN"});
  bad.logScale[4].y = 0.0f;
  bad.diffuse[2].z = std::numeric_limits<float>::infinity();
  expectErrorNaming([&] { exportGaussianPly3dgs(path, bad); }, path, {"f_dc_2", "infinite"});
  // The failed writes touched neither the file nor the folder.
  expectSameGeometry(scene, readGaussianPly(path));
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(folder.path())) files += entry.is_regular_file();
  EXPECT_EQ(files, 1u);
}

}  // namespace
}  // namespace glint
