// Generic PLY tables: typed round trips, skipping of lists and other elements, the ASCII and
// big-endian formats, and clear errors.
#include "io/ply.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

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


// A table with a column of every type, and awkward values.
PlyTable everyTypeTable() {
  PlyTable table;
  table.add("x", {1.5f, -2.25f, 1.0e30f});
  table.add("d", {0.1f, -1e-30f, 3.0f}, PlyType::Float64);
  table.add("c", {-128.0f, 0.0f, 127.0f}, PlyType::Int8);
  table.add("red", {0.0f, 128.0f, 255.0f}, PlyType::UInt8);
  table.add("s", {-32768.0f, -1.0f, 32767.0f}, PlyType::Int16);
  table.add("us", {0.0f, 1234.0f, 65535.0f}, PlyType::UInt16);
  table.add("i", {-100000.0f, 0.0f, 16777216.0f}, PlyType::Int32);
  table.add("ui", {0.0f, 7.0f, 4000000000.0f}, PlyType::UInt32);
  return table;
}

TEST(Ply, RoundTripKeepsEveryTypeAndValue) {
  TempFolder folder;
  PlyTable table = everyTypeTable();
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

// The header lines of everyTypeTable's vertex element, after a face element of one row.
std::string everyTypeHeader(const std::string& format) {
  std::string header = "ply\nformat " + format + " 1.0\ncomment written by ply_test\ncomment second comment\n" +
                       "element face 1\nproperty list uchar int vertex_indices\nelement vertex 3\n";
  PlyTable table = everyTypeTable();
  for (size_t c = 0; c < table.names.size(); ++c)
    header += std::string("property ") + plyTypeName(table.types[c]) + " " + table.names[c] + "\n";
  return header + "end_header\n";
}

// Appends a value in big-endian byte order.
template <typename T>
void putBigEndian(std::string& body, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  for (size_t k = sizeof(T); k-- > 0;) body.push_back(bytes[k]);
}

void expectSameTable(const PlyTable& read, const PlyTable& expected) {
  EXPECT_EQ(read.count, expected.count);
  EXPECT_EQ(read.names, expected.names);
  EXPECT_EQ(read.types, expected.types);
  EXPECT_EQ(read.columns, expected.columns);
  EXPECT_EQ(read.comments, expected.comments);
}

TEST(Ply, AsciiAndBigEndianGiveTheSameTableAsLittleEndian) {
  TempFolder folder;
  const PlyTable table = everyTypeTable();
  auto little = folder / "little.ply";
  writePly(little, table, {{"written by ply_test", "second comment"}});
  PlyTable expected = readPly(little);
  EXPECT_EQ(expected.comments, (std::vector<std::string>{"written by ply_test", "second comment"}));

  // Big-endian, with a face element (a list) to skip first.
  std::string body;
  putBigEndian(body, uint8_t(3));
  for (int32_t index : {0, 1, 2}) putBigEndian(body, index);
  for (size_t row = 0; row < 3; ++row) {
    putBigEndian(body, table.columns[0][row]);
    putBigEndian(body, double(table.columns[1][row]));
    putBigEndian(body, int8_t(table.columns[2][row]));
    putBigEndian(body, uint8_t(table.columns[3][row]));
    putBigEndian(body, int16_t(table.columns[4][row]));
    putBigEndian(body, uint16_t(table.columns[5][row]));
    putBigEndian(body, int32_t(table.columns[6][row]));
    putBigEndian(body, uint32_t(table.columns[7][row]));
  }
  auto big = folder / "big.ply";
  test::writeBytes(big, everyTypeHeader("binary_big_endian") + body);
  expectSameTable(readPly(big), expected);

  // ASCII: floats printed to round-trip, rows split over lines as writers do, a '+' sign.
  std::string text = "3 0 1 2\n";
  for (size_t row = 0; row < 3; ++row) {
    char line[256];
    std::snprintf(line, sizeof(line), "%.9g %.17g %d %d %d %d %d %.0f\n", double(table.columns[0][row]),
                  double(table.columns[1][row]), int(table.columns[2][row]), int(table.columns[3][row]),
                  int(table.columns[4][row]), int(table.columns[5][row]), int(table.columns[6][row]),
                  double(table.columns[7][row]));
    text += line;
  }
  text.replace(text.find("\n1.5 "), 5, "\n+1.5 ");
  auto ascii = folder / "ascii.ply";
  test::writeBytes(ascii, everyTypeHeader("ascii") + text);
  expectSameTable(readPly(ascii), expected);
  // The face element, read from each format.
  EXPECT_EQ(readPly(ascii, "face").count, 1u);
  EXPECT_EQ(readPly(big, "face").count, 1u);
}

TEST(Ply, AsciiKeepsEveryCheck) {
  TempFolder folder;
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty uchar red\nend_header\n";
  struct Case {
    const char* name;
    std::string text;
    std::vector<std::string> details;
  };
  for (const Case& c : {
           Case{"word.ply", header + "1 2\nabc 3\n", {"'x'", "vertex 1", "'abc'", "float"}},
           Case{"fraction.ply", header + "1 2.5\n0 0\n", {"'red'", "vertex 0", "'2.5'", "uchar"}},
           Case{"range.ply", header + "1 2\n0 256\n", {"'red'", "vertex 1", "'256'"}},
           Case{"nan.ply", header + "1 2\nnan 3\n", {"'x'", "vertex 1", "NaN"}},
           Case{"inf.ply", header + "-inf 2\n0 3\n", {"'x'", "vertex 0", "infinite"}},
           Case{"huge.ply", header + "1e300 2\n0 3\n", {"'x'", "vertex 0", "outside the float range"}},
           Case{"short.ply", header + "1 2\n3\n", {"vertex 1 ends after 1 values", "before property 'red'"}},
           // Two values more than the header declares: refused, not shifted into the next rows.
           Case{"long.ply", header + "1 2 7 8\n3 4\n", {"vertex 0 has 4 values", "declares 2"}},
           Case{"cut.ply", header + "1 2\n", {"truncated", "vertex 1"}},
           Case{"count.ply", "ply\nformat ascii 1.0\nelement vertex 1000000000000\nproperty float x\nend_header\n1\n",
                {"truncated", "1000000000000 vertex rows"}},
           Case{"list.ply",
                "ply\nformat ascii 1.0\nelement face 1\nproperty list char int v\nelement vertex 1\n"
                "property float x\nend_header\n-1 0\n5\n",
                {"'v'", "negative length"}},
           Case{"face.ply",
                "ply\nformat ascii 1.0\nelement face 2\nproperty list uchar int v\nelement vertex 1\n"
                "property float x\nend_header\n2 0 1\n3 0\n",
                {"element 'face' row 1", "ends inside list property 'v'"}},
       }) {
    auto path = folder / c.name;
    test::writeBytes(path, c.text);
    for (const std::string& detail : c.details) expectErrorNaming([&] { readPly(path); }, path, detail);
  }
  // Elements without properties hold nothing, however many rows they declare.
  auto empty = folder / "empty_rows.ply";
  test::writeBytes(empty, "ply\nformat ascii 1.0\nelement marker 1000000000000\nelement vertex 1000000000000\n"
                          "end_header\n");
  EXPECT_EQ(readPly(empty).count, 1000000000000u);
  // Lists inside the wanted element are skipped, as in binary files.
  auto lists = folder / "lists.ply";
  test::writeBytes(lists, "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty list uchar float extra\n"
                          "property ushort z\nend_header\n1.5 2 9 9 7\n-2.5 0 8\n");
  PlyTable table = readPly(lists);
  EXPECT_EQ(table.names, (std::vector<std::string>{"x", "z"}));
  EXPECT_EQ(table.column("x"), (std::vector<float>{1.5f, -2.5f}));
  EXPECT_EQ(table.column("z"), (std::vector<float>{7.0f, 8.0f}));
}

TEST(Ply, BigEndianTruncationIsRefused) {
  TempFolder folder;
  auto big = folder / "big_cut.ply";
  std::string body;
  putBigEndian(body, 1.0f);
  test::writeBytes(big, "ply\nformat binary_big_endian 1.0\nelement vertex 2\nproperty float x\nend_header\n" + body);
  expectErrorNaming([&] { readPly(big); }, big, {"truncated: 2 vertex rows of 4 bytes declared, but only 4 bytes of data follow"});
  // 2^62 rows of 4 bytes overflow 64 bits: the message gives the count as declared.
  auto huge = folder / "huge_count.ply";
  test::writeBytes(huge, "ply\nformat binary_big_endian 1.0\nelement vertex 4611686018427387904\nproperty float x\n"
                         "end_header\n" + body);
  expectErrorNaming([&] { readPly(huge); }, huge, {"4611686018427387904 vertex rows of 4 bytes declared"});
  auto other = folder / "other_format.ply";
  test::writeBytes(other, "ply\nformat binary_middle_endian 1.0\nelement vertex 0\nend_header\n");
  expectErrorNaming([&] { readPly(other); }, other, {"unsupported PLY format"});
}

TEST(Ply, RejectsTruncatedData) {
  TempFolder folder;
  auto path = folder / "cut.ply";
  RawPly ply;
  ply.header = "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty uchar red\nend_header\n";
  for (int i = 0; i < 3; ++i) ply.put(float(i)).put(uint8_t(i));
  ply.put(3.0f);  // the last vertex lacks its colour byte
  ply.save(path);
  expectErrorNaming([&] { readPly(path); }, path, {"truncated: 4 vertex rows of 5 bytes declared, but only 19 bytes of data follow"});

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
  expectErrorNaming([&] { readPly(path); }, path, {"truncated: 1 vertex rows of 4 bytes declared, but only 0 bytes of data follow"});
}

TEST(Ply, TypeNamesAndSizes) {
  EXPECT_STREQ(plyTypeName(PlyType::UInt8), "uchar");
  EXPECT_STREQ(plyTypeName(PlyType::Float64), "double");
  EXPECT_EQ(plyTypeSize(PlyType::Int16), 2u);
  EXPECT_EQ(plyTypeSize(PlyType::Float64), 8u);
}

}  // namespace
}  // namespace glint
