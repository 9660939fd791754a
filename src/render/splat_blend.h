// The colour a plain 3D Gaussian Splatting viewer blends along a ray: each hit Gaussian's
// SH colour for its own viewing direction, composited front to back with the tracer's
// alphas, without any reflection. Used to measure baked colours against Glint's renders.
#pragma once

#include "math/vec.h"
#include "raytrace/ray_result.h"
#include "scene/gaussians.h"
#include "scene/splat_colour.h"

namespace glint {

// sum_i T_i alpha_i max(c_i(d_i), 0) over the hits in order, T_i the product of (1 - alpha)
// before hit i, c_i the SplatColour of Gaussian i for d_i = normalize(mu_i - eye): the
// direction 3DGS evaluates SH in (from the camera centre to the Gaussian's mean).
Rgb blendSplatColour(const GaussianScene& scene, const SplatColour& colour, const Vec3f& eye, const HitList& hits);

// c_i(d) = base_i + sum_{k >= 1} sh_ik B_k(d) for a unit direction d.
Rgb splatColourAt(const SplatColour& colour, size_t i, const Vec3f& d);

}  // namespace glint
