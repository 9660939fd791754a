// Gradient accumulators: sizing, clearing, filtering and the per-range reduction, each over
// every parameter's float array.
#include "raytrace/gaussian_gradients.h"

#include <algorithm>

#include "core/error.h"

namespace glint {

void GaussianGradients::reset(size_t n) {
  forEachParameter([&](const auto& p) { values[p.index].assign(n * p.components, 0.0f); });
  weight.assign(n, 0.0f);
}

void GaussianGradients::grow(size_t n) {
  GLINT_CHECK(n >= size(), "GaussianGradients::grow cannot shrink");
  // resize value-initialises the new floats: zero.
  forEachParameter([&](const auto& p) { values[p.index].resize(n * p.components); });
  weight.resize(n);
}

void GaussianGradients::zero(size_t begin, size_t end) {
  forEachParameter([&](const auto& p) {
    std::vector<float>& v = values[p.index];
    std::fill(v.begin() + begin * p.components, v.begin() + end * p.components, 0.0f);
  });
  std::fill(weight.begin() + begin, weight.begin() + end, 0.0f);
}

void GaussianGradients::filter(const std::vector<bool>& keep) {
  GLINT_CHECK(keep.size() == size(), "keep mask must match the gradient arrays");
  forEachParameter([&](const auto& p) { keepSelected(values[p.index], keep, p.components); });
  keepSelected(weight, keep);
}

void GaussianGradients::appendCopies(std::span<const uint32_t> from) {
  const size_t n = size();
  for (uint32_t i : from) GLINT_CHECK(i < n, "appendCopies: index out of range");
  forEachParameter([&](const auto& p) {
    std::vector<float>& v = values[p.index];
    v.resize((n + from.size()) * p.components);
    for (size_t k = 0; k < from.size(); ++k)
      std::copy_n(v.begin() + from[k] * p.components, p.components, v.begin() + (n + k) * p.components);
  });
  weight.resize(n + from.size());
  for (size_t k = 0; k < from.size(); ++k) weight[n + k] = weight[from[k]];
}

namespace {
// to[j] += from[j] over [begin, end): one contiguous loop the compiler vectorises.
void addFloats(std::vector<float>& to, const std::vector<float>& from, size_t begin, size_t end) {
  float* t = to.data();
  const float* f = from.data();
  for (size_t j = begin; j < end; ++j) t[j] += f[j];
}
}  // namespace

void GaussianGradients::addRange(const GaussianGradients& o, size_t begin, size_t end) {
  forEachParameter([&](const auto& p) {
    addFloats(values[p.index], o.values[p.index], begin * p.components, end * p.components);
  });
  addFloats(weight, o.weight, begin, end);
}

}  // namespace glint
