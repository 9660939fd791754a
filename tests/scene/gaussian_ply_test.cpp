// Gaussian scene PLY files: bit-exact Glint round trips, 3DGS export (display colour, SH
// degree) and import (layout detection, material defaults), lookup by name in any order and
// type, and clear errors naming the file.
#include "scene/gaussian_ply.h"

#include <gtest/gtest.h>

#include <algorithm>
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
#include "io/tonemap.h"
#include "math/mat3.h"
#include "math/quat.h"
#include "math/rng.h"
#include "scene/imported_materials.h"

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

  GaussianPlyImport import;
  GaussianScene read = readGaussianPly(path, PlyLayout::Auto, &import);
  EXPECT_EQ(import.layout, PlyLayout::Glint);
  EXPECT_EQ(describeImport(import), "");
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

TEST(GaussianPly, LayoutDetectionRuleAndExplicitOverride) {
  auto expectAmbiguous = [](const PlyTable& table, const std::string& why) {
    expectErrorNaming([&] { detectGaussianPlyLayout(table); }, "table.ply", {"--input-layout", why});
  };
  PlyTable plain = minimalTable(1);
  plain.source = "table.ply";
  // Only the properties both layouts share, no header: a degree-0 splat file, read as 3DGS,
  // and the caller is told that the missing header alone decided.
  bool assumed = false;
  EXPECT_EQ(detectGaussianPlyLayout(plain, &assumed), PlyLayout::ThreeDgs);
  EXPECT_TRUE(assumed);
  // The properties only one layout writes decide ...
  for (const char* splatOnly : {"f_rest_0", "f_rest_44", "nx", "nz"}) {
    PlyTable table = plain;
    table.add(splatOnly, {0.0f});
    EXPECT_EQ(detectGaussianPlyLayout(table, &assumed), PlyLayout::ThreeDgs) << splatOnly;
    EXPECT_FALSE(assumed);
  }
  for (const char* glintOnly : {"normal_0", "roughness", "f0_1"}) {
    PlyTable table = plain;
    table.add(glintOnly, {0.0f});
    EXPECT_EQ(detectGaussianPlyLayout(table), PlyLayout::Glint) << glintOnly;
    // ... and with 3DGS's own as well, a file without Glint's header is 3DGS's.
    table.add("f_rest_0", {0.0f});
    EXPECT_EQ(detectGaussianPlyLayout(table), PlyLayout::ThreeDgs) << glintOnly;
  }
  // A comment decides before the properties; a Glint header contradicted by 3DGS's own
  // properties, or both comments, are refused.
  PlyTable commented = plain;
  commented.comments = {"Glint Gaussian scene: f_dc_0..2 is linear diffuse colour (not SH)"};
  EXPECT_EQ(detectGaussianPlyLayout(commented), PlyLayout::Glint);
  commented.add("f_rest_0", {0.0f});
  expectAmbiguous(commented, "header says Glint's layout, but it has 3DGS's 'f_rest_0'");
  PlyTable exported = plain;
  exported.comments = {"made by hand", splatColourComment({})};
  EXPECT_EQ(detectGaussianPlyLayout(exported), PlyLayout::ThreeDgs);
  exported.comments.push_back(commented.comments[0]);
  expectAmbiguous(exported, "both");

  // The explicit layout overrides detection in both directions.
  TempFolder folder;
  GaussianScene scene = randomScene(4, 3);
  fs::path glintPath = folder / "glint.ply", splatPath = folder / "splat.ply";
  writeGaussianPly(glintPath, scene);
  exportGaussianPly3dgs(splatPath, scene);
  // A file without Glint's export comment holds display-referred colour.
  GaussianPlyImport import;
  GaussianScene asSh = readGaussianPly(glintPath, PlyLayout::ThreeDgs, &import);
  EXPECT_NE(describeImport(import).find("materials from the file"), std::string::npos) << describeImport(import);
  EXPECT_FLOAT_EQ(asSh.diffuse[2].y, untonemapFilmic(float(0.5 + kShC0 * scene.diffuse[2].y)));
  EXPECT_EQ(asSh.roughness[2], scene.roughness[2]);  // materials are still read
  EXPECT_EQ(asSh.normal[2], scene.normal[2]);
  GaussianScene raw = readGaussianPly(splatPath, PlyLayout::Glint);
  EXPECT_FLOAT_EQ(raw.diffuse[2].y, float((tonemapFilmic(scene.diffuse[2].y) - 0.5) / kShC0));
  EXPECT_STREQ(plyLayoutName(PlyLayout::ThreeDgs), "3dgs");
}

// The property names of a 3DGS file of the given SH degree, in the order 3DGS writes them.
std::vector<std::string> threeDgsNames(int degree) {
  std::vector<std::string> names = {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"};
  for (int k = 0; k < 3 * shRestPerChannel(degree); ++k) names.push_back("f_rest_" + std::to_string(k));
  for (const char* name : {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"})
    names.push_back(name);
  return names;
}

// Reads of a tonemapped colour come back within float rounding, amplified where the
// curve is flat (bright colours).
void expectColourNear(float read, float original, const std::string& where) {
  EXPECT_NEAR(read, original, 1e-5 + 2e-4 * original) << where;
}

TEST(GaussianPly, ThreeDgsExportIsDisplayReferredStandardAndLoadsBack) {
  TempFolder folder;
  GaussianScene scene = randomScene(300, 11);
  fs::path path = folder / "splat.ply";
  exportGaussianPly3dgs(path, scene);

  PlyTable table = readPly(path);
  EXPECT_EQ(table.names, threeDgsNames(0));  // degree 0 by default: no f_rest
  for (PlyType type : table.types) EXPECT_EQ(type, PlyType::Float32);
  for (const char* name : {"nx", "ny", "nz"})
    for (float v : table.column(name)) ASSERT_EQ(v, 0.0f) << name;
  ASSERT_EQ(table.comments.size(), 1u);
  EXPECT_EQ(table.comments[0].rfind("Glint 3DGS export: colour display, exposure 1 ", 0), 0u) << table.comments[0];
  // f_dc is the SH DC coefficient of the display colour: 0.5 + C0 * f_dc = tonemapFilmic(c).
  for (size_t i = 0; i < scene.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      double shown = 0.5 + kShC0 * table.column("f_dc_" + std::to_string(k))[i];
      EXPECT_NEAR(shown, tonemapFilmic(scene.diffuse[i][k]), 1e-6) << i;
    }
  }

  GaussianPlyImport import;
  GaussianScene read = readGaussianPly(path, PlyLayout::Auto, &import);
  EXPECT_EQ(import.layout, PlyLayout::ThreeDgs);
  EXPECT_EQ(import.colour.colour, SplatColourSpace::Display);
  EXPECT_TRUE(import.normalsSet && import.roughnessSet && import.f0Set);
  EXPECT_EQ(import.gaussiansWithShRest, 0u);
  expectSameGeometry(scene, read);
  for (size_t i = 0; i < scene.size(); ++i) {
    // Glint reads its own export back through the inverse tonemap.
    for (int k = 0; k < 3; ++k) expectColourNear(read.diffuse[i][k], scene.diffuse[i][k], std::to_string(i));
    // 3DGS has no materials: imported ones are a rough dielectric.
    EXPECT_EQ(read.roughness[i], kImportedRoughness);
    EXPECT_EQ(read.f0[i], Rgb(kImportedF0));
    EXPECT_NEAR(length(read.normal[i]), 1.0f, 1e-5);
  }
}

TEST(GaussianPly, ExportExposureAndLinearColourAreRecordedAndInverted) {
  TempFolder folder;
  GaussianScene scene = randomScene(50, 12);
  fs::path bright = folder / "bright.ply", linear = folder / "linear.ply";
  ThreeDgsExportOptions options;
  options.colour.exposure = 2.5f;
  exportGaussianPly3dgs(bright, scene, options);
  PlyTable table = readPly(bright);
  for (size_t i = 0; i < scene.size(); ++i)
    EXPECT_NEAR(0.5 + kShC0 * table.column("f_dc_1")[i], tonemapFilmic(2.5f * scene.diffuse[i].y), 1e-6) << i;
  GaussianPlyImport import;
  GaussianScene read = readGaussianPly(bright, PlyLayout::Auto, &import);
  EXPECT_EQ(import.colour.exposure, 2.5f);
  EXPECT_NE(describeImport(import).find("exposure 2.5"), std::string::npos) << describeImport(import);
  for (size_t i = 0; i < scene.size(); ++i)
    for (int k = 0; k < 3; ++k) expectColourNear(read.diffuse[i][k], scene.diffuse[i][k], std::to_string(i));

  options.colour = {SplatColourSpace::Linear, 1.0f};
  exportGaussianPly3dgs(linear, scene, options);
  table = readPly(linear);
  EXPECT_NEAR(0.5 + kShC0 * table.column("f_dc_2")[7], scene.diffuse[7].z, 1e-6);
  read = readGaussianPly(linear, PlyLayout::Auto, &import);
  EXPECT_EQ(import.colour.colour, SplatColourSpace::Linear);
  for (size_t i = 0; i < scene.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(read.diffuse[i][k], scene.diffuse[i][k], 1e-6) << i;
}

TEST(GaussianPly, ShDegreeControlsTheRestCoefficientsAndTakesGivenValues) {
  TempFolder folder;
  GaussianScene scene = randomScene(6, 14);
  const int expectedCounts[] = {0, 9, 24, 45};
  for (int degree = 0; degree <= 3; ++degree) {
    fs::path path = folder / ("degree" + std::to_string(degree) + ".ply");
    ThreeDgsExportOptions options;
    options.shDegree = degree;
    exportGaussianPly3dgs(path, scene, options);
    PlyTable table = readPly(path);
    EXPECT_EQ(3 * shRestPerChannel(degree), expectedCounts[degree]);
    EXPECT_EQ(table.names, threeDgsNames(degree)) << degree;
    GaussianPlyImport import;
    readGaussianPly(path, PlyLayout::Auto, &import);
    EXPECT_EQ(import.shDegree, degree);
    EXPECT_EQ(import.gaussiansWithShRest, 0u);  // zeros: nothing dropped, no warning
    EXPECT_EQ(droppedShWarning(import, path.string()), "");
  }
  // Baked colours land in the 3DGS order: channel-major, f_rest_(3 c + k) is coefficient
  // k + 1 of channel c at degree 1; f_dc encodes the baked base as is.
  SplatColour baked;
  baked.shDegree = 1;
  baked.base.assign(scene.size(), Rgb(0.25f));
  baked.sh.resize(scene.size() * baked.restCount());
  for (size_t i = 0; i < baked.sh.size(); ++i) baked.sh[i] = Rgb(0.01f, 0.02f, 0.03f) * float(i + 1);
  ThreeDgsExportOptions options;
  options.shDegree = 1;
  options.baked = &baked;
  fs::path path = folder / "given.ply";
  exportGaussianPly3dgs(path, scene, options);
  PlyTable table = readPly(path);
  const size_t perChannel = baked.restCount();
  for (size_t i = 0; i < scene.size(); ++i) {
    EXPECT_FLOAT_EQ(table.column("f_dc_0")[i], float((0.25 - 0.5) / kShC0));
    for (int c = 0; c < 3; ++c)
      for (size_t k = 0; k < perChannel; ++k)
        EXPECT_EQ(table.column("f_rest_" + std::to_string(size_t(c) * perChannel + k))[i], baked.rest(i)[k][c])
            << i << " " << c << " " << k;
  }
  GaussianPlyImport import;
  readGaussianPly(path, PlyLayout::Auto, &import);
  EXPECT_EQ(import.gaussiansWithShRest, 6u);  // every Gaussian has a non-zero coefficient
  std::string warning = droppedShWarning(import, path.string());
  EXPECT_NE(warning.find(path.string()), std::string::npos) << warning;
  EXPECT_NE(warning.find("f_rest"), std::string::npos) << warning;
}

// A splat-transform -H 0 file: exactly the properties both layouts share, no comment.
PlyTable coreOnlyThreeDgsTable() {
  PlyTable table;
  table.add("x", {0.0f, 1.0f, -1.0f});
  table.add("y", {0.0f, 0.0f, 0.5f});
  table.add("z", {2.0f, 0.0f, 0.0f});
  table.add("f_dc_0", {-1.5f, 0.0f, 1.2f});
  table.add("f_dc_1", {0.3f, -0.6f, 0.9f});
  table.add("f_dc_2", {1.7f, 0.1f, -1.0f});
  table.add("opacity", {0.5f, 1.0f, -2.0f});
  table.add("scale_0", {-3.0f, -2.0f, -2.5f});
  table.add("scale_1", {-5.0f, -4.0f, -6.0f});  // the shortest axis of every Gaussian
  table.add("scale_2", {-3.0f, -2.0f, -2.5f});
  table.add("rot_0", {1.0f, 0.7f, 0.0f});
  table.add("rot_1", {0.0f, 0.7f, 0.0f});
  table.add("rot_2", {0.0f, 0.0f, 1.0f});
  table.add("rot_3", {0.0f, 0.0f, 0.0f});
  return table;
}

TEST(GaussianPly, DegreeZeroThreeDgsWithoutNormalsIsReadAs3dgsAndSaysSo) {
  TempFolder folder;
  PlyTable table = coreOnlyThreeDgsTable();
  fs::path path = folder / "h0.ply";
  writePly(path, table);
  GaussianPlyImport detected;
  readGaussianPly(path, PlyLayout::Auto, &detected);
  EXPECT_EQ(detected.layout, PlyLayout::ThreeDgs);
  EXPECT_NE(describeImport(detected).find("no Glint header or material properties, so read as a 3DGS file"),
            std::string::npos)
      << describeImport(detected);
  EXPECT_NE(describeImport(detected).find("--input-layout glint"), std::string::npos);

  // Its colours come back: Glint's filmic render of the read diffuse
  // shows the file's display colour, 0.5 + C0 f_dc (within the accuracy of
  // untonemapFilmic's published constants, far below an 8-bit level).
  GaussianScene scene = readGaussianPly(path);
  ASSERT_EQ(scene.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) {
      double shown = 0.5 + kShC0 * table.column("f_dc_" + std::to_string(k))[i];
      EXPECT_NEAR(tonemapFilmic(scene.diffuse[i][k]), std::clamp(shown, 0.0, 254.5 / 255.0), 5e-5) << i << k;
    }
  }
  EXPECT_GT(scene.diffuse[0].z, 1.0f);  // a bright colour, not the SH coefficient
  // The same file as ASCII reads the same.
  std::string text = "ply\nformat ascii 1.0\nelement vertex 3\n";
  for (const std::string& name : table.names) text += "property float " + name + "\n";
  text += "end_header\n";
  for (size_t i = 0; i < 3; ++i) {
    for (const auto& column : table.columns) text += std::to_string(column[i]) + " ";
    text += "\n";
  }
  fs::path ascii = folder / "h0_ascii.ply";
  test::writeBytes(ascii, text);
  GaussianScene fromAscii = readGaussianPly(ascii, PlyLayout::ThreeDgs);
  for (size_t i = 0; i < 3; ++i) EXPECT_EQ(fromAscii.diffuse[i], scene.diffuse[i]) << i;
}

TEST(GaussianPly, ImportedThreeDgsGetsRoughDielectricWithOutwardShortestAxisNormals) {
  TempFolder folder;
  PlyTable table = coreOnlyThreeDgsTable();
  for (int k = 0; k < 45; ++k) table.add("f_rest_" + std::to_string(k), {0.0f, k == 7 ? 0.25f : 0.0f, 0.0f});
  fs::path path = folder / "degree3.ply";
  writePly(path, table);
  GaussianPlyImport import;
  GaussianScene scene = readGaussianPly(path, PlyLayout::Auto, &import);
  EXPECT_EQ(import.layout, PlyLayout::ThreeDgs);
  EXPECT_EQ(import.shDegree, 3);
  EXPECT_EQ(import.gaussiansWithShRest, 1u);
  EXPECT_NE(droppedShWarning(import, path.string()).find("degree3.ply"), std::string::npos);
  EXPECT_NE(describeImport(import).find("roughness 0.9"), std::string::npos) << describeImport(import);

  const Vec3f centre = medianPosition(scene);
  EXPECT_EQ(centre, Vec3f(0.0f, 0.0f, 0.0f));
  for (size_t i = 0; i < scene.size(); ++i) {
    const Vec3f& n = scene.normal[i];
    EXPECT_NEAR(length(n), 1.0f, 1e-6) << i;
    // Along the shortest axis (scale_1 is the smallest: the local y axis) ...
    Vec3f axis = quatToRotation(scene.rotation[i]).column(1);
    EXPECT_NEAR(std::abs(dot(n, axis)), 1.0f, 1e-6) << i;
    // ... and away from the centre where the position says which way that is.
    EXPECT_GE(dot(n, scene.position[i] - centre), 0.0f) << i;
    EXPECT_EQ(scene.roughness[i], kImportedRoughness);
    EXPECT_EQ(scene.f0[i], Rgb(kImportedF0));
  }
  // Gaussian 0 at (0, 0, 2), unrotated: its local y axis is perpendicular to its offset.
  // Gaussian 1 at (1, 0, 0), rotated 90 degrees about x: local y is world z, perpendicular
  // to its offset too. Gaussian 2 at (-1, 0.5, 0), rotated 180 degrees about y: local y is
  // world y, flipped to face the offset's +y.
  EXPECT_NEAR(std::abs(scene.normal[1].z), 1.0f, 1e-6);
  EXPECT_NEAR(scene.normal[2].y, 1.0f, 1e-6);
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
  table.add("quality", {9.0f, 9.0f});  // unknown to both layouts: ignored
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

  fs::path ascii = folder / "ascii.ply";
  test::writeBytes(ascii,
                   "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                   "end_header\n0 0 0\n");
  expectErrorNaming([&] { readGaussianPly(ascii); }, ascii, {"not a Gaussian scene", "'f_dc_0'"});

  // Overwrite the opacity of vertex 3 (column 6 of 21 float32 columns) with a NaN.
  fs::path nan = folder / "nan.ply";
  writeGaussianPly(nan, scene);
  std::string bytes = test::readBytes(nan);
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
