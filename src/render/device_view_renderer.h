// The per-pixel sums of a view's samples, and the interface of a tracer that computes them
// on its own device (the GPU): renderGaussianView then averages them as it does the CPU's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "math/vec.h"
#include "render/gaussian_renderer.h"
#include "scene/camera.h"

namespace glint {

// Sums over samples of the per-path outputs of a band of pixels (row-major, the band's
// first row first), in structure-of-arrays form.
struct PixelSums {
  std::vector<Rgb> diffuse, specular, normal, f0;
  std::vector<float> depth, roughness;
  std::vector<std::vector<Rgb>> bounces;  // [k][pixel]: the light of reflected segment k + 1

  void reset(size_t pixels, int separate) {
    diffuse.assign(pixels, Rgb(0.0f));
    specular.assign(pixels, Rgb(0.0f));
    normal.assign(pixels, Rgb(0.0f));
    f0.assign(pixels, Rgb(0.0f));
    depth.assign(pixels, 0.0f);
    roughness.assign(pixels, 0.0f);
    bounces.resize(size_t(separate));
    for (auto& b : bounces) b.assign(pixels, Rgb(0.0f));
  }
  // The same sizes, not cleared: for a caller that writes every element (a download).
  void resize(size_t pixels, int separate) {
    for (auto* v : {&diffuse, &specular, &normal, &f0}) v->resize(pixels);
    depth.resize(pixels);
    roughness.resize(pixels);
    bounces.resize(size_t(separate));
    for (auto& b : bounces) b.resize(pixels);
  }
};

class DeviceViewRenderer {
 public:
  virtual ~DeviceViewRenderer() = default;
  // Sums samples firstSample .. firstSample + spp - 1 of every pixel of rows [rowBegin,
  // rowEnd) into *sums (sized to the band, with `separate` bounce images), sample by
  // sample, with the paths, random numbers and order of additions of the CPU loop.
  virtual void sumView(const Camera& camera, const RenderSettings& settings, uint64_t viewKey, int rowBegin,
                       int rowEnd, int separate, PixelSums* sums) const = 0;
};

}  // namespace glint
