// A scene of 3D Gaussian primitives carrying physically-based attributes, in
// structure-of-arrays form (one contiguous array per parameter, as the optimiser and the
// tracer's builders stream over them). Index i of every array is Gaussian i.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "math/quat.h"
#include "math/vec.h"

namespace glint {

// Every array is also an entry of the parameter table (scene/gaussian_parameters.h), which
// the code that handles all parameters walks: a new array needs an entry there.
struct GaussianScene {
  std::vector<Vec3f> position;      // mean, world space
  std::vector<Quatf> rotation;      // (w, x, y, z); normalised on use
  std::vector<Vec3f> logScale;      // natural log of the standard deviations along the local axes
  std::vector<float> opacityLogit;  // opacity = sigmoid(opacityLogit)
  std::vector<Rgb> diffuse;         // linear diffuse colour (the paper's cached irradiance x albedo)
  std::vector<Vec3f> normal;        // attached normal (not necessarily unit; 0 = none)
  std::vector<float> roughness;     // perceptual roughness in [0, 1]
  std::vector<Rgb> f0;              // base reflectance in [0, 1]

  size_t size() const { return position.size(); }
  bool empty() const { return position.empty(); }
  // Resizes every array; new Gaussians get the table's neutral values (identity rotation,
  // zero scale logs, opacity 0.5, zero colour and normal, roughness 0, F0 0.04).
  void resize(size_t n);
  // Appends Gaussian `index` of `other`.
  void append(const GaussianScene& other, size_t index);
  // Keeps the Gaussians whose keep[i] is true, in order.
  void filter(const std::vector<bool>& keep);
  // True when every array has size() entries.
  bool consistent() const;

  float opacity(size_t i) const;
  Vec3f scale(size_t i) const;
};

inline float sigmoid(float x) { return 1.0f / (1.0f + std::exp(-x)); }
inline float logit(float p) { return std::log(p / (1.0f - p)); }

}  // namespace glint
