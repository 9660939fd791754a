// Point clouds in PLY: round trips, colour encodings other tools use, and missing coordinates.
#include "io/point_cloud.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/ply.h"
#include "math/rng.h"
#include "temp_folder.h"

namespace glint {
namespace {

using test::TempFolder;

TEST(PointCloud, RoundTripPositionsExactColoursToEightBits) {
  TempFolder folder;
  PointCloud cloud;
  Rng rng(11);
  for (int i = 0; i < 500; ++i) {
    cloud.positions.push_back(Vec3f(rng.uniform() * 20 - 10, rng.uniform() * 20 - 10, rng.uniform() * 20 - 10));
    cloud.colors.push_back(Rgb(rng.uniform(), rng.uniform(), rng.uniform()));
  }
  cloud.colors[0] = Rgb(0.0f, 1.0f, 0.5f);
  auto path = folder / "cloud.ply";
  writePointCloud(path, cloud);

  // The file has the layout docs/data-format.md promises: x y z float, red green blue uchar.
  PlyTable table = readPly(path);
  EXPECT_EQ(table.names, (std::vector<std::string>{"x", "y", "z", "red", "green", "blue"}));
  EXPECT_EQ(table.type("x"), PlyType::Float32);
  EXPECT_EQ(table.type("red"), PlyType::UInt8);

  PointCloud read = readPointCloud(path);
  ASSERT_EQ(read.positions.size(), cloud.positions.size());
  ASSERT_EQ(read.colors.size(), cloud.colors.size());
  for (size_t i = 0; i < cloud.positions.size(); ++i) {
    EXPECT_EQ(read.positions[i], cloud.positions[i]);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(read.colors[i][c], cloud.colors[i][c], 0.5f / 255.0f + 1e-6f);
  }
  EXPECT_EQ(read.colors[0], Rgb(0.0f, 1.0f, 128.0f / 255.0f));
}

TEST(PointCloud, WithoutColoursStaysWithoutColours) {
  TempFolder folder;
  PointCloud cloud;
  cloud.positions = {Vec3f(1, 2, 3), Vec3f(4, 5, 6)};
  auto path = folder / "plain.ply";
  writePointCloud(path, cloud);
  EXPECT_FALSE(readPly(path).has("red"));
  PointCloud read = readPointCloud(path);
  EXPECT_EQ(read.positions, cloud.positions);
  EXPECT_TRUE(read.colors.empty());
}

TEST(PointCloud, FloatColoursAndExtraPropertiesFromOtherTools) {
  TempFolder folder;
  PlyTable table;
  table.add("nx", {0.0f, 1.0f});
  table.add("x", {1.0f, 2.0f});
  table.add("y", {3.0f, 4.0f}, PlyType::Float64);
  table.add("z", {5.0f, 6.0f});
  table.add("red", {0.25f, 2.0f});  // float colours are used as they are
  table.add("green", {0.5f, 0.0f});
  table.add("blue", {1000.0f, 65535.0f}, PlyType::UInt16);  // ushort scaled by 1/65535
  auto path = folder / "float_colour.ply";
  writePly(path, table);
  PointCloud read = readPointCloud(path);
  ASSERT_EQ(read.positions.size(), 2u);
  EXPECT_EQ(read.positions[1], Vec3f(2, 4, 6));
  EXPECT_EQ(read.colors[0].x, 0.25f);
  EXPECT_EQ(read.colors[1].x, 2.0f);
  EXPECT_FLOAT_EQ(read.colors[0].z, 1000.0f / 65535.0f);
  EXPECT_EQ(read.colors[1].z, 1.0f);
}

TEST(PointCloud, ErrorsNameTheFile) {
  TempFolder folder;
  PlyTable noZ;
  noZ.add("x", {1.0f});
  noZ.add("y", {1.0f});
  auto path = folder / "no_z.ply";
  writePly(path, noZ);
  try {
    readPointCloud(path);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no_z.ply"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'z'"), std::string::npos) << e.what();
  }

  PlyTable partial = noZ;
  partial.add("z", {1.0f});
  partial.add("red", {1.0f}, PlyType::UInt8);
  auto partialPath = folder / "red_only.ply";
  writePly(partialPath, partial);
  EXPECT_THROW(readPointCloud(partialPath), Error);

  PlyTable signedColour = partial;
  signedColour.add("green", {1.0f}, PlyType::Int8);
  signedColour.add("blue", {1.0f}, PlyType::UInt8);
  auto signedPath = folder / "signed_colour.ply";
  writePly(signedPath, signedColour);
  EXPECT_THROW(readPointCloud(signedPath), Error);

  EXPECT_THROW(readPointCloud(folder / "missing.ply"), Error);
}

}  // namespace
}  // namespace glint
