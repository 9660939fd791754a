// PSNR, SSIM (separable Gaussian window), depth RMSE and normal angular error.
#include "eval/image_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/tonemap.h"
#include "scene/buffers.h"

namespace glint {

namespace {

// SSIM constants of Wang et al. 2004 for data range 1.
constexpr int kWindowSize = 11;
constexpr int kWindowRadius = kWindowSize / 2;
constexpr double kWindowSigma = 1.5;
constexpr double kC1 = (0.01 * 1.0) * (0.01 * 1.0);
constexpr double kC2 = (0.03 * 1.0) * (0.03 * 1.0);

std::string describeShape(const Image& image) {
  return std::to_string(image.width) + "x" + std::to_string(image.height) + " with " +
         std::to_string(image.channels) + " channel(s)";
}

void requireSameShape(const Image& a, const Image& b, const char* what) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    throw Error(std::string(what) + ": images differ in shape (" + describeShape(a) + " vs " + describeShape(b) + ")");
}

void requireChannels(const Image& image, int channels, const char* what) {
  if (image.channels != channels)
    throw Error(std::string(what) + ": expected " + std::to_string(channels) + " channel(s), got " +
                describeShape(image));
}

void requireSameSize(const Image& a, const Image& b, const char* what) {
  if (a.width != b.width || a.height != b.height)
    throw Error(std::string(what) + ": images differ in size (" + describeShape(a) + " vs " + describeShape(b) + ")");
}

// The 1D factor of the 11x11 window: the 2D window is its outer product with itself.
std::array<double, kWindowSize> gaussianWindow() {
  std::array<double, kWindowSize> w{};
  double sum = 0;
  for (int i = 0; i < kWindowSize; ++i) {
    double d = i - kWindowRadius;
    w[i] = std::exp(-d * d / (2.0 * kWindowSigma * kWindowSigma));
    sum += w[i];
  }
  for (double& v : w) v /= sum;
  return w;
}

// Gaussian-weighted local means of a plane over the 'valid' region: a horizontal then a
// vertical pass, (width - 10) x (height - 10) outputs. Separable, so 22 rather than 121
// multiplies per output.
std::vector<double> filterValid(const std::vector<double>& plane, int width, int height) {
  static const std::array<double, kWindowSize> w = gaussianWindow();
  int outWidth = width - (kWindowSize - 1), outHeight = height - (kWindowSize - 1);
  std::vector<double> rows(size_t(outWidth) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < outWidth; ++x) {
      const double* p = &plane[size_t(y) * width + x];
      double s = 0;
      for (int k = 0; k < kWindowSize; ++k) s += w[k] * p[k];
      rows[size_t(y) * outWidth + x] = s;
    }
  std::vector<double> out(size_t(outWidth) * outHeight);
  for (int y = 0; y < outHeight; ++y)
    for (int x = 0; x < outWidth; ++x) {
      double s = 0;
      for (int k = 0; k < kWindowSize; ++k) s += w[k] * rows[size_t(y + k) * outWidth + x];
      out[size_t(y) * outWidth + x] = s;
    }
  return out;
}

// Mean SSIM of one channel.
double ssimChannel(const Image& a, const Image& b, int c) {
  size_t n = size_t(a.width) * a.height;
  std::vector<double> x(n), y(n), xx(n), yy(n), xy(n);
  for (size_t i = 0; i < n; ++i) {
    x[i] = a.pixels[i * a.channels + c];
    y[i] = b.pixels[i * b.channels + c];
    xx[i] = x[i] * x[i];
    yy[i] = y[i] * y[i];
    xy[i] = x[i] * y[i];
  }
  std::vector<double> muX = filterValid(x, a.width, a.height), muY = filterValid(y, a.width, a.height);
  std::vector<double> eXX = filterValid(xx, a.width, a.height), eYY = filterValid(yy, a.width, a.height);
  std::vector<double> eXY = filterValid(xy, a.width, a.height);
  double sum = 0;
  for (size_t i = 0; i < muX.size(); ++i) {
    // Local variances and covariance as E[xy] - E[x]E[y] under the window's weights.
    double varX = eXX[i] - muX[i] * muX[i];
    double varY = eYY[i] - muY[i] * muY[i];
    double covXY = eXY[i] - muX[i] * muY[i];
    sum += ((2 * muX[i] * muY[i] + kC1) * (2 * covXY + kC2)) /
           ((muX[i] * muX[i] + muY[i] * muY[i] + kC1) * (varX + varY + kC2));
  }
  return sum / double(muX.size());
}

}  // namespace

double psnr(const Image& a, const Image& b) {
  requireSameShape(a, b, "PSNR");
  if (a.pixels.empty()) throw Error("PSNR: the images are empty");
  double sum = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    double d = double(a.pixels[i]) - double(b.pixels[i]);
    sum += d * d;
  }
  double mse = sum / double(a.pixels.size());
  if (mse == 0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(1.0 / mse);
}

double ssim(const Image& a, const Image& b) {
  requireSameShape(a, b, "SSIM");
  if (a.width < kWindowSize || a.height < kWindowSize)
    throw Error("SSIM: images of " + describeShape(a) + " are smaller than the 11x11 window");
  double sum = 0;
  for (int c = 0; c < a.channels; ++c) sum += ssimChannel(a, b, c);
  return sum / a.channels;
}

Image tonemapTo8Bit(const Image& linear, Transfer transfer) {
  Image out = linear;
  for (float& v : out.pixels) v = std::round(std::clamp(toDisplay(transfer, v), 0.0f, 1.0f) * 255.0f) / 255.0f;
  return out;
}

double psnrTonemapped8Bit(const Image& a, const Image& b, Transfer transfer) {
  requireSameShape(a, b, "PSNR (tonemapped 8-bit)");
  return psnr(tonemapTo8Bit(a, transfer), tonemapTo8Bit(b, transfer));
}

double ssimTonemapped8Bit(const Image& a, const Image& b, Transfer transfer) {
  requireSameShape(a, b, "SSIM (tonemapped 8-bit)");
  return ssim(tonemapTo8Bit(a, transfer), tonemapTo8Bit(b, transfer));
}

double depthRmse(const Image& predictedDepth, const Image& truthDepth) {
  requireChannels(predictedDepth, 1, "depth RMSE (prediction)");
  requireChannels(truthDepth, 1, "depth RMSE (ground truth)");
  requireSameSize(predictedDepth, truthDepth, "depth RMSE");
  double sum = 0;
  size_t count = 0;
  for (size_t i = 0; i < truthDepth.pixels.size(); ++i) {
    if (!hasSurface(truthDepth.pixels[i])) continue;
    double d = double(predictedDepth.pixels[i]) - double(truthDepth.pixels[i]);
    sum += d * d;
    ++count;
  }
  if (count == 0) return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(sum / double(count));
}

double normalAngleDegrees(const Image& predictedNormal, const Image& truthNormal, const Image& truthDepth) {
  requireChannels(predictedNormal, 3, "normal angle (prediction)");
  requireChannels(truthNormal, 3, "normal angle (ground truth)");
  requireChannels(truthDepth, 1, "normal angle (ground-truth depth)");
  requireSameSize(predictedNormal, truthNormal, "normal angle");
  requireSameSize(truthNormal, truthDepth, "normal angle (normal vs depth)");
  double sum = 0;
  size_t count = 0;
  for (int y = 0; y < truthNormal.height; ++y)
    for (int x = 0; x < truthNormal.width; ++x) {
      if (!hasSurface(truthDepth.at(x, y))) continue;
      Vec3d truth = Vec3d(truthNormal.rgb(x, y));
      if (dot(truth, truth) == 0) continue;
      Vec3d predicted = Vec3d(predictedNormal.rgb(x, y));
      double degrees = 90.0;
      if (dot(predicted, predicted) > 0) {
        // atan2 of |cross| and dot is accurate near 0 and 180 degrees, where acos is not.
        Vec3d p = normalize(predicted), t = normalize(truth);
        degrees = std::atan2(length(cross(p, t)), dot(p, t)) * (180.0 / std::numbers::pi);
      }
      sum += degrees;
      ++count;
    }
  if (count == 0) return std::numeric_limits<double>::quiet_NaN();
  return sum / double(count);
}

}  // namespace glint
