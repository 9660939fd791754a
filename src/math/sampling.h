// Warps from the unit square to directions and points, their densities, and tabulated
// discrete / piecewise-constant distributions for importance sampling.
#pragma once

#include <cstddef>
#include <vector>

#include "math/vec.h"

namespace glint {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 0.31830988618379067154f;
constexpr float kInv4Pi = 0.07957747154594766788f;

// Cosine-weighted hemisphere around +z (Malley's method on a concentric disk).
Vec3f sampleCosineHemisphere(Vec2f u);
inline float cosineHemispherePdf(float cosTheta) { return cosTheta > 0 ? cosTheta * kInvPi : 0.0f; }

// Uniform direction on the unit sphere.
Vec3f sampleUniformSphere(Vec2f u);
constexpr float uniformSpherePdf() { return kInv4Pi; }

// Uniform point in the unit disk (Shirley-Chiu concentric map).
Vec2f sampleConcentricDisk(Vec2f u);

// Uniform barycentrics (b0, b1) on a triangle; b2 = 1 - b0 - b1.
Vec2f sampleUniformTriangle(Vec2f u);

// Direction inside a cone of half-angle acos(cosThetaMax) around +z, uniform in solid angle.
Vec3f sampleUniformCone(Vec2f u, float cosThetaMax);
inline float uniformConePdf(float cosThetaMax) { return 1.0f / (2.0f * kPi * (1.0f - cosThetaMax)); }

// Veach's power heuristic with beta = 2 for multiple importance sampling.
inline float powerHeuristic(float pdfA, float pdfB) {
  float a = pdfA * pdfA, b = pdfB * pdfB;
  return a + b > 0 ? a / (a + b) : 0.0f;
}

// Discrete distribution proportional to non-negative weights (CDF + binary search).
class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(std::vector<float> weights);

  size_t size() const { return weights_.size(); }
  float total() const { return total_; }
  // Samples an index; u in [0,1). Also returns its probability and the remapped u
  // (uniform again within the chosen bin), for reuse as a continuous sample.
  size_t sample(float u, float* probability = nullptr, float* remapped = nullptr) const;
  float probability(size_t index) const { return total_ > 0 ? weights_[index] / total_ : 0.0f; }

 private:
  std::vector<float> weights_;
  std::vector<double> cdf_;  // size n + 1, cdf_[n] == 1
  float total_ = 0;
};

// Piecewise-constant 2D distribution over [0,1)^2 (rows are v, columns are u), for
// environment maps: marginal over rows, conditional within each row.
class Distribution2D {
 public:
  Distribution2D() = default;
  Distribution2D(const std::vector<float>& weights, int width, int height);

  // Returns a point in [0,1)^2 and its density with respect to area on the unit square.
  Vec2f sample(Vec2f u, float* pdf) const;
  float pdf(Vec2f p) const;
  bool empty() const { return width_ == 0; }

 private:
  int width_ = 0, height_ = 0;
  std::vector<Distribution1D> rows_;
  Distribution1D marginal_;
};

}  // namespace glint
