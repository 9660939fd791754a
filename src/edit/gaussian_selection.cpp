// Selections are evaluated recursively into masks; shape tests and filters run in parallel
// over the Gaussians, since trained scenes hold millions of them.
#include "edit/gaussian_selection.h"

#include "core/error.h"
#include "core/parallel.h"
#include "edit/shape.h"

namespace glint {

namespace {

constexpr int64_t kGrain = 4096;

// The selection before its filters.
GaussianMask unfiltered(const EditDocument& document, const Selection& selection, const GaussianScene& scene) {
  size_t n = scene.size();
  switch (selection.kind) {
    case Selection::Kind::Everything: return GaussianMask(n, 1);
    case Selection::Kind::Shape: {
      GaussianMask mask(n, 0);
      parallelFor(int64_t(n), kGrain, [&](int64_t i) { mask[i] = shapeContains(selection.shape, scene.position[i]); });
      return mask;
    }
    case Selection::Kind::Union:
    case Selection::Kind::Intersection:
    case Selection::Kind::Difference: break;
  }
  GaussianMask mask = selectGaussians(document, selection.operands.at(0), scene);
  for (size_t k = 1; k < selection.operands.size(); ++k) {
    GaussianMask other = selectGaussians(document, selection.operands[k], scene);
    for (size_t i = 0; i < n; ++i) {
      if (selection.kind == Selection::Kind::Union) mask[i] |= other[i];
      else if (selection.kind == Selection::Kind::Intersection) mask[i] &= other[i];
      else mask[i] &= !other[i];
    }
  }
  return mask;
}

}  // namespace

bool passesFilter(const AttributeFilter& filter, const GaussianScene& scene, size_t i) {
  return filterAccepts(filter, scene.f0[i], scene.roughness[i], scene.diffuse[i]);
}

GaussianMask selectGaussians(const EditDocument& document, const std::string& name, const GaussianScene& scene) {
  auto it = document.selections.find(name);
  GLINT_CHECK(it != document.selections.end(), "selectGaussians: unknown selection " + name);
  const Selection& selection = it->second;
  GaussianMask mask = unfiltered(document, selection, scene);
  if (!selection.filters.empty()) {
    parallelFor(int64_t(mask.size()), kGrain, [&](int64_t i) {
      for (const AttributeFilter& filter : selection.filters)
        if (mask[i] && !passesFilter(filter, scene, size_t(i))) mask[i] = 0;
    });
  }
  return mask;
}

size_t countSelected(const GaussianMask& mask) {
  size_t count = 0;
  for (uint8_t m : mask) count += m;
  return count;
}

}  // namespace glint
