// GaussianScene bookkeeping: resizing, appending, filtering, each over every array of the
// parameter table (scene/gaussian_parameters.h).
#include "scene/gaussians.h"

#include <cmath>

#include "core/error.h"
#include "scene/gaussian_parameters.h"

namespace glint {

void GaussianScene::resize(size_t n) {
  forEachParameter([&](const auto& p) { (this->*p.values).resize(n, p.neutral); });
}

void GaussianScene::append(const GaussianScene& other, size_t i) {
  GLINT_CHECK(i < other.size(), "append: index out of range");
  forEachParameter([&](const auto& p) { (this->*p.values).push_back((other.*p.values)[i]); });
}

void GaussianScene::filter(const std::vector<bool>& keep) {
  GLINT_CHECK(keep.size() == size(), "filter: mask size differs from the scene");
  forEachParameter([&](const auto& p) { keepSelected(this->*p.values, keep); });
}

bool GaussianScene::consistent() const {
  bool same = true;
  forEachParameter([&](const auto& p) { same = same && (this->*p.values).size() == size(); });
  return same;
}

float GaussianScene::opacity(size_t i) const { return sigmoid(opacityLogit[i]); }

Vec3f GaussianScene::scale(size_t i) const {
  const Vec3f& s = logScale[i];
  return {std::exp(s.x), std::exp(s.y), std::exp(s.z)};
}

}  // namespace glint
