// The edge-avoiding a-trous filter on structure-of-arrays planes, parallel over rows: eight
// neighbouring pixels are filtered at once in AVX2 registers (their taps are eight
// contiguous floats of each plane), the image's borders pixel by pixel.
#include "render/denoise.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"

#ifdef __AVX2__
#include <immintrin.h>
#endif

namespace glint {

namespace {

// Colour differences are relative to a pixel's brightness, but at least to this fraction of
// the image's mean value, so that near-black pixels still smooth.
constexpr float kBrightnessFloor = 0.1f;

// B3-spline weights (1 4 6 4 1) / 16 of Dammertz et al.'s kernel, per axis.
constexpr std::array<float, 5> kB3 = {1.0f / 16, 1.0f / 4, 3.0f / 8, 1.0f / 4, 1.0f / 16};

// exp(-x) for x >= 0 within 1e-6 relative (float rounding included): 2^y with y = -x / ln 2,
// split into an integer part placed in the exponent bits and a degree-5 polynomial for 2^f,
// f in [0, 1) (least-squares fit of the relative error, 2e-7, with p(0) = 1). Below 2^-80 it returns 2^-80 x p, a negligible weight that keeps
// every product with it clear of denormals (which are ~100 times slower).
inline float fastExpNegative(float x) {
  float y = std::max(-x * 1.44269504f, -80.0f);
  float whole = std::floor(y);
  float f = y - whole;
  float p = 1.858808676e-3f;
  p = p * f + 9.031053107e-3f;
  p = p * f + 5.579382121e-2f;
  p = p * f + 2.401643461e-1f;
  p = p * f + 6.931515913e-1f;
  p = p * f + 1.0f;
  int32_t bits = (int32_t(whole) + 127) << 23;
  return std::bit_cast<float>(bits) * p;
}

#ifdef __AVX2__
// fastExpNegative on eight values, the same steps in AVX2.
inline __m256 fastExpNegative8(__m256 x) {
  __m256 y = _mm256_max_ps(_mm256_mul_ps(x, _mm256_set1_ps(-1.44269504f)), _mm256_set1_ps(-80.0f));
  __m256 whole = _mm256_floor_ps(y);
  __m256 f = _mm256_sub_ps(y, whole);
  __m256 p = _mm256_set1_ps(1.858808676e-3f);
  p = _mm256_fmadd_ps(p, f, _mm256_set1_ps(9.031053107e-3f));
  p = _mm256_fmadd_ps(p, f, _mm256_set1_ps(5.579382121e-2f));
  p = _mm256_fmadd_ps(p, f, _mm256_set1_ps(2.401643461e-1f));
  p = _mm256_fmadd_ps(p, f, _mm256_set1_ps(6.931515913e-1f));
  p = _mm256_fmadd_ps(p, f, _mm256_set1_ps(1.0f));
  __m256i bits = _mm256_slli_epi32(_mm256_add_epi32(_mm256_cvttps_epi32(whole), _mm256_set1_epi32(127)), 23);
  return _mm256_mul_ps(_mm256_castsi256_ps(bits), p);
}
#endif

// What one pass reads: the planes of the colour being filtered and of the guides, in the
// order of kPlane*, and how its taps are spread and weighted.
enum Plane { kColourR, kColourG, kColourB, kAlbedoR, kAlbedoG, kAlbedoB, kNormalX, kNormalY, kNormalZ, kDepth,
             kDepthScale, kColourScale, kPlaneCount };
struct PassInput {
  std::array<const float*, kPlaneCount> plane;
  int width, height, step;
};

// Every plane of one atrousFilter call (those of PassInput and a second set of colour
// planes for the ping-pong between passes) in one buffer kept by the calling thread from
// call to call. Allocating and zeroing fresh planes per call and per pass had cost more
// than the filtering itself (denoise_bench at 1280x720: three quarters of the time in page
// faults and memset). Planes are staggered by a cache line, so that the same pixel of
// different planes does not fall into one L1 set when a plane is a multiple of 4 KiB.
class Workspace {
 public:
  static constexpr int kPlanes = kPlaneCount + 3;

  explicit Workspace(size_t pixels) {
    stride_ = (pixels + 15) / 16 * 16 + 16;
    thread_local std::vector<float> buffer;
    if (buffer.size() < stride_ * kPlanes) buffer.resize(stride_ * kPlanes);
    data_ = buffer.data();
  }
  float* plane(int k) const { return data_ + size_t(k) * stride_; }

 private:
  size_t stride_ = 0;
  float* data_ = nullptr;
};

// Splits an interleaved 3-channel image into planes[0..2], multiplying every value by scale.
void toPlanes(const Image& image, float scale, float* const planes[3]) {
  const size_t n = size_t(image.width) * size_t(image.height);
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) planes[k][i] = image.pixels[3 * i + size_t(k)] * scale;
}

// Writes the guides in the units of the edge-stopping function (squared differences of
// these are already divided by the squared sigmas) into their planes of the workspace:
// albedo, normal, depth (0 where there is no surface) and the depth scale
// 1 / (sigmaDepth x depth) of each pixel.
void makeGuides(const Image& albedo, const Image& normal, const Image& depth, const DenoiseSettings& settings,
                const Workspace& ws) {
  float* albedoPlanes[3] = {ws.plane(kAlbedoR), ws.plane(kAlbedoG), ws.plane(kAlbedoB)};
  float* normalPlanes[3] = {ws.plane(kNormalX), ws.plane(kNormalY), ws.plane(kNormalZ)};
  toPlanes(albedo, 1.0f / settings.sigmaAlbedo, albedoPlanes);
  toPlanes(normal, 1.0f / settings.sigmaNormal, normalPlanes);
  float* depthPlane = ws.plane(kDepth);
  float* depthScale = ws.plane(kDepthScale);
  for (size_t i = 0; i < depth.pixels.size(); ++i) {
    float d = hasSurface(depth.pixels[i]) ? depth.pixels[i] : 0.0f;
    depthPlane[i] = d;
    // A pixel with no surface gets a huge scale, so it mixes only with others of depth 0.
    depthScale[i] = 1.0f / (settings.sigmaDepth * std::max(d, 1e-6f));
  }
}

// The edge-stopping exponent between centre pixel p and tap q (plane indices), without the
// colour weight's product: colour and the rest are kept apart.
inline float edgeExponent(const PassInput& in, size_t p, size_t q) {
  auto sq = [&](int k) {
    float d = in.plane[size_t(k)][p] - in.plane[size_t(k)][q];
    return d * d;
  };
  float colour = sq(kColourR) + sq(kColourG) + sq(kColourB);
  float rest = sq(kAlbedoR) + sq(kAlbedoG) + sq(kAlbedoB) + sq(kNormalX) + sq(kNormalY) + sq(kNormalZ);
  float dd = (in.plane[kDepth][p] - in.plane[kDepth][q]) * in.plane[kDepthScale][p];
  return in.plane[kColourScale][p] * colour + rest + dd * dd;
}

// Filters pixel (x, y) into out (3 planes), skipping taps outside the image: they drop out
// of the normalised sum. The plain version, used at the image's borders.
void filterPixel(const PassInput& in, int x, int y, const std::array<float*, 3>& out) {
  size_t p = size_t(y) * size_t(in.width) + size_t(x);
  float sum[3] = {0, 0, 0}, weightSum = 0;
  for (int j = 0; j < 5; ++j) {
    int qy = y + (j - 2) * in.step;
    if (qy < 0 || qy >= in.height) continue;
    for (int i = 0; i < 5; ++i) {
      int qx = x + (i - 2) * in.step;
      if (qx < 0 || qx >= in.width) continue;
      size_t q = size_t(qy) * size_t(in.width) + size_t(qx);
      float w = kB3[size_t(i)] * kB3[size_t(j)] * fastExpNegative(edgeExponent(in, p, q));
      for (int c = 0; c < 3; ++c) sum[c] += w * in.plane[size_t(kColourR + c)][q];
      weightSum += w;
    }
  }
  // The centre tap always counts (weight > 0.14), so the sum is never zero.
  for (int c = 0; c < 3; ++c) out[size_t(c)][p] = sum[c] / weightSum;
}

#ifdef __AVX2__
// filterPixel for the eight pixels (x0..x0+7, y), all of whose taps lie inside the image
// columns: the centre pixels' values and the sums stay in registers over the 25 taps.
void filterEightPixels(const PassInput& in, int x0, int y, const std::array<float*, 3>& out) {
  size_t p = size_t(y) * size_t(in.width) + size_t(x0);
  __m256 centre[kPlaneCount];
  for (int k = 0; k < kPlaneCount; ++k) centre[k] = _mm256_loadu_ps(in.plane[size_t(k)] + p);
  __m256 sumR = _mm256_setzero_ps(), sumG = sumR, sumB = sumR, weightSum = sumR;
  for (int j = 0; j < 5; ++j) {
    int qy = y + (j - 2) * in.step;
    if (qy < 0 || qy >= in.height) continue;
    for (int i = 0; i < 5; ++i) {
      size_t q = size_t(qy) * size_t(in.width) + size_t(x0 + (i - 2) * in.step);
      __m256 tap[kDepth + 1];
      for (int k = 0; k <= kDepth; ++k) tap[k] = _mm256_loadu_ps(in.plane[size_t(k)] + q);
      auto sq = [&](__m256 acc, int k) {
        __m256 d = _mm256_sub_ps(centre[k], tap[k]);
        return _mm256_fmadd_ps(d, d, acc);
      };
      __m256 colour = sq(sq(sq(_mm256_setzero_ps(), kColourR), kColourG), kColourB);
      __m256 rest = sq(sq(sq(_mm256_setzero_ps(), kAlbedoR), kAlbedoG), kAlbedoB);
      rest = sq(sq(sq(rest, kNormalX), kNormalY), kNormalZ);
      __m256 dd = _mm256_mul_ps(_mm256_sub_ps(centre[kDepth], tap[kDepth]), centre[kDepthScale]);
      rest = _mm256_fmadd_ps(dd, dd, rest);
      __m256 w = _mm256_mul_ps(_mm256_set1_ps(kB3[size_t(i)] * kB3[size_t(j)]),
                               fastExpNegative8(_mm256_fmadd_ps(centre[kColourScale], colour, rest)));
      sumR = _mm256_fmadd_ps(w, tap[kColourR], sumR);
      sumG = _mm256_fmadd_ps(w, tap[kColourG], sumG);
      sumB = _mm256_fmadd_ps(w, tap[kColourB], sumB);
      weightSum = _mm256_add_ps(w, weightSum);
    }
  }
  __m256 inv = _mm256_div_ps(_mm256_set1_ps(1.0f), weightSum);
  _mm256_storeu_ps(out[0] + p, _mm256_mul_ps(sumR, inv));
  _mm256_storeu_ps(out[1] + p, _mm256_mul_ps(sumG, inv));
  _mm256_storeu_ps(out[2] + p, _mm256_mul_ps(sumB, inv));
}
#endif

// One pass: out = the kernel with taps `step` pixels apart over the colour planes `in`,
// weighted by the edge-stopping function with the workspace's guides. Colour differences
// are relative to the centre pixel's brightness, the root mean square of its channels
// (Monte Carlo noise grows with the signal), floored at brightnessFloor, and divided by
// sigmaColor.
void atrousPass(const std::array<float*, 3>& in, const std::array<float*, 3>& out, const Workspace& ws, int width,
                int height, int step, float sigmaColor, float brightnessFloor) {
  const size_t n = size_t(width) * size_t(height);
  float* colourScale = ws.plane(kColourScale);
  const float floorSquared = brightnessFloor * brightnessFloor;
  parallelForChunks(int64_t(n), 16384, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      float r = in[0][i], gr = in[1][i], b = in[2][i];
      float brightnessSquared = std::max((r * r + gr * gr + b * b) * (1.0f / 3.0f), floorSquared);
      colourScale[i] = 1.0f / (sigmaColor * sigmaColor * brightnessSquared);
    }
  });
  PassInput input{{in[0], in[1], in[2], ws.plane(kAlbedoR), ws.plane(kAlbedoG), ws.plane(kAlbedoB),
                   ws.plane(kNormalX), ws.plane(kNormalY), ws.plane(kNormalZ), ws.plane(kDepth),
                   ws.plane(kDepthScale), colourScale},
                  width, height, step};
  // Pixels whose taps all lie inside the image columns: [interiorBegin, interiorEnd).
  const int interiorBegin = std::min(width, 2 * step), interiorEnd = std::max(interiorBegin, width - 2 * step);
  parallelForChunks(height, 2, [&](int64_t rowBegin, int64_t rowEnd) {
    for (int y = int(rowBegin); y < int(rowEnd); ++y) {
      int x = 0;
      for (; x < interiorBegin; ++x) filterPixel(input, x, y, out);
#ifdef __AVX2__
      for (; x + 8 <= interiorEnd; x += 8) filterEightPixels(input, x, y, out);
#endif
      for (; x < width; ++x) filterPixel(input, x, y, out);
    }
  });
}

void checkGuide(const Image& guide, const Image& colour, int channels, const char* name) {
  if (guide.width != colour.width || guide.height != colour.height || guide.channels != channels)
    throw Error("denoiser", std::string("the ") + name + " guide is " + std::to_string(guide.width) + "x" +
                                std::to_string(guide.height) + "x" + std::to_string(guide.channels) + ", expected " +
                                std::to_string(colour.width) + "x" + std::to_string(colour.height) + "x" +
                                std::to_string(channels));
}

}  // namespace

Image atrousFilter(const Image& colour, const Image& albedo, const Image& normal, const Image& depth,
                   const DenoiseSettings& settings) {
  if (colour.channels != 3) throw Error("denoiser", "filters 3-channel colour images only");
  checkGuide(albedo, colour, 3, "albedo");
  checkGuide(normal, colour, 3, "normal");
  checkGuide(depth, colour, 1, "depth");
  const int width = colour.width, height = colour.height;
  double valueSum = 0;
  for (float v : colour.pixels) valueSum += double(v);
  float meanValue = float(valueSum / std::max<double>(1.0, double(colour.pixels.size())));
  if (!(meanValue > 0.0f) || settings.iterations <= 0) return colour;

  const Workspace ws(size_t(width) * size_t(height));
  makeGuides(albedo, normal, depth, settings, ws);
  std::array<float*, 3> current = {ws.plane(kColourR), ws.plane(kColourG), ws.plane(kColourB)};
  std::array<float*, 3> next = {ws.plane(kPlaneCount), ws.plane(kPlaneCount + 1), ws.plane(kPlaneCount + 2)};
  toPlanes(colour, 1.0f, current.data());
  float sigma = settings.sigmaColor;
  for (int pass = 0; pass < settings.iterations; ++pass) {
    atrousPass(current, next, ws, width, height, 1 << pass, sigma, kBrightnessFloor * meanValue);
    std::swap(current, next);
    sigma *= 0.5f;  // Dammertz et al.: the filtered colour is smoother after every pass
  }
  Image out(width, height, 3);
  for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
    for (int k = 0; k < 3; ++k) out.pixels[3 * i + size_t(k)] = current[size_t(k)][i];
  return out;
}

Image denoiseView(const ViewBuffers& buffers, const DenoiseSettings& settings) {
  const Image& diffuse = buffers[Buffer::Diffuse];
  const Image& normal = buffers[Buffer::Normal];
  const Image& depth = buffers[Buffer::Depth];
  if (settings.target == DenoiseTarget::Render) return atrousFilter(buffers[Buffer::Render], diffuse, normal, depth, settings);

  Image specular = buffers[Buffer::Specular];
  const Image& f0 = buffers[Buffer::F0];
  bool demodulate = settings.target == DenoiseTarget::SpecularDemodulated;
  if (demodulate)
    for (size_t i = 0; i < specular.pixels.size(); ++i)
      specular.pixels[i] /= std::max(f0.pixels[i], kMinDemodulationF0);
  Image out = atrousFilter(specular, diffuse, normal, depth, settings);
  for (size_t i = 0; i < out.pixels.size(); ++i) {
    if (demodulate) out.pixels[i] *= std::max(f0.pixels[i], kMinDemodulationF0);
    out.pixels[i] += diffuse.pixels[i];
  }
  return out;
}

}  // namespace glint
