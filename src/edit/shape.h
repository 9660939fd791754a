// Point-in-region tests for the shapes of edit selections (box, sphere, elliptic cylinder),
// shared by the Gaussian and the mesh sides of editing.
#pragma once

#include "edit/edit_document.h"

namespace glint {

// True when p lies inside (or on the boundary of) the shape.
bool shapeContains(const Shape& shape, const Vec3f& p);

// The derived metalness of docs/edit-files.md from mean diffuse d and mean F0 F:
// clamp((F - 0.04) / (F - 0.04 + d), 0, 1); 0 when both terms vanish.
float derivedMetalness(float meanDiffuse, float meanF0);

// True when a primitive with these attributes passes the filter: the mean F0, the
// roughness, the mean diffuse or the derived metalness lies in [lo, hi].
bool filterAccepts(const AttributeFilter& filter, const Rgb& F0, float roughness, const Rgb& diffuse);

}  // namespace glint
