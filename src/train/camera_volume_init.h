// The initialisation of a dataset with neither depth buffers nor points (the NeRF-synthetic
// layout): Gaussians at random through the volume the training cameras look at, as 3D
// Gaussian Splatting starts its synthetic scenes, and a shell in the background colour.
#pragma once

#include "scene/dataset.h"
#include "train/dense_init.h"

namespace glint {

// The most Gaussians spread through the volume (3DGS's 100,000 random points); fewer for
// small datasets: one per kPixelsPerVolumeGaussian training pixels, at least 1,000.
inline constexpr int64_t kMaxVolumeGaussians = 100'000;
inline constexpr int64_t kPixelsPerVolumeGaussian = 8;
// Gaussians of the background shell (far enough out not to crowd training).
inline constexpr int kShellGaussians = 4000;

// Uniform random positions in a cube around the point nearest every training camera's
// optical axis, of half-edge 0.35 x the cameras' mean distance from it (1.4 for the
// NeRF-synthetic cameras 4 units out, where 3DGS uses 1.3), grey (0.5 linear), with the
// settings' opacity, roughness and F0. When the dataset composites its images over a
// non-black background (CaptureSource::alphaBackground), a shell of Gaussians of that
// colour at twice the farthest camera's distance lies behind everything every camera
// sees, so that the background is part of the scene any renderer shows, rather than a
// constant added by Glint's renderer alone; a black background is what a ray that leaves
// the Gaussians returns anyway. Deterministic.
DenseInit initInCameraVolume(const Dataset& dataset, const DenseInitSettings& settings);

}  // namespace glint
