// Material defaults for Gaussians imported from a standard 3DGS file, which carries no
// normals, roughness or F0: a rough dielectric whose normals follow each Gaussian's shape.
#pragma once

#include "math/quat.h"
#include "math/vec.h"
#include "scene/gaussians.h"

namespace glint {

// Rough enough that an imported splat shows no sharp reflections (Glint's own painted walls
// are 0.9), with a common dielectric's 4% reflectance at normal incidence.
inline constexpr float kImportedRoughness = 0.9f;
inline constexpr float kImportedF0 = 0.04f;

// The unit direction of the Gaussian's shortest axis in world space: the column of its
// rotation matrix with the smallest scale (the first of equal ones). A flat splat's normal.
Vec3f shortestAxis(const Quatf& rotation, const Vec3f& logScale);

// The per-axis median of the Gaussians' positions: a centre that the sparse far-away
// background of a capture does not pull about as the mean would. Zero for an empty scene.
Vec3f medianPosition(const GaussianScene& scene);

// Sets every normal to the Gaussian's shortest axis, flipped to point away from `centre`
// (kept as is when the position lies on the axis's plane through the centre).
void setShortestAxisNormals(GaussianScene& scene, const Vec3f& centre);

}  // namespace glint
