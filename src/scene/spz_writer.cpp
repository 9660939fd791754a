// The .spz encoder: header, then each attribute as one array over all Gaussians, quantised
// as the format's reference implementation reads it, then gzip.
#include "scene/spz_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/gzip.h"
#include "scene/gaussian_ply.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

constexpr uint32_t kSpzMagic = 0x5053474e;  // "NGSP" read as a little-endian uint32
constexpr uint32_t kSpzVersion = 3;         // smallest-three rotations
// DC colour byte = f_dc x 0.15 x 255 + 127.5: a smaller scale than kShC0, so colours a little
// outside [0, 1] (which higher SH bands may bring back) still fit.
constexpr double kSpzColourScale = 0.15;
// Bits kept of each SH byte, degree 1 and degrees 2-3 (the reference writer's defaults; the
// dropped low bits are zero, which gzip compresses well, and readers need not know).
constexpr int kSpzSh1Bits = 5;
constexpr int kSpzShRestBits = 4;

void put8(std::string& out, int value) { out.push_back(char(uint8_t(value))); }
void put32(std::string& out, uint32_t value) {
  for (int b = 0; b < 4; ++b) put8(out, int(value >> (8 * b)));
}
uint8_t byteOf(double value) { return uint8_t(std::clamp(std::lround(value), 0L, 255L)); }

// The largest number of fractional bits <= kSpzFractionalBits with which every coordinate
// fits a signed 24-bit integer, or an Error.
int fractionalBitsFor(const fs::path& path, const GaussianScene& scene) {
  double extent = 0;
  for (const Vec3f& p : scene.position) extent = std::max({extent, std::abs(double(p.x)), std::abs(double(p.y)), std::abs(double(p.z))});
  constexpr double kLargest = double((1 << 23) - 1);
  for (int bits = kSpzFractionalBits; bits >= 0; --bits)
    if (extent * double(1 << bits) <= kLargest) return bits;
  throw Error(path.string(), "a Gaussian lies " + std::to_string(extent) +
                                 " m from the origin, beyond the +-8388607 m that .spz's 24-bit positions hold");
}

// The rotation as four bytes: the index of the largest |component| of the unit quaternion
// (x, y, z, w order) in the top 2 bits, then the other three, each as a sign bit and a 9-bit
// magnitude of |q_i| / sqrt(1/2), earlier components in higher bits. The largest is made
// positive (q and -q are one rotation) and recovered from the unit norm.
uint32_t smallestThree(const Quatf& rotation) {
  Quatf u = rotation.normalized();
  const double q[4] = {u.x, u.y, u.z, u.w};
  const int largest = largestMagnitudeIndex(q);
  const bool flip = q[largest] < 0;
  uint32_t packed = uint32_t(largest);
  for (int i = 0; i < 4; ++i) {
    if (i == largest) continue;
    double value = flip ? -q[i] : q[i];
    uint32_t magnitude = uint32_t(std::min(511L, std::lround(511.0 * std::abs(value) / std::sqrt(0.5))));
    packed = (packed << 10) | (uint32_t(value < 0) << 9) | magnitude;
  }
  return packed;
}

// An SH coefficient as a byte: 128 + 128 f, rounded to a multiple of 2^(8 - bits) so
// only `bits` significant bits remain.
uint8_t shByte(float f, int bits) {
  const long step = 1L << (8 - bits);
  return uint8_t(std::clamp(128 + step * std::lround(double(f) * 128.0 / double(step)), 0L, 255L));
}

std::string encodeSpz(const fs::path& path, const GaussianScene& scene, const SplatColour& colour) {
  const size_t n = scene.size();
  const int fractionalBits = fractionalBitsFor(path, scene);
  const size_t rest = colour.restCount();
  std::string out;
  out.reserve(16 + n * (9 + 1 + 3 + 3 + 4 + 3 * rest));
  put32(out, kSpzMagic);
  put32(out, kSpzVersion);
  put32(out, uint32_t(n));
  put8(out, colour.shDegree);
  put8(out, fractionalBits);
  put8(out, 0);  // flags: not trained with antialiasing, no extensions
  put8(out, 0);  // reserved

  // The format's axes are y up, z back: PLY's (x, y, z) is (x, -y, -z) there.
  const double flip[3] = {1, -1, -1};
  for (const Vec3f& p : scene.position) {
    for (int a = 0; a < 3; ++a) {
      int32_t fixed = int32_t(std::lround(flip[a] * double(p[a]) * double(1 << fractionalBits)));
      for (int b = 0; b < 3; ++b) put8(out, int(uint32_t(fixed) >> (8 * b)));
    }
  }
  // Opacity bytes 0 and 255 decode to a logit of -inf or +inf, which PLY readers reject.
  for (size_t i = 0; i < n; ++i) put8(out, std::clamp<int>(byteOf(255.0 * scene.opacity(i)), 1, 254));
  for (const Rgb& c : colour.base) {
    for (int k = 0; k < 3; ++k) put8(out, byteOf((double(c[k]) - 0.5) / kShC0 * kSpzColourScale * 255.0 + 127.5));
  }
  // Log scale byte = (log sigma + 10) x 16: sigma from e^-10 to e^5.9 in steps of 1/16 in the log.
  for (const Vec3f& s : scene.logScale)
    for (int k = 0; k < 3; ++k) put8(out, byteOf((double(s[k]) + 10.0) * 16.0));
  for (const Quatf& q : scene.rotation) put32(out, smallestThree(Quatf{q.w, q.x, -q.y, -q.z}));
  // Per Gaussian, coefficient by coefficient, the three channels of each together.
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = 0; k < rest; ++k) {
      const int sign = kShSignUnderTurnAboutX[k + 1];
      const int bits = k < 3 ? kSpzSh1Bits : kSpzShRestBits;
      for (int c = 0; c < 3; ++c) put8(out, shByte(float(sign) * colour.rest(i)[k][c], bits));
    }
  }
  return out;
}

}  // namespace

void writeSpz(const fs::path& path, const GaussianScene& scene, const SplatColour& colour) {
  GLINT_CHECK(scene.consistent() && colour.consistent(scene.size()), "writeSpz: arrays of different sizes");
  requireFiniteSplats(path, scene, colour);
  writeTextAtomically(path, gzipCompress(encodeSpz(path, scene, colour)));
}

}  // namespace glint
