// Generic PLY tables: typed round trips, skipping of lists and other elements, and clear errors.
#include "io/ply.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "common/expect_error.h"
#include "core/error.h"
#include "temp_folder.h"

namespace glint {
namespace {

using test::expectErrorNaming;

using test::TempFolder;

// A PLY file assembled by hand: header text plus little-endian values appended one by one.
struct RawPly {
  std::string header;
  std::string body;

  template <typename T>
  RawPly& put(T value) {
    body.append(reinterpret_cast<const char*>(&value), sizeof(T));
    return *this;
  }
  void save(const std::filesystem::path& path) const { test::writeBytes(path, header + body); }
};


TEST(Ply, RoundTripKeepsEveryTypeAndValue) {
  TempFolder folder;
  PlyTable table;
  table.add("x", {1.5f, -2.25f, 1.0e30f});
  table.add("d", {0.1f, -1e-30f, 3.0f}, PlyType::Float64);
  table.add("c", {-128.0f, 0.0f, 127.0f}, PlyType::Int8);
  table.add("red", {0.0f, 128.0f, 255.0f}, PlyType::UInt8);
  table.add("s", {-32768.0f, -1.0f, 32767.0f}, PlyType::Int16);
  table.add("us", {0.0f, 1234.0f, 65535.0f}, PlyType::UInt16);
  table.add("i", {-100000.0f, 0.0f, 16777216.0f}, PlyType::Int32);
  table.add("ui", {0.0f, 7.0f, 4000000000.0f}, PlyType::UInt32);
  auto path = folder / "table.ply";
  writePly(path, table, {{"written by ply_test", "second comment"}});

  PlyTable read = readPly(path);
  EXPECT_EQ(read.element, "vertex");
  EXPECT_EQ(read.count, 3u);
  EXPECT_EQ(read.names, table.names);
  EXPECT_EQ(read.types, table.types);
  EXPECT_EQ(read.columns, table.columns);
  EXPECT_EQ(read.source, path.string());
}

TEST(Ply, IntegerColumnsAreRoundedAndClampedOnWrite) {
  TempFolder folder;
  PlyTable table;
  table.add("red", {12.4f, 12.6f, -3.0f, 300.0f}, PlyType::UInt8);
  table.add("c", {-200.0f, 200.0f, -0.4f, 1.5f}, PlyType::Int8);
  auto path = folder / "clamp.ply";
  writePly(path, table);
  PlyTable read = readPly(path);
  EXPECT_EQ(read.column("red"), (std::vector<float>{12.0f, 13.0f, 0.0f, 255.0f}));
  EXPECT_EQ(read.column("c"), (std::vector<float>{-128.0f, 127.0f, 0.0f, 2.0f}));
}

TEST(Ply, LargeTableCrossesBufferBoundaries) {
  TempFolder folder;
  const size_t n = 150000;  // 150k rows of 9 bytes: several 1 MiB read and write blocks
  std::vector<float> x(n), y(n), red(n);
  for (size_t i = 0; i < n; ++i) {
    x[i] = float(i) * 0.5f;
    y[i] = -float(i);
    red[i] = float(i % 256);
  }
  PlyTable table;
  table.add("x", x);
  table.add("red", red, PlyType::UInt8);
  table.add("y", y);
  auto path = folder / "large.ply";
  writePly(path, table);
  PlyTable read = readPly(path);
  EXPECT_EQ(read.column("x"), x);
  EXPECT_EQ(read.column("y"), y);
  EXPECT_EQ(read.column("red"), red);
}

TEST(Ply, LookupByNameAndMissingPropertyError) {
  TempFolder folder;
  auto path = folder / "lookup.ply";
  RawPly ply;
  ply.header =
      "ply\nformat binary_little_endian 1.0\ncomment made by hand\nobj_info anything\n"
      "element vertex 2\nproperty float32 y\nproperty uint8 mystery\nproperty float64 x\nend_header\n";
  ply.put(1.0f).put(uint8_t(9)).put(2.0).put(3.0f).put(uint8_t(10)).put(4.0);
  ply.save(path);
  PlyTable table = readPly(path);
  EXPECT_TRUE(table.has("mystery"));  // unknown properties are kept for whoever wants them
  EXPECT_FALSE(table.has("z"));
  EXPECT_EQ(table.find("x"), 2);
  EXPECT_EQ(table.column("x"), (std::vector<float>{2.0f, 4.0f}));
  EXPECT_EQ(table.column("y"), (std::vector<float>{1.0f, 3.0f}));
  EXPECT_EQ(table.type("mystery"), PlyType::UInt8);
  EXPECT_EQ(table.type("x"), PlyType::Float64);
  expectErrorNaming([&] { table.column("opacity"); }, path, {"opacity"});
  expectErrorNaming([&] { table.type("opacity"); }, path, {"opacity"});
}

TEST(Ply, SkipsListsAndOtherElements) {
  TempFolder folder;
  auto path = folder / "mesh.ply";
  RawPly ply;
  ply.header =
      "ply\r\nformat binary_little_endian 1.0\r\n"
      "element camera 1\r\nproperty double fov\r\nproperty int id\r\n"
      "element edge 2\r\nproperty list uchar int ends\r\nproperty short weight\r\n"
      "element vertex 2\r\nproperty float x\r\nproperty list ushort float extra\r\nproperty ushort z\r\n"
      "element face 1\r\nproperty list uchar uint vertex_indices\r\n"
      "end_header\r\n";
  ply.put(0.7).put(int32_t(3));                                                    // camera
  ply.put(uint8_t(2)).put(int32_t(0)).put(int32_t(1)).put(int16_t(5));             // edge 0
  ply.put(uint8_t(0)).put(int16_t(6));                                             // edge 1
  ply.put(1.5f).put(uint16_t(2)).put(9.0f).put(9.0f).put(uint16_t(7));             // vertex 0
  ply.put(-2.5f).put(uint16_t(0)).put(uint16_t(8));                                // vertex 1
  ply.put(uint8_t(3)).put(uint32_t(0)).put(uint32_t(1)).put(uint32_t(1));          // face
  ply.save(path);

  PlyTable vertices = readPly(path);
  EXPECT_EQ(vertices.names, (std::vector<std::string>{"x", "z"}));
  EXPECT_EQ(vertices.column("x"), (std::vector<float>{1.5f, -2.5f}));
  EXPECT_EQ(vertices.column("z"), (std::vector<float>{7.0f, 8.0f}));

  PlyTable edges = readPly(path, "edge");
  EXPECT_EQ(edges.element, "edge");
  EXPECT_EQ(edges.column("weight"), (std::vector<float>{5.0f, 6.0f}));

  PlyTable camera = readPly(path, "camera");
  EXPECT_FLOAT_EQ(camera.column("fov")[0], 0.7f);

  expectErrorNaming([&] { readPly(path, "normals"); }, path, {"no element 'normals'"});
}

TEST(Ply, RejectsAsciiAndBigEndian) {
  TempFolder folder;
  auto ascii = folder / "ascii.ply";
  test::writeBytes(ascii, "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1.0\n");
  expectErrorNaming([&] { readPly(ascii); }, ascii, {"ASCII", "format ascii", "binary_little_endian"});

  auto big = folder / "big.ply";
  RawPly ply;
  ply.header = "ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty float x\nend_header\n";
  ply.put(1.0f).save(big);
  expectErrorNaming([&] { readPly(big); }, big, {"big-endian", "format binary_big_endian"});
}

TEST(Ply, RejectsTruncatedData) {
  TempFolder folder;
  auto path = folder / "cut.ply";
  RawPly ply;
  ply.header = "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty uchar red\nend_header\n";
  for (int i = 0; i < 3; ++i) ply.put(float(i)).put(uint8_t(i));
  ply.put(3.0f);  // the last vertex lacks its colour byte
  ply.save(path);
  expectErrorNaming([&] { readPly(path); }, path, {"truncated: expected 20 bytes of vertex data, found 19"});

  // Truncated inside an element with lists, and inside an earlier element.
  auto listCut = folder / "list_cut.ply";
  RawPly lists;
  lists.header = "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty list uchar float v\nend_header\n";
  lists.put(uint8_t(1)).put(1.0f).put(uint8_t(5)).put(1.0f);
  lists.save(listCut);
  expectErrorNaming([&] { readPly(listCut); }, listCut, {"truncated", "vertex 1"});

  auto earlier = folder / "earlier_cut.ply";
  RawPly before;
  before.header =
      "ply\nformat binary_little_endian 1.0\nelement face 3\nproperty int a\nelement vertex 1\nproperty float x\nend_header\n";
  before.put(int32_t(1)).save(earlier);
  expectErrorNaming([&] { readPly(earlier); }, earlier, {"truncated", "face"});
}

TEST(Ply, RejectsNonFiniteValuesNamingPropertyAndVertex) {
  TempFolder folder;
  const char* header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty double opacity\nend_header\n";
  struct Case {
    const char* name;
    double bad;
    const char* what;
  };
  for (const Case& c : {Case{"nan.ply", std::nan(""), "NaN"}, Case{"inf.ply", -INFINITY, "infinite"},
                        Case{"huge.ply", 1e300, "outside the float range"}}) {
    auto path = folder / c.name;
    RawPly ply;
    ply.header = header;
    ply.put(0.0f).put(0.5).put(1.0f).put(0.5).put(2.0f).put(c.bad);
    ply.save(path);
    expectErrorNaming([&] { readPly(path); }, path, {"'opacity'", "vertex 2", c.what});
  }
}

TEST(Ply, RejectsMalformedHeaders) {
  TempFolder folder;
  struct Case {
    const char* name;
    std::string text;
    const char* detail;
  };
  const std::string start = "ply\nformat binary_little_endian 1.0\n";
  for (const Case& c : {
           Case{"magic.ply", "PLY\nformat binary_little_endian 1.0\nend_header\n", "not a PLY file"},
           Case{"noend.ply", start + "element vertex 1\nproperty float x\n", "end_header"},
           Case{"type.ply", start + "element vertex 1\nproperty half x\nend_header\n", "'half'"},
           Case{"count.ply", start + "element vertex -1\nproperty float x\nend_header\n", "malformed element"},
           Case{"orphan.ply", start + "property float x\nend_header\n", "before any element"},
           Case{"dup.ply", start + "element vertex 0\nproperty float x\nproperty float x\nend_header\n", "duplicate"},
           Case{"version.ply", "ply\nformat binary_little_endian 2.0\nend_header\n", "unsupported PLY format"},
           Case{"noformat.ply", "ply\nelement vertex 0\nend_header\n", "no format"},
       }) {
    auto path = folder / c.name;
    test::writeBytes(path, c.text);
    expectErrorNaming([&] { readPly(path); }, path, {c.detail});
  }
  expectErrorNaming([&] { readPly(folder / "missing.ply"); }, folder / "missing.ply", {"not found"});
}

// Issue 19: a binary file with a PLY magic line had its bytes echoed raw to the terminal.
TEST(Ply, BinaryHeaderBytesAreEscapedInErrors) {
  TempFolder folder;
  auto path = folder / "binary.ply";
  const std::string header = "ply\nformat binary_little_endian 1.0\n";
  test::writeBytes(path, header + std::string("\x1b[2J\x89\x01\x00junk\nend_header\n", 23));
  try {
    readPly(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const Error& e) {
    std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find("unknown PLY header keyword '\\x1B[2J\\x89\\x01\\x00junk' (header line 3"),
              std::string::npos)
        << message;
    for (char c : message) EXPECT_TRUE(c >= 0x20 && c < 0x7F) << "unescaped byte " << int(c) << " in " << message;
  }
}

TEST(Ply, EmptyElementIsValid) {
  TempFolder folder;
  PlyTable table;
  table.add("x", {});
  auto path = folder / "empty.ply";
  writePly(path, table);
  PlyTable read = readPly(path);
  EXPECT_EQ(read.count, 0u);
  EXPECT_TRUE(read.has("x"));
  EXPECT_TRUE(read.column("x").empty());
}

TEST(Ply, WriteRefusesNonFiniteValuesAndLeavesNoFile) {
  TempFolder folder;
  PlyTable table;
  table.add("x", {0.0f, 1.0f});
  table.add("scale_0", {0.0f, std::numeric_limits<float>::quiet_NaN()});
  auto path = folder / "bad.ply";
  expectErrorNaming([&] { writePly(path, table); }, path, {"'scale_0'", "vertex 1", "NaN"});
  EXPECT_TRUE(std::filesystem::is_empty(folder.path()));
}

TEST(Ply, HeaderWithoutFinalNewline) {
  TempFolder folder;
  auto path = folder / "no_newline.ply";
  test::writeBytes(path, "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\nend_header");
  EXPECT_EQ(readPly(path).count, 0u);
  test::writeBytes(path, "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nend_header");
  expectErrorNaming([&] { readPly(path); }, path, {"truncated: expected 4 bytes of vertex data, found 0"});
}

TEST(Ply, TypeNamesAndSizes) {
  EXPECT_STREQ(plyTypeName(PlyType::UInt8), "uchar");
  EXPECT_STREQ(plyTypeName(PlyType::Float64), "double");
  EXPECT_EQ(plyTypeSize(PlyType::Int16), 2u);
  EXPECT_EQ(plyTypeSize(PlyType::Float64), 8u);
}

}  // namespace
}  // namespace glint
