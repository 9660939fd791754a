// Compressed PLY files Glint writes, decoded by a minimal reader written here from the
// format's description (text header; chunk bounds; packed uint32 per Gaussian; 8-bit SH),
// and compared with the scene.
#include "scene/compressed_ply_writer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/random_gaussians.h"
#include "common/splat_check.h"
#include "core/error.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

struct CompressedPly {
  std::vector<std::string> headerLines;
  size_t chunks = 0, vertices = 0, shColumns = 0;
  std::vector<std::array<float, 18>> chunk;
  test::DecodedSplats splats;
  float positionRange = 0, logScaleRange = 0, colourRange = 0;  // the widest chunk's
};

double unorm(uint32_t value, int bits) { return double(value & ((1u << bits) - 1)) / double((1u << bits) - 1); }
double lerp(double a, double b, double t) { return a + (b - a) * t; }

CompressedPly decodeCompressedPly(const std::filesystem::path& path) {
  const std::string bytes = test::readBytes(path);
  CompressedPly f;
  size_t end = bytes.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  std::istringstream header(bytes.substr(0, end));
  for (std::string line; std::getline(header, line);) {
    f.headerLines.push_back(line);
    std::istringstream words(line);
    std::string word, name;
    size_t count = 0;
    words >> word;
    if (word == "element" && words >> name >> count) {
      if (name == "chunk") f.chunks = count;
      if (name == "vertex") f.vertices = count;
    }
    if (line.rfind("property uchar f_rest_", 0) == 0) ++f.shColumns;
  }
  size_t at = end + std::strlen("end_header\n");
  auto f32 = [&]() {
    float v = 0;
    if (at + 4 <= bytes.size()) std::memcpy(&v, bytes.data() + at, 4);
    at += 4;
    return v;
  };
  auto u32 = [&]() {
    uint32_t v = 0;
    if (at + 4 <= bytes.size()) std::memcpy(&v, bytes.data() + at, 4);  // little-endian host
    at += 4;
    return v;
  };
  for (size_t c = 0; c < f.chunks; ++c) {
    std::array<float, 18> row;
    for (float& v : row) v = f32();
    f.chunk.push_back(row);
    for (int a = 0; a < 3; ++a) {
      f.positionRange = std::max(f.positionRange, row[size_t(3 + a)] - row[size_t(a)]);
      f.logScaleRange = std::max(f.logScaleRange, row[size_t(9 + a)] - row[size_t(6 + a)]);
      f.colourRange = std::max(f.colourRange, row[size_t(15 + a)] - row[size_t(12 + a)]);
    }
  }
  test::DecodedSplats& s = f.splats;
  for (size_t i = 0; i < f.vertices; ++i) {
    const std::array<float, 18>& b = f.chunk[i / 256];
    const uint32_t position = u32(), rotation = u32(), scale = u32(), colour = u32();
    auto unpack111011 = [&](uint32_t v, size_t lo, size_t hi) {
      return Vec3f(float(lerp(b[lo], b[hi], unorm(v >> 21, 11))), float(lerp(b[lo + 1], b[hi + 1], unorm(v >> 11, 10))),
                   float(lerp(b[lo + 2], b[hi + 2], unorm(v, 11))));
    };
    s.position.push_back(unpack111011(position, 0, 3));
    s.logScale.push_back(unpack111011(scale, 6, 9));
    float q[4], sumSquares = 0;
    const int largest = int(rotation >> 30);
    int shift = 20;
    for (int c = 0; c < 4; ++c) {
      if (c == largest) continue;
      q[c] = float((unorm(rotation >> shift, 10) - 0.5) * std::sqrt(2.0));
      shift -= 10;
      sumSquares += q[c] * q[c];
    }
    q[largest] = std::sqrt(std::max(0.0f, 1.0f - sumSquares));
    s.rotation.push_back(Quatf{q[0], q[1], q[2], q[3]});  // w x y z
    s.colour.push_back(Rgb(float(lerp(b[12], b[15], unorm(colour >> 24, 8))),
                           float(lerp(b[13], b[16], unorm(colour >> 16, 8))),
                           float(lerp(b[14], b[17], unorm(colour >> 8, 8)))));
    s.opacity.push_back(float(unorm(colour, 8)));
  }
  // f_rest_j, channel-major: j = channel x rest + k.
  const size_t rest = f.shColumns / 3;
  s.shDegree = rest == 0 ? 0 : rest == 3 ? 1 : rest == 8 ? 2 : 3;
  s.sh.assign(f.vertices * rest, Rgb(0.0f));
  for (size_t i = 0; i < f.vertices; ++i) {
    for (size_t j = 0; j < f.shColumns; ++j) {
      const int byte = at < bytes.size() ? uint8_t(bytes[at]) : 0;
      ++at;
      s.sh[i * rest + j % rest][int(j / rest)] = float(((byte + 0.5) / 256.0 - 0.5) * 8.0);
    }
  }
  EXPECT_EQ(at, bytes.size()) << "file length does not match its header";
  return f;
}

TEST(CompressedPlyWriter, HeaderHasTheElementsReadersLookFor) {
  test::TempFolder folder;
  GaussianScene scene = randomScene(600, 1);  // 3 chunks, the last one partial
  writeCompressedPly(folder / "a.compressed.ply", scene, test::randomShColour(scene, 1, 3.9f, 2));
  CompressedPly f = decodeCompressedPly(folder / "a.compressed.ply");
  EXPECT_EQ(f.chunks, 3u);
  EXPECT_EQ(f.vertices, 600u);
  EXPECT_EQ(f.shColumns, 9u);
  const std::string text = [&] {
    std::string all;
    for (const std::string& line : f.headerLines) all += line + "\n";
    return all;
  }();
  EXPECT_EQ(text.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  for (const char* property : {"property float min_x", "property float max_scale_z", "property float max_b",
                               "property uint packed_position", "property uint packed_color", "element sh 600",
                               "property uchar f_rest_8"})
    EXPECT_NE(text.find(property), std::string::npos) << property;
}

TEST(CompressedPlyWriter, DecodesToTheSceneWithinTheQuantisation) {
  test::TempFolder folder;
  GaussianScene scene = randomScene(700, 3);
  for (int degree = 0; degree <= 3; ++degree) {
    SplatColour colour = test::randomShColour(scene, degree, 3.9f, 20 + uint64_t(degree));
    writeCompressedPly(folder / "a.compressed.ply", scene, colour);
    CompressedPly f = decodeCompressedPly(folder / "a.compressed.ply");
    const test::SplatTolerance tolerance = test::compressedPlyTolerance(f.positionRange, f.logScaleRange, f.colourRange);
    EXPECT_EQ(test::compareSplats(test::expectedSplats(scene, colour, compressedPlyOrder(scene)), f.splats, tolerance),
              "")
        << "degree " << degree;
  }
}

TEST(CompressedPlyWriter, ChunksCoverSmallBoxes) {
  // Morton order makes each chunk of 256 a small part of the scene, which is what keeps
  // 11-bit positions fine. 16 chunks of a Z-order curve halve z twice and x and y once, so
  // a chunk's longest side is about 1 of the [-1, 1] box's 2 (scene order: all of 2).
  test::TempFolder folder;
  GaussianScene scene = randomScene(256 * 16, 4);
  writeCompressedPly(folder / "a.compressed.ply", scene, displayColour(scene));
  CompressedPly f = decodeCompressedPly(folder / "a.compressed.ply");
  double meanLongestSide = 0;
  for (const std::array<float, 18>& row : f.chunk)
    meanLongestSide += std::max({row[3] - row[0], row[4] - row[1], row[5] - row[2]}) / double(f.chunks);
  EXPECT_LT(meanLongestSide, 1.3);
  std::vector<uint32_t> order = compressedPlyOrder(scene);
  std::sort(order.begin(), order.end());
  for (size_t i = 0; i < order.size(); ++i) ASSERT_EQ(order[i], i) << "not a permutation";
}

TEST(CompressedPlyWriter, ToleranceIsTightEnoughToCatchAWrongBitField) {
  test::TempFolder folder;
  GaussianScene scene = randomScene(300, 5);
  SplatColour colour = displayColour(scene);
  writeCompressedPly(folder / "a.compressed.ply", scene, colour);
  CompressedPly f = decodeCompressedPly(folder / "a.compressed.ply");
  const test::SplatTolerance tolerance = test::compressedPlyTolerance(f.positionRange, f.logScaleRange, f.colourRange);
  test::DecodedSplats swapped = f.splats;
  for (Quatf& q : swapped.rotation) std::swap(q.x, q.y);
  EXPECT_NE(test::compareSplats(test::expectedSplats(scene, colour, compressedPlyOrder(scene)), swapped, tolerance), "");
}

TEST(CompressedPlyWriter, RefusesNaN) {
  test::TempFolder folder;
  GaussianScene scene = randomScene(3, 6);
  scene.logScale[1].y = NAN;
  EXPECT_THROW(writeCompressedPly(folder / "a.compressed.ply", scene, displayColour(scene)), Error);
  EXPECT_FALSE(std::filesystem::exists(folder / "a.compressed.ply"));
}

}  // namespace
}  // namespace glint
