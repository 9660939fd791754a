// The compressed PLY encoder: Morton order, per-chunk bounds, then positions and scales as
// 11-10-11-bit fractions of their chunk's range, rotations as smallest-three 2-10-10-10, and
// colour and opacity as 8-bit fractions.
#include "scene/compressed_ply_writer.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "math/morton.h"
#include "scene/gaussian_ply.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

// Log scales are bounded to this range before the chunk's range is taken, as PlayCanvas
// does: a degenerate Gaussian's huge log scale would otherwise spoil its chunk's others.
constexpr float kMaxAbsLogScale = 20.0f;

// value in [0, 1] as an unsigned integer of `bits` bits, rounded to nearest.
uint32_t unorm(double value, int bits) {
  const double top = double((1u << bits) - 1);
  return uint32_t(std::clamp(std::floor(value * top + 0.5), 0.0, top));
}

// Where x lies in [lo, hi] as a fraction; 0 when the range is (nearly) empty.
double fraction(double x, double lo, double hi) {
  if (x <= lo) return 0.0;
  if (x >= hi) return 1.0;
  return hi - lo < 1e-5 ? 0.0 : (x - lo) / (hi - lo);
}

// Minimum and maximum of one float quantity over a chunk.
struct Range {
  float lo = INFINITY, hi = -INFINITY;
  void add(float v) { lo = std::min(lo, v); hi = std::max(hi, v); }
};

// Three components packed 11, 10 and 11 bits wide, x in the top bits.
uint32_t pack111011(const Vec3f& v, const Range (&r)[3]) {
  return unorm(fraction(v.x, r[0].lo, r[0].hi), 11) << 21 | unorm(fraction(v.y, r[1].lo, r[1].hi), 10) << 11 |
         unorm(fraction(v.z, r[2].lo, r[2].hi), 11);
}

// The unit quaternion (w, x, y, z order) as 2-10-10-10 bits: the index of its largest
// |component| on top, then the other three, each mapped from [-sqrt(1/2), sqrt(1/2)] to
// [0, 1]. The largest is made positive and recovered from the unit norm.
uint32_t packRotation(const Quatf& rotation) {
  Quatf u = rotation.normalized();
  const double q[4] = {u.w, u.x, u.y, u.z};
  const int largest = largestMagnitudeIndex(q);
  const double sign = q[largest] < 0 ? -1.0 : 1.0;
  uint32_t packed = uint32_t(largest);
  for (int i = 0; i < 4; ++i)
    if (i != largest) packed = (packed << 10) | unorm(sign * q[i] * std::sqrt(0.5) + 0.5, 10);
  return packed;
}

// An f_rest coefficient as a byte: [-4, 4] in 256 steps (readers take the step's centre).
uint8_t shByte(float f) { return uint8_t(std::clamp(std::floor((double(f) / 8.0 + 0.5) * 256.0), 0.0, 255.0)); }

void putFloat(std::string& out, float v) { out.append(reinterpret_cast<const char*>(&v), 4); }
void putUint(std::string& out, uint32_t v) {
  for (int b = 0; b < 4; ++b) out.push_back(char(uint8_t(v >> (8 * b))));
}

std::string header(size_t n, size_t chunks, size_t shColumns) {
  std::string h = "ply\nformat binary_little_endian 1.0\n";
  h += "comment Glint Gaussian scene, PlayCanvas compressed layout: colour is display-referred (filmic tonemap)\n";
  h += "element chunk " + std::to_string(chunks) + "\n";
  for (const char* bound : {"min", "max"})
    for (const char* axis : {"x", "y", "z"}) h += std::string("property float ") + bound + "_" + axis + "\n";
  for (const char* bound : {"min", "max"})
    for (const char* axis : {"x", "y", "z"}) h += std::string("property float ") + bound + "_scale_" + axis + "\n";
  for (const char* bound : {"min", "max"})
    for (const char* channel : {"r", "g", "b"}) h += std::string("property float ") + bound + "_" + channel + "\n";
  h += "element vertex " + std::to_string(n) + "\n";
  for (const char* name : {"packed_position", "packed_rotation", "packed_scale", "packed_color"})
    h += std::string("property uint ") + name + "\n";
  if (shColumns > 0) {
    h += "element sh " + std::to_string(n) + "\n";
    for (size_t j = 0; j < shColumns; ++j) h += "property uchar f_rest_" + std::to_string(j) + "\n";
  }
  return h + "end_header\n";
}

}  // namespace

std::vector<uint32_t> compressedPlyOrder(const GaussianScene& scene) {
  Range box[3];
  for (const Vec3f& p : scene.position)
    for (int a = 0; a < 3; ++a) box[a].add(p[a]);
  std::vector<uint32_t> code(scene.size());
  for (size_t i = 0; i < scene.size(); ++i) {
    uint32_t cell[3];
    for (int a = 0; a < 3; ++a) cell[a] = unorm(fraction(scene.position[i][a], box[a].lo, box[a].hi), 10);
    code[i] = mortonCode3(cell[0], cell[1], cell[2]);
  }
  std::vector<uint32_t> order(scene.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return code[a] < code[b]; });
  return order;
}

void writeCompressedPly(const fs::path& path, const GaussianScene& scene, const SplatColour& colour) {
  GLINT_CHECK(scene.consistent() && colour.consistent(scene.size()), "writeCompressedPly: arrays of different sizes");
  requireFiniteSplats(path, scene, colour);
  const size_t n = scene.size();
  const size_t chunks = (n + kCompressedPlyChunkSize - 1) / kCompressedPlyChunkSize;
  const size_t rest = colour.restCount();
  const std::vector<uint32_t> order = compressedPlyOrder(scene);

  std::string chunkBytes, vertexBytes, shBytes;
  for (size_t chunk = 0; chunk < chunks; ++chunk) {
    const size_t first = chunk * kCompressedPlyChunkSize, last = std::min(n, first + kCompressedPlyChunkSize);
    Range position[3], scale[3], rgb[3];
    for (size_t j = first; j < last; ++j) {
      const uint32_t i = order[j];
      for (int a = 0; a < 3; ++a) {
        position[a].add(scene.position[i][a]);
        scale[a].add(std::clamp(scene.logScale[i][a], -kMaxAbsLogScale, kMaxAbsLogScale));
        rgb[a].add(colour.base[i][a]);
      }
    }
    // The chunk's row: min_x min_y min_z max_x max_y max_z, then the scale's, then the colour's.
    auto putBounds = [&](const Range(&ranges)[3]) {
      for (const Range& r : ranges) putFloat(chunkBytes, r.lo);
      for (const Range& r : ranges) putFloat(chunkBytes, r.hi);
    };
    putBounds(position);
    putBounds(scale);
    putBounds(rgb);
    for (size_t j = first; j < last; ++j) {
      const uint32_t i = order[j];
      putUint(vertexBytes, pack111011(scene.position[i], position));
      putUint(vertexBytes, packRotation(scene.rotation[i]));
      putUint(vertexBytes, pack111011(scene.logScale[i], scale));
      const Rgb& c = colour.base[i];
      // Opacity 0 and 1 decode to a logit of -inf or +inf, which PLY readers reject.
      const uint32_t alpha = std::clamp<uint32_t>(unorm(scene.opacity(i), 8), 1, 254);
      putUint(vertexBytes, unorm(fraction(c.x, rgb[0].lo, rgb[0].hi), 8) << 24 |
                               unorm(fraction(c.y, rgb[1].lo, rgb[1].hi), 8) << 16 |
                               unorm(fraction(c.z, rgb[2].lo, rgb[2].hi), 8) << 8 | alpha);
      // f_rest_j: channel-major as in 3DGS PLY files (the red coefficients first).
      for (int channel = 0; channel < 3; ++channel)
        for (size_t k = 0; k < rest; ++k) shBytes.push_back(char(shByte(colour.rest(i)[k][channel])));
    }
  }
  writeTextAtomically(path, header(n, chunks, 3 * rest) + chunkBytes + vertexBytes + shBytes);
}

}  // namespace glint
