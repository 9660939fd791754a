// Comparing Gaussians decoded from a compressed splat file with what was written, within
// stated quantisation tolerances; shared by the writers' unit tests and the splat-transform
// round trip (tests/splat).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "math/quat.h"
#include "math/rng.h"
#include "math/vec.h"
#include "scene/gaussians.h"
#include "scene/splat_colour.h"

namespace glint::test {

// Gaussians as a splat viewer sees them: display colour and SH coefficients f_1.. per Gaussian.
struct DecodedSplats {
  std::vector<Vec3f> position;
  std::vector<Vec3f> logScale;
  std::vector<Quatf> rotation;
  std::vector<float> opacity;  // after the sigmoid
  std::vector<Rgb> colour;     // 0.5 + kShC0 f_dc
  int shDegree = 0;
  std::vector<Rgb> sh;  // Gaussian i's coefficient k >= 1 at i * (count - 1) + k - 1

  size_t size() const { return position.size(); }
};

// Display colours of the scene with random SH coefficients of `degree`, uniform in
// [-range, range] (a format's range, so that nothing is clamped).
inline SplatColour randomShColour(const GaussianScene& scene, int degree, float range, uint64_t seed) {
  SplatColour colour = displayColour(scene);
  colour.shDegree = degree;
  Rng rng(seed);
  auto uniform = [&] { return range * (2.0f * rng.uniform() - 1.0f); };
  for (size_t i = 0; i < scene.size() * colour.restCount(); ++i) colour.sh.push_back({uniform(), uniform(), uniform()});
  return colour;
}

// What a writer was given, in the order order[j] (all of them in scene order if empty).
inline DecodedSplats expectedSplats(const GaussianScene& scene, const SplatColour& colour,
                                    const std::vector<uint32_t>& order = {}) {
  DecodedSplats s;
  s.shDegree = colour.shDegree;
  for (size_t j = 0; j < scene.size(); ++j) {
    const size_t i = order.empty() ? j : order[j];
    s.position.push_back(scene.position[i]);
    s.logScale.push_back(scene.logScale[i]);
    s.rotation.push_back(scene.rotation[i].normalized());
    s.opacity.push_back(scene.opacity(i));
    s.colour.push_back(colour.base[i]);
    for (size_t k = 0; k < colour.restCount(); ++k) s.sh.push_back(colour.rest(i)[k]);
  }
  return s;
}

// Largest errors a format's quantisation allows (each with a margin for float rounding).
struct SplatTolerance {
  float position;       // metres, per coordinate
  float logScale;       // per axis
  float rotationAngle;  // radians between the two rotations
  float opacity;
  float colour;         // display colour, per channel
  float sh1;            // SH coefficients of degree 1
  float shRest;         // of degrees 2 and 3
  // What the format can hold at all: expected values beyond are compared clamped.
  float colourMin = -INFINITY, colourMax = INFINITY;
  float shMin = -INFINITY, shMax = INFINITY;
};

// "" when every value of got lies within tol of expected, else a description of the first
// few failures (Gaussian, quantity, values).
inline std::string compareSplats(const DecodedSplats& expected, const DecodedSplats& got, const SplatTolerance& tol) {
  if (expected.size() != got.size())
    return "Gaussian count " + std::to_string(got.size()) + ", expected " + std::to_string(expected.size());
  if (expected.shDegree != got.shDegree)
    return "SH degree " + std::to_string(got.shDegree) + ", expected " + std::to_string(expected.shDegree);
  std::string failures;
  int count = 0;
  auto check = [&](size_t i, const char* what, double want, double have, double limit) {
    if (std::abs(want - have) <= limit) return;
    if (++count <= 8) {
      char line[200];
      std::snprintf(line, sizeof(line), "Gaussian %zu %s: %.6g, expected %.6g (tolerance %.3g)\n", i, what, have,
                    want, limit);
      failures += line;
    }
  };
  const size_t rest = expected.sh.size() / std::max<size_t>(expected.size(), 1);
  if (got.sh.size() != expected.sh.size()) return "SH coefficient count differs";
  for (size_t i = 0; i < expected.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      check(i, "position", expected.position[i][a], got.position[i][a], tol.position);
      check(i, "log scale", expected.logScale[i][a], got.logScale[i][a], tol.logScale);
      check(i, "colour", std::clamp(expected.colour[i][a], tol.colourMin, tol.colourMax), got.colour[i][a],
            tol.colour);
    }
    const Quatf p = expected.rotation[i].normalized(), q = got.rotation[i].normalized();
    const double cosHalf = std::min(1.0, std::abs(double(p.w * q.w + p.x * q.x + p.y * q.y + p.z * q.z)));
    check(i, "rotation angle", 0.0, 2.0 * std::acos(cosHalf), tol.rotationAngle);
    check(i, "opacity", expected.opacity[i], got.opacity[i], tol.opacity);
    for (size_t k = 0; k < rest; ++k)
      for (int c = 0; c < 3; ++c)
        check(i, k < 3 ? "SH degree 1" : "SH degree 2-3", std::clamp(expected.sh[i * rest + k][c], tol.shMin, tol.shMax),
              got.sh[i * rest + k][c], k < 3 ? tol.sh1 : tol.shRest);
  }
  if (count > 8) failures += "... " + std::to_string(count - 8) + " more\n";
  return failures;
}

// .spz's steps (scene/spz_writer.cpp), half of each plus rounding: positions 2^-12 m
// (12 fractional bits); log scales 1/16; rotations 9-bit magnitudes of the three smallest
// components over [0, sqrt(1/2)] (e = 6.9e-4 each; the largest, recovered from the unit
// norm and no smaller than they are, errs by at most 3e, so |dq| <= sqrt(12) e and the
// angle twice that); opacity 1/255 (and the clamp to [1, 254] / 255); colour
// kShC0 / (0.15 x 255); SH steps of 1/128 kept to 5 bits (1/16) for degree 1, 4 bits (1/8)
// above. The bytes hold colour within 0.5 +- kShC0 / 0.3 and SH within [-1, 127/128].
inline SplatTolerance spzTolerance() {
  SplatTolerance t{0.5f / 4096 + 1e-6f, 0.5f / 16 + 1e-5f, 2 * 3.4641f * (0.7072f / 511 / 2) + 1e-4f, 1.0f / 255,
                   0.5f * 0.28209479f / (0.15f * 255) + 1e-5f, 0.5f / 16 + 1e-5f, 0.5f / 8 + 1e-5f};
  t.colourMin = 0.5f - 0.28209479f / 0.3f;
  t.colourMax = 0.5f + 0.28209479f / 0.3f;
  t.shMin = -1.0f;
  t.shMax = 127.0f / 128;
  return t;
}

// The compressed PLY's steps (scene/compressed_ply_writer.cpp) for a scene whose positions,
// log scales and colours span at most the given ranges (a chunk spans no more than the
// scene): positions and log scales in 10 bits at worst (y; x and z have 11), colour and
// opacity in 8 bits, rotations' three smallest components 10 bits over [-sqrt(1/2),
// sqrt(1/2)] (angle bound as for .spz), SH 8 bits over [-4, 4] (readers take a step's centre).
inline SplatTolerance compressedPlyTolerance(float positionRange, float logScaleRange, float colourRange) {
  SplatTolerance t{0.5f * positionRange / 1023 + 1e-5f, 0.5f * logScaleRange / 1023 + 1e-5f,
                   2 * 3.4641f * (1.4143f / 1023 / 2) + 1e-4f, 1.0f / 255, 0.5f * colourRange / 255 + 1e-5f,
                   0.5f * 8 / 256 + 1e-5f, 0.5f * 8 / 256 + 1e-5f};
  t.shMin = -4.0f;
  t.shMax = 4.0f;
  return t;
}

}  // namespace glint::test
