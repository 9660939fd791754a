// Blur, noise, affine depth error, tilted normals and biased roughness.
#include "scene/buffer_degradation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/error.h"
#include "math/rng.h"
#include "math/vec.h"

namespace glint {

namespace {

// Normalised 1D Gaussian weights for offsets -radius..radius, radius = ceil(3 sigma).
std::vector<double> gaussianKernel(double sigma) {
  int radius = std::max(1, int(std::ceil(3.0 * sigma)));
  std::vector<double> w(2 * radius + 1);
  double sum = 0;
  for (int o = -radius; o <= radius; ++o) sum += w[o + radius] = std::exp(-0.5 * o * o / (sigma * sigma));
  for (double& v : w) v /= sum;
  return w;
}

// One pass of the separable blur along x (dx = 1) or y (dx = 0). Where `weight` is given
// (1 per pixel: 1 = contributes), the result is a normalised convolution of weight x value.
Image blurPass(const Image& image, const std::vector<double>& kernel, bool alongX, const Image* weight,
               Image* outWeight) {
  int radius = int(kernel.size() / 2);
  Image out(image.width, image.height, image.channels);
  if (outWeight) *outWeight = Image(image.width, image.height, 1);
  std::vector<double> sum(image.channels);
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i) {
      std::fill(sum.begin(), sum.end(), 0.0);
      double weightSum = 0;
      for (int o = -radius; o <= radius; ++o) {
        int x = alongX ? std::clamp(i + o, 0, image.width - 1) : i;
        int y = alongX ? j : std::clamp(j + o, 0, image.height - 1);
        double w = kernel[o + radius] * (weight ? weight->at(x, y) : 1.0);
        weightSum += w;
        for (int c = 0; c < image.channels; ++c) sum[c] += w * image.at(x, y, c);
      }
      if (outWeight) outWeight->at(i, j) = float(weightSum);
      for (int c = 0; c < image.channels; ++c) out.at(i, j, c) = weightSum > 0 ? float(sum[c] / weightSum) : 0.0f;
    }
  return out;
}

// A standard normal deviate for (seed, pixel, channel), by the Box-Muller transform.
double gaussianDeviate(uint64_t seed, size_t pixel, int channel) {
  Rng rng = Rng::forKeys({seed, uint64_t(pixel), uint64_t(channel)});
  double u1 = 1.0 - rng.uniformDouble();  // (0, 1], so the log is finite
  double u2 = rng.uniformDouble();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

}  // namespace

Image smoothGaussianField(int width, int height, int channels, uint64_t seed, double correlation) {
  Image field(width, height, channels);
  for (size_t p = 0; p < size_t(width) * height; ++p)
    for (int c = 0; c < channels; ++c) field.pixels[p * channels + c] = float(gaussianDeviate(seed, p, c));
  if (correlation <= 0) return field;
  // Blurring white noise with weights w along x and then y scales its variance by
  // (sum w^2)^2; dividing by sum w^2 restores unit variance (away from the borders).
  std::vector<double> kernel = gaussianKernel(correlation);
  double sumSquares = 0;
  for (double w : kernel) sumSquares += w * w;
  Image smooth = gaussianBlur(field, correlation);
  for (float& v : smooth.pixels) v = float(v / sumSquares);
  return smooth;
}

Image blurSurfaces(const Image& image, const Image& depth, double sigma) {
  if (sigma <= 0) return image;
  Image mask(depth.width, depth.height, 1);
  for (size_t p = 0; p < depth.pixels.size(); ++p) mask.pixels[p] = hasSurface(depth.pixels[p]) ? 1.0f : 0.0f;
  std::vector<double> kernel = gaussianKernel(sigma);
  Image rowWeight;
  Image rows = blurPass(image, kernel, true, &mask, &rowWeight);
  Image blurred = blurPass(rows, kernel, false, &rowWeight, nullptr);
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i)
      if (mask.at(i, j) == 0)
        for (int c = 0; c < image.channels; ++c) blurred.at(i, j, c) = image.at(i, j, c);
  return blurred;
}

Image gaussianBlur(const Image& image, double sigma) {
  if (sigma <= 0) return image;
  std::vector<double> kernel = gaussianKernel(sigma);
  return blurPass(blurPass(image, kernel, true, nullptr, nullptr), kernel, false, nullptr, nullptr);
}

Image addGaussianNoise(const Image& image, double sigma, uint64_t seed) {
  Image out = image;
  for (size_t p = 0; p < size_t(image.width) * image.height; ++p)
    for (int c = 0; c < image.channels; ++c)
      out.pixels[p * image.channels + c] += float(sigma * gaussianDeviate(seed, p, c));
  return out;
}

Image affineDepthError(const Image& depth, double scale, double offset) {
  GLINT_CHECK(depth.channels == 1, "depth has one channel");
  Image out = depth;
  for (float& d : out.pixels)
    if (hasSurface(d)) d = std::max(0.0f, float(scale * d + offset));
  return out;
}

Image perturbNormals(const Image& normals, double meanAngle, uint64_t seed, double correlationPixels) {
  GLINT_CHECK(normals.channels == 3, "normal maps have three channels");
  Image out = normals;
  if (meanAngle <= 0) return out;
  Image field = smoothGaussianField(normals.width, normals.height, 3, seed, correlationPixels);
  // The tangent part t of a unit 3D Gaussian has |t| Rayleigh distributed with mean
  // sqrt(pi/2), so this scale makes the mean tilt angle meanAngle.
  double anglePerLength = meanAngle / std::sqrt(std::numbers::pi / 2.0);
  for (int j = 0; j < normals.height; ++j)
    for (int i = 0; i < normals.width; ++i) {
      Vec3d n(normals.rgb(i, j));
      if (length(n) == 0) continue;
      n = normalize(n);
      Vec3d g(field.rgb(i, j));
      Vec3d t = g - n * dot(g, n);
      double tLength = length(t);
      if (tLength == 0) continue;
      double angle = anglePerLength * tLength;
      out.setRgb(i, j, Rgb(n * std::cos(angle) + t * (std::sin(angle) / tLength)));
    }
  return out;
}

Image biasRoughness(const Image& roughness, double scale, double offset) {
  Image out = roughness;
  for (float& r : out.pixels) r = std::clamp(float(scale * r + offset), 0.0f, 1.0f);
  return out;
}

ViewBuffers degradeBuffers(const ViewBuffers& exact, const BufferDegradation& degradation, uint64_t view) {
  const BufferDegradation& g = degradation;
  const Image& depth = exact[Buffer::Depth];
  ViewBuffers out = exact;
  // A network's outputs are smooth: blur the G-buffers within surfaces first.
  for (Buffer b : {Buffer::Depth, Buffer::Normal, Buffer::Roughness, Buffer::F0})
    out[b] = blurSurfaces(exact[b], depth, g.blurSigma);

  Image noisyDepth = affineDepthError(out[Buffer::Depth], g.depthScale, g.depthOffset);
  if (g.depthNoise > 0) {
    Image noise = addGaussianNoise(Image(depth.width, depth.height, 1), g.depthNoise, hashKeys({g.seed, view, 1}));
    for (size_t p = 0; p < noisyDepth.pixels.size(); ++p)
      if (hasSurface(noisyDepth.pixels[p]))
        noisyDepth.pixels[p] = std::max(0.0f, noisyDepth.pixels[p] + noise.pixels[p]);
  }
  out[Buffer::Depth] = noisyDepth;

  Image normals = out[Buffer::Normal];
  for (size_t p = 0; p < normals.pixels.size(); p += 3) {  // the blur shortened them
    Vec3d n = normalize(Vec3d(normals.pixels[p], normals.pixels[p + 1], normals.pixels[p + 2]));
    normals.pixels[p] = float(n.x), normals.pixels[p + 1] = float(n.y), normals.pixels[p + 2] = float(n.z);
  }
  out[Buffer::Normal] = perturbNormals(normals, g.normalMeanAngle, hashKeys({g.seed, view, 2}), g.normalCorrelation);

  Image roughness = addGaussianNoise(out[Buffer::Roughness], g.roughnessNoise, hashKeys({g.seed, view, 3}));
  out[Buffer::Roughness] = biasRoughness(roughness, g.roughnessScale, g.roughnessOffset);
  return out;
}

}  // namespace glint
