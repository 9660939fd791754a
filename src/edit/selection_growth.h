// Growing a Gaussian selection along connected Gaussians of similar material (the "grow"
// of an edit file's selections; edit_document.h, SelectionGrowth).
#pragma once

#include "edit/edit_document.h"
#include "edit/gaussian_selection.h"
#include "scene/gaussians.h"

namespace glint {

// Adds to mask, until nothing more joins, every Gaussian whose centre lies within
// growth.distance of a selected Gaussian of similar material (mean diffuse, mean F0 and
// roughness each within growth.tolerance of that neighbour's). Deterministic: the result
// does not depend on the order of the search.
void growSelection(const SelectionGrowth& growth, const GaussianScene& scene, GaussianMask& mask);

}  // namespace glint
