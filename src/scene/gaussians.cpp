// GaussianScene bookkeeping: resizing, appending, filtering.
#include "scene/gaussians.h"

#include <cmath>

#include "core/error.h"

namespace glint {

void GaussianScene::resize(size_t n) {
  position.resize(n, Vec3f(0.0f));
  rotation.resize(n, Quatf{});
  logScale.resize(n, Vec3f(0.0f));
  opacityLogit.resize(n, 0.0f);
  diffuse.resize(n, Rgb(0.0f));
  normal.resize(n, Vec3f(0.0f));
  roughness.resize(n, 0.0f);
  f0.resize(n, Rgb(0.04f));
}

void GaussianScene::append(const GaussianScene& other, size_t i) {
  GLINT_CHECK(i < other.size(), "append: index out of range");
  position.push_back(other.position[i]);
  rotation.push_back(other.rotation[i]);
  logScale.push_back(other.logScale[i]);
  opacityLogit.push_back(other.opacityLogit[i]);
  diffuse.push_back(other.diffuse[i]);
  normal.push_back(other.normal[i]);
  roughness.push_back(other.roughness[i]);
  f0.push_back(other.f0[i]);
}

namespace {
template <typename T>
void keepSelected(std::vector<T>& values, const std::vector<bool>& keep) {
  size_t out = 0;
  for (size_t i = 0; i < values.size(); ++i)
    if (keep[i]) values[out++] = values[i];
  values.resize(out);
}
}  // namespace

void GaussianScene::filter(const std::vector<bool>& keep) {
  GLINT_CHECK(keep.size() == size(), "filter: mask size differs from the scene");
  keepSelected(position, keep);
  keepSelected(rotation, keep);
  keepSelected(logScale, keep);
  keepSelected(opacityLogit, keep);
  keepSelected(diffuse, keep);
  keepSelected(normal, keep);
  keepSelected(roughness, keep);
  keepSelected(f0, keep);
}

bool GaussianScene::consistent() const {
  size_t n = position.size();
  return rotation.size() == n && logScale.size() == n && opacityLogit.size() == n && diffuse.size() == n &&
         normal.size() == n && roughness.size() == n && f0.size() == n;
}

float GaussianScene::opacity(size_t i) const { return sigmoid(opacityLogit[i]); }

Vec3f GaussianScene::scale(size_t i) const {
  const Vec3f& s = logScale[i];
  return {std::exp(s.x), std::exp(s.y), std::exp(s.z)};
}

}  // namespace glint
