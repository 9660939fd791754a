// Baking Glint's path-traced reflections into spherical-harmonics colours that a plain 3D
// Gaussian Splatting viewer shows: per Gaussian, the display-referred radiance leaving it in
// sampled directions, fitted by SH of degree 1-3 (docs/derivations.md, "Baking reflections").
#pragma once

#include <cstdint>
#include <vector>

#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_path.h"
#include "scene/camera.h"
#include "scene/gaussians.h"
#include "scene/splat_colour.h"

namespace glint {

struct ShBakeSettings {
  int degree = 3;       // 1..3 (0 fits a constant)
  int directions = 64;  // rays traced through each Gaussian
  // Ridge lambda on the view-dependent coefficients, relative to the samples' total weight
  // (math/sh_fit.h): what the samples leave open falls back to a constant colour.
  double ridge = 0.005;
  float exposure = 1.0f;  // radiance is scaled by this before the tonemap
  uint64_t seed = 0;
  PathSettings path;  // how radiance is traced: the scene's render settings
  // The dataset's cameras: a Gaussian is sampled from the directions in which the cameras
  // that have it in view see it (each ray from a random point near one such camera). A
  // Gaussian no camera sees, or every Gaussian when this is empty, is sampled over the
  // whole sphere.
  std::vector<Camera> cameras;
};

// The SplatColour of every Gaussian (degree settings.degree). For Gaussian i and each
// sampled direction d, a path is traced along d from just outside the Gaussian's 3-sigma
// ellipsoid through its mean; its radiance L (diffuse plus specular of
// settings.path.bounces reflections) becomes the display-referred target
// y = tonemapFilmic(exposure L) / (1 - T_f), T_f the ray's remaining transmittance, so that
// a viewer blending y with the ray's weights shows tonemapFilmic(exposure L) there. The
// sample's weight is the Gaussian's own blending weight w_i = T_i alpha_i on the ray (how
// much of what is seen from d it makes). A Gaussian that no ray sees keeps the tonemapped
// diffuse colour and zero SH. Parallel over Gaussians, with a progress bar; deterministic
// for a given seed.
SplatColour bakeReflections(const GaussianScene& scene, const GaussianTracer& tracer, const ShBakeSettings& settings);

}  // namespace glint
