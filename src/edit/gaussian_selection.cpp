// Selections are evaluated into masks in the order of a SelectionPlan (each reached
// selection once); shape tests and filters run in parallel over the Gaussians, since trained
// scenes hold millions of them.
#include "edit/gaussian_selection.h"

#include "core/error.h"
#include "core/parallel.h"
#include "edit/selection_growth.h"
#include "edit/selection_plan.h"
#include "edit/shape.h"

namespace glint {

namespace {

constexpr int64_t kGrain = 4096;

// One selection's mask from its operands' masks, then its filters.
GaussianMask evaluateSelection(const Selection& selection, const std::vector<const GaussianMask*>& operands,
                               const GaussianScene& scene) {
  size_t n = scene.size();
  GaussianMask mask;
  switch (selection.kind) {
    case Selection::Kind::Everything: mask.assign(n, 1); break;
    case Selection::Kind::Shape:
      mask.assign(n, 0);
      parallelFor(int64_t(n), kGrain, [&](int64_t i) { mask[i] = shapeContains(selection.shape, scene.position[i]); });
      break;
    case Selection::Kind::Union:
    case Selection::Kind::Intersection:
    case Selection::Kind::Difference:
      mask = *operands.at(0);
      for (size_t k = 1; k < operands.size(); ++k) {
        const GaussianMask& other = *operands[k];
        for (size_t i = 0; i < n; ++i) {
          if (selection.kind == Selection::Kind::Union) mask[i] |= other[i];
          else if (selection.kind == Selection::Kind::Intersection) mask[i] &= other[i];
          else mask[i] &= !other[i];
        }
      }
      break;
  }
  if (!selection.filters.empty()) {
    parallelFor(int64_t(mask.size()), kGrain, [&](int64_t i) {
      for (const AttributeFilter& filter : selection.filters)
        if (mask[i] && !passesFilter(filter, scene, size_t(i))) mask[i] = 0;
    });
  }
  if (selection.grow.distance > 0) growSelection(selection.grow, scene, mask);
  return mask;
}

}  // namespace

bool passesFilter(const AttributeFilter& filter, const GaussianScene& scene, size_t i) {
  return filterAccepts(filter, scene.f0[i], scene.roughness[i], scene.diffuse[i]);
}

GaussianMask selectGaussians(const EditDocument& document, const std::string& name, const GaussianScene& scene) {
  return evaluatePlan<GaussianMask>(planSelection(document, name),
                                    [&](const Selection& selection, const std::vector<const GaussianMask*>& operands) {
                                      return evaluateSelection(selection, operands, scene);
                                    });
}

size_t countSelected(const GaussianMask& mask) {
  size_t count = 0;
  for (uint8_t m : mask) count += m;
  return count;
}

}  // namespace glint
