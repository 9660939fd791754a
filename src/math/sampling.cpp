// Sample warps and tabulated distributions (pbrt-v4 chapter A.5 describes the same maps).
#include "math/sampling.h"

#include <algorithm>
#include <cmath>

namespace glint {

Vec2f sampleConcentricDisk(Vec2f u) {
  float ox = 2.0f * u.x - 1.0f, oy = 2.0f * u.y - 1.0f;
  if (ox == 0 && oy == 0) return {0, 0};
  float r, theta;
  if (std::abs(ox) > std::abs(oy)) {
    r = ox;
    theta = (kPi / 4) * (oy / ox);
  } else {
    r = oy;
    theta = kPi / 2 - (kPi / 4) * (ox / oy);
  }
  return {r * std::cos(theta), r * std::sin(theta)};
}

Vec3f sampleCosineHemisphere(Vec2f u) {
  Vec2f d = sampleConcentricDisk(u);
  float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}

Vec3f sampleUniformSphere(Vec2f u) {
  float z = 1.0f - 2.0f * u.x;
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec2f sampleUniformTriangle(Vec2f u) {
  // Heitz 2019, "A Low-Distortion Map Between Triangle and Square".
  float b0, b1;
  if (u.x < u.y) {
    b0 = u.x / 2;
    b1 = u.y - b0;
  } else {
    b1 = u.y / 2;
    b0 = u.x - b1;
  }
  return {b0, b1};
}

Vec3f sampleUniformCone(Vec2f u, float cosThetaMax) {
  float cosTheta = (1.0f - u.x) + u.x * cosThetaMax;
  float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
  float phi = 2.0f * kPi * u.y;
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

Distribution1D::Distribution1D(std::vector<float> weights) : weights_(std::move(weights)) {
  cdf_.resize(weights_.size() + 1);
  cdf_[0] = 0;
  double sum = 0;
  for (size_t i = 0; i < weights_.size(); ++i) {
    weights_[i] = std::max(0.0f, weights_[i]);
    sum += weights_[i];
    cdf_[i + 1] = sum;
  }
  total_ = static_cast<float>(sum);
  if (sum > 0) {
    for (double& c : cdf_) c /= sum;
  } else {
    // All-zero weights: fall back to uniform so sampling stays defined.
    for (size_t i = 0; i < cdf_.size(); ++i) cdf_[i] = weights_.empty() ? 0 : double(i) / weights_.size();
  }
  if (!cdf_.empty()) cdf_.back() = 1.0;
}

size_t Distribution1D::sample(float u, float* probability, float* remapped) const {
  // First bin whose upper CDF edge exceeds u; zero-width bins are never chosen.
  auto it = std::upper_bound(cdf_.begin() + 1, cdf_.end(), double(u));
  size_t index = std::min<size_t>(std::distance(cdf_.begin() + 1, it), weights_.size() - 1);
  double width = cdf_[index + 1] - cdf_[index];
  if (probability) *probability = static_cast<float>(width);
  if (remapped) *remapped = width > 0 ? std::clamp(float((u - cdf_[index]) / width), 0.0f, 0x1.fffffep-1f) : 0.0f;
  return index;
}

Distribution2D::Distribution2D(const std::vector<float>& weights, int width, int height)
    : width_(width), height_(height) {
  std::vector<float> rowSums(height);
  rows_.reserve(height);
  for (int y = 0; y < height; ++y) {
    std::vector<float> row(weights.begin() + size_t(y) * width, weights.begin() + size_t(y + 1) * width);
    rows_.emplace_back(row);
    rowSums[y] = rows_.back().total();
  }
  marginal_ = Distribution1D(rowSums);
}

Vec2f Distribution2D::sample(Vec2f u, float* pdf) const {
  float pRow, pCol, uy, ux;
  size_t row = marginal_.sample(u.y, &pRow, &uy);
  size_t col = rows_[row].sample(u.x, &pCol, &ux);
  if (pdf) *pdf = pRow * pCol * float(width_) * float(height_);
  return {(float(col) + ux) / float(width_), (float(row) + uy) / float(height_)};
}

float Distribution2D::pdf(Vec2f p) const {
  int col = std::clamp(int(p.x * width_), 0, width_ - 1);
  int row = std::clamp(int(p.y * height_), 0, height_ - 1);
  return marginal_.probability(row) * rows_[row].probability(col) * float(width_) * float(height_);
}

}  // namespace glint
