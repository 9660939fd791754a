// Gradient accumulators: sizing, clearing and the per-range reduction.
#include "raytrace/gaussian_gradients.h"

#include <algorithm>

#include "core/error.h"

namespace glint {

void GaussianGradients::reset(size_t n) {
  position.assign(n, Vec3f(0.0f));
  rotation.assign(n, Quatf{0, 0, 0, 0});
  logScale.assign(n, Vec3f(0.0f));
  opacityLogit.assign(n, 0.0f);
  diffuse.assign(n, Rgb(0.0f));
  normal.assign(n, Vec3f(0.0f));
  roughness.assign(n, 0.0f);
  f0.assign(n, Rgb(0.0f));
  weight.assign(n, 0.0f);
}

void GaussianGradients::grow(size_t n) {
  GLINT_CHECK(n >= size(), "GaussianGradients::grow cannot shrink");
  const size_t old = size();
  position.resize(n);
  rotation.resize(n);
  logScale.resize(n);
  opacityLogit.resize(n);
  diffuse.resize(n);
  normal.resize(n);
  roughness.resize(n);
  f0.resize(n);
  weight.resize(n);
  zero(old, n);
}

void GaussianGradients::zero(size_t begin, size_t end) {
  std::fill(position.begin() + begin, position.begin() + end, Vec3f(0.0f));
  std::fill(rotation.begin() + begin, rotation.begin() + end, Quatf{0, 0, 0, 0});
  std::fill(logScale.begin() + begin, logScale.begin() + end, Vec3f(0.0f));
  std::fill(opacityLogit.begin() + begin, opacityLogit.begin() + end, 0.0f);
  std::fill(diffuse.begin() + begin, diffuse.begin() + end, Rgb(0.0f));
  std::fill(normal.begin() + begin, normal.begin() + end, Vec3f(0.0f));
  std::fill(roughness.begin() + begin, roughness.begin() + end, 0.0f);
  std::fill(f0.begin() + begin, f0.begin() + end, Rgb(0.0f));
  std::fill(weight.begin() + begin, weight.begin() + end, 0.0f);
}

void GaussianGradients::addRange(const GaussianGradients& o, size_t begin, size_t end) {
  for (size_t i = begin; i < end; ++i) {
    position[i] += o.position[i];
    rotation[i].w += o.rotation[i].w;
    rotation[i].x += o.rotation[i].x;
    rotation[i].y += o.rotation[i].y;
    rotation[i].z += o.rotation[i].z;
    logScale[i] += o.logScale[i];
    opacityLogit[i] += o.opacityLogit[i];
    diffuse[i] += o.diffuse[i];
    normal[i] += o.normal[i];
    roughness[i] += o.roughness[i];
    f0[i] += o.f0[i];
    weight[i] += o.weight[i];
  }
}

}  // namespace glint
