// Evaluates the named selections of an edit document on a Gaussian scene: which Gaussians
// (by their mean) lie in a shape, pass the attribute filters, or belong to a combination.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "edit/edit_document.h"
#include "scene/gaussians.h"

namespace glint {

// One byte per Gaussian (1 = selected): unlike std::vector<bool>, threads may write
// different entries at once.
using GaussianMask = std::vector<uint8_t>;

// The Gaussians of `scene` that selection `name` of `document` holds. The document must be
// valid (parseEditDocument): names resolve and combinations have no cycles.
GaussianMask selectGaussians(const EditDocument& document, const std::string& name, const GaussianScene& scene);

// True when Gaussian i passes the filter (mean F0, roughness, mean diffuse or the derived
// metalness within [lo, hi]).
bool passesFilter(const AttributeFilter& filter, const GaussianScene& scene, size_t i);

// How many entries of the mask are set.
size_t countSelected(const GaussianMask& mask);

}  // namespace glint
