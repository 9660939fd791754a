// .spz files Glint writes, decoded by a minimal reader written here from the format's
// description (gunzip, 16-byte header, attribute arrays), and compared with the scene.
#include "scene/spz_writer.h"

#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "common/random_gaussians.h"
#include "common/splat_check.h"
#include "core/error.h"
#include "io/temp_folder.h"
#include "math/spherical_harmonics.h"
#include "scene/gaussian_ply.h"

namespace glint {
namespace {

struct SpzFile {
  uint32_t magic = 0, version = 0, count = 0;
  int shDegree = 0, fractionalBits = 0, flags = 0, reserved = 0;
  test::DecodedSplats splats;
};

std::string gunzip(const std::string& compressed) {
  z_stream stream{};
  EXPECT_EQ(inflateInit2(&stream, 15 + 16), Z_OK);
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  stream.avail_in = uInt(compressed.size());
  std::string out;
  char buffer[4096];
  int status = Z_OK;
  while (status == Z_OK) {
    stream.next_out = reinterpret_cast<Bytef*>(buffer);
    stream.avail_out = sizeof(buffer);
    status = inflate(&stream, Z_NO_FLUSH);
    out.append(buffer, sizeof(buffer) - stream.avail_out);
  }
  EXPECT_EQ(status, Z_STREAM_END) << "not a complete gzip stream";
  inflateEnd(&stream);
  return out;
}

// Decodes as the format describes it: little-endian header; positions as 24-bit signed
// fixed point; alphas as sigmoid x 255; colours as f_dc x 0.15 x 255 + 127.5; scales as
// (log + 10) x 16; rotations as smallest-three (x y z w, 2 + 3 x 10 bits); SH as
// (byte - 128) / 128, coefficient-major, channel-minor. The axes are y up, z back: turned
// back by (x, y, z) -> (x, -y, -z) to compare with Glint's.
SpzFile decodeSpz(const std::filesystem::path& path) {
  const std::string bytes = gunzip(test::readBytes(path));
  size_t at = 0;
  auto u8 = [&]() { return at < bytes.size() ? int(uint8_t(bytes[at++])) : (ADD_FAILURE() << "truncated", 0); };
  auto u32 = [&]() {
    uint32_t v = 0;
    for (int b = 0; b < 4; ++b) v |= uint32_t(u8()) << (8 * b);
    return v;
  };
  SpzFile f;
  f.magic = u32();
  f.version = u32();
  f.count = u32();
  f.shDegree = u8();
  f.fractionalBits = u8();
  f.flags = u8();
  f.reserved = u8();
  test::DecodedSplats& s = f.splats;
  s.shDegree = f.shDegree;
  const size_t n = f.count;
  s.position.resize(n);
  s.logScale.resize(n);
  s.rotation.resize(n);
  s.opacity.resize(n);
  s.colour.resize(n);
  const float flip[3] = {1, -1, -1};
  for (size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      int32_t fixed = u8();
      fixed |= u8() << 8;
      fixed |= u8() << 16;
      if (fixed & 0x800000) fixed -= 1 << 24;
      s.position[i][a] = flip[a] * float(fixed) / float(1 << f.fractionalBits);
    }
  }
  for (size_t i = 0; i < n; ++i) s.opacity[i] = float(u8()) / 255.0f;
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) s.colour[i][c] = float(0.5 + 0.28209479177387814 * ((u8() / 255.0 - 0.5) / 0.15));
  for (size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) s.logScale[i][a] = float(u8()) / 16.0f - 10.0f;
  for (size_t i = 0; i < n; ++i) {
    const uint32_t packed = u32();
    const int largest = int(packed >> 30);
    float q[4];
    float sumSquares = 0;
    int shift = 20;
    for (int c = 0; c < 4; ++c) {
      if (c == largest) continue;
      const uint32_t field = (packed >> shift) & 0x3ff;
      shift -= 10;
      q[c] = float(field & 0x1ff) / 511.0f * std::sqrt(0.5f) * ((field & 0x200) ? -1.0f : 1.0f);
      sumSquares += q[c] * q[c];
    }
    q[largest] = std::sqrt(std::max(0.0f, 1.0f - sumSquares));
    s.rotation[i] = Quatf{q[3], q[0], -q[1], -q[2]};  // x y z w, turned back to PLY axes
  }
  const int rest = shCoefficientCount(f.shDegree) - 1;
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < rest; ++k) {
      Rgb coefficient;
      for (int c = 0; c < 3; ++c) coefficient[c] = float(kShSignUnderTurnAboutX[size_t(k + 1)]) * (u8() - 128) / 128.0f;
      s.sh.push_back(coefficient);
    }
  }
  EXPECT_EQ(at, bytes.size()) << "bytes after the SH array";
  return f;
}

TEST(SpzWriter, HeaderFollowsTheFormat) {
  test::TempFolder folder;
  GaussianScene scene = randomScene(10, 1);
  writeSpz(folder / "a.spz", scene, displayColour(scene));
  SpzFile f = decodeSpz(folder / "a.spz");
  EXPECT_EQ(f.magic, 0x5053474eu);
  EXPECT_EQ(f.version, 3u);
  EXPECT_EQ(f.count, 10u);
  EXPECT_EQ(f.shDegree, 0);
  EXPECT_EQ(f.fractionalBits, kSpzFractionalBits);
  EXPECT_EQ(f.flags, 0);
  EXPECT_EQ(f.reserved, 0);
}

TEST(SpzWriter, DecodesToTheSceneWithinTheQuantisation) {
  test::TempFolder folder;
  GaussianScene scene = randomScene(300, 2);
  for (int degree = 0; degree <= 3; ++degree) {
    SplatColour colour = test::randomShColour(scene, degree, 0.9f, 10 + uint64_t(degree));
    writeSpz(folder / "a.spz", scene, colour);
    SpzFile f = decodeSpz(folder / "a.spz");
    EXPECT_EQ(test::compareSplats(test::expectedSplats(scene, colour), f.splats, test::spzTolerance()), "")
        << "degree " << degree;
  }
}

TEST(SpzWriter, ToleranceIsTightEnoughToCatchAnOffByOneStep) {
  // The test above can fail: moving every position by one fixed-point step breaks it.
  test::TempFolder folder;
  GaussianScene scene = randomScene(50, 3);
  SplatColour colour = displayColour(scene);
  writeSpz(folder / "a.spz", scene, colour);
  SpzFile f = decodeSpz(folder / "a.spz");
  for (Vec3f& p : f.splats.position) p.x += 1.0f / 4096;
  EXPECT_NE(test::compareSplats(test::expectedSplats(scene, colour), f.splats, test::spzTolerance()), "");
}

TEST(SpzWriter, FarSceneKeepsFewerFractionalBits) {
  test::TempFolder folder;
  GaussianScene scene = randomScene(20, 4);
  scene.position[7] = {5000.0f, -3.0f, 2.0f};  // beyond the 2048 m that 12 fractional bits hold
  writeSpz(folder / "a.spz", scene, displayColour(scene));
  SpzFile f = decodeSpz(folder / "a.spz");
  EXPECT_EQ(f.fractionalBits, 10);  // 5000 x 2^10 < 2^23 <= 5000 x 2^11
  EXPECT_NEAR(f.splats.position[7].x, 5000.0f, 1.0f / 1024);
}

TEST(SpzWriter, OpacityStaysStrictlyBetweenZeroAndOne) {
  // Bytes 0 and 255 would decode to a logit of -inf or +inf.
  test::TempFolder folder;
  GaussianScene scene = randomScene(2, 5);
  scene.opacityLogit = {-30.0f, 30.0f};
  writeSpz(folder / "a.spz", scene, displayColour(scene));
  SpzFile f = decodeSpz(folder / "a.spz");
  EXPECT_FLOAT_EQ(f.splats.opacity[0], 1.0f / 255);
  EXPECT_FLOAT_EQ(f.splats.opacity[1], 254.0f / 255);
}

TEST(SpzWriter, RefusesPositionsNoFixedPointHolds) {
  test::TempFolder folder;
  GaussianScene scene = randomScene(3, 6);
  scene.position[1].z = 1e7f;
  try {
    writeSpz(folder / "a.spz", scene, displayColour(scene));
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a.spz"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("24-bit"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(folder / "a.spz"));
}

TEST(SpzWriter, RefusesNaN) {
  test::TempFolder folder;
  GaussianScene scene = randomScene(3, 7);
  SplatColour colour = displayColour(scene);
  colour.base[2].y = NAN;
  EXPECT_THROW(writeSpz(folder / "a.spz", scene, colour), Error);
  EXPECT_FALSE(std::filesystem::exists(folder / "a.spz"));
}

}  // namespace
}  // namespace glint
