// The monocular degradation's parameters, and its application to one view.
#include "synth/monocular_degradation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "io/transfer.h"
#include "math/rng.h"
#include "scene/buffer_degradation.h"

namespace glint {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Rodrigues' rotation of v by `angle` about the unit axis k.
Vec3d rotateAbout(const Vec3d& v, const Vec3d& k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + cross(k, v) * s + k * (dot(k, v) * (1.0 - c));
}

// Blur, then noise added to the filmic display values (what an 8-bit predictor output holds).
Image degradeRadiance(const Image& exact, const MonocularDegradation& g, uint64_t seed) {
  Image display = toDisplay(Transfer::Filmic, gaussianBlur(exact, g.radianceBlur));
  display = addGaussianNoise(display, g.radianceNoise, seed);
  for (float& v : display.pixels) v = std::clamp(v, 0.0f, 1.0f);
  return toLinear(Transfer::Filmic, std::move(display));
}

double medianSurfaceDepth(const Image& depth) {
  std::vector<float> z;
  for (float v : depth.pixels)
    if (hasSurface(v)) z.push_back(v);
  if (z.empty()) return 1.0;
  std::nth_element(z.begin(), z.begin() + z.size() / 2, z.end());
  return z[z.size() / 2];
}

// A unit-variance field correlated over `correlation` pixels, cut from a larger one: the
// blur repeats the edge pixels, which leaves a field blurred at the image's own size with
// several times the variance within 3 sigma of its borders.
Image borderlessField(int width, int height, uint64_t seed, double correlation) {
  const int pad = int(std::ceil(3.0 * correlation));
  const Image padded = smoothGaussianField(width + 2 * pad, height + 2 * pad, 1, seed, correlation);
  Image field(width, height, 1);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) field.at(i, j) = padded.at(i + pad, j + pad);
  return field;
}

// The warp z' = zm (z / zm)^gamma, the smooth scale field, the edge blur and the noise.
Image degradeDepth(const Image& exact, const MonocularDegradation& g, uint64_t seed) {
  const double zm = medianSurfaceDepth(exact);
  const Image field = borderlessField(exact.width, exact.height, hashKeys({seed, 1}), g.depthFieldCorrelation);
  Image warped = exact;
  for (size_t p = 0; p < warped.pixels.size(); ++p) {
    float& z = warped.pixels[p];
    if (!hasSurface(z)) continue;
    z = float(zm * std::pow(z / zm, g.depthGamma) * (1.0 + g.depthFieldAmplitude * field.pixels[p]));
  }
  warped = blurSurfaces(warped, exact, g.depthEdgeBlur);
  const Image noise = smoothGaussianField(exact.width, exact.height, 1, hashKeys({seed, 2}), 0);
  for (size_t p = 0; p < warped.pixels.size(); ++p)
    if (hasSurface(exact.pixels[p]))
      warped.pixels[p] = std::max(0.0f, float(warped.pixels[p] * (1.0 + g.depthRelativeNoise * noise.pixels[p])));
  return warped;
}

// Per-pixel tilt, then one rotation of the whole view about a random axis.
Image degradeNormals(const Image& exact, const MonocularDegradation& g, uint64_t seed) {
  Image normals = perturbNormals(exact, g.normalMeanAngle, hashKeys({seed, 3}), 0);
  Rng rng = Rng::forKeys({seed, 4});
  const double u = 2.0 * rng.uniformDouble() - 1.0, phi = 2.0 * std::numbers::pi * rng.uniformDouble();
  const double r = std::sqrt(std::max(0.0, 1.0 - u * u));
  const Vec3d axis(r * std::cos(phi), r * std::sin(phi), u);
  for (size_t p = 0; p < normals.pixels.size(); p += 3) {
    Vec3d n(normals.pixels[p], normals.pixels[p + 1], normals.pixels[p + 2]);
    if (length(n) == 0) continue;
    n = rotateAbout(n, axis, g.normalViewTilt);
    normals.pixels[p] = float(n.x), normals.pixels[p + 1] = float(n.y), normals.pixels[p + 2] = float(n.z);
  }
  return normals;
}

}  // namespace

MonocularDegradation monocularDegradation(int width, uint64_t seed, uint64_t view) {
  const double pixelScale = width / 160.0;
  MonocularDegradation g;
  g.radianceBlur = 0.7 * pixelScale;
  Rng rng = Rng::forKeys({seed, view, 0x30c0});
  g.depthGamma = 0.85 + 0.3 * rng.uniformDouble();
  g.depthFieldCorrelation = 12.0 * pixelScale;
  g.depthEdgeBlur = 1.0 * pixelScale;
  g.normalMeanAngle = 3.0 * kDegree;
  g.normalViewTilt = 1.5 * kDegree;
  return g;
}

ViewBuffers monocularPriors(const ViewBuffers& exact, uint64_t seed, uint64_t view) {
  const MonocularDegradation g = monocularDegradation(exact[Buffer::Render].width, seed, view);
  const uint64_t viewSeed = hashKeys({seed, view, 0x30c1});
  ViewBuffers out = exact;
  out[Buffer::Diffuse] = degradeRadiance(exact[Buffer::Diffuse], g, hashKeys({viewSeed, 5}));
  out[Buffer::Specular] = degradeRadiance(exact[Buffer::Specular], g, hashKeys({viewSeed, 6}));
  out[Buffer::Depth] = degradeDepth(exact[Buffer::Depth], g, viewSeed);
  out[Buffer::Normal] = degradeNormals(exact[Buffer::Normal], g, viewSeed);
  const Image roughness = addGaussianNoise(exact[Buffer::Roughness], g.roughnessNoise, hashKeys({viewSeed, 7}));
  out[Buffer::Roughness] = biasRoughness(roughness, 1.0, g.roughnessOffset);
  return out;
}

}  // namespace glint
