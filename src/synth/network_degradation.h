// The documented "network-like" degradation of `glint synth --layout capture --degrade
// network`: what a monocular predictor's buffers typically get wrong, at stated amounts.
#pragma once

#include <cstdint>

#include "scene/buffer_degradation.h"
#include "scene/buffers.h"

namespace glint {

// The settings for one view of a width-pixel-wide image (pixel amounts are given per 320
// pixels of width and scale with it, so the error looks the same at every resolution):
// - blur: Gaussian, sigma 1 px, of every prior (G-buffers within surfaces; diffuse and
//   specular over the whole image);
// - depth: a per-view affine error d' = s d + o with s uniform in [0.95, 1.05] and o uniform
//   in [-0.1, 0.1] m, then Gaussian noise of 0.01 m;
// - normals: tilted by 4 degrees on average, the tilt field correlated over 3 px;
// - roughness: r' = clamp(0.8 (r + n) + 0.1, 0, 1), n Gaussian of 0.03, so 0.024 after the
//   scale (smooth surfaces look rougher, rough ones smoother, as regression to the mean does);
// - F0: the blur only.
// The view index and seed decide the random parts, so a dataset is reproducible.
BufferDegradation networkLikeDegradation(int width, uint64_t seed, uint64_t view);

// The priors of one view under networkLikeDegradation: degradeBuffers plus the blur of the
// diffuse and specular buffers. The render buffer (the photograph) stays exact.
ViewBuffers networkLikePriors(const ViewBuffers& exact, uint64_t seed, uint64_t view);

}  // namespace glint
