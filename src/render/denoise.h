// A CPU denoiser for rendered views: the edge-avoiding a-trous wavelet filter of Dammertz
// et al. 2010 ("Edge-avoiding A-Trous wavelet transform for fast global illumination
// filtering"), guided by the albedo (diffuse), normal and depth buffers.
#pragma once

#include "io/image.h"
#include "scene/buffers.h"

namespace glint {

// Which part of the render the filter smooths. Measured on the glossy floor of
// tests/render/denoise_test.cpp (16 spp against 1024 spp): filtering the whole render
// gains 8.9 dB, the specular alone 7.0 dB. The diffuse buffer is not noise-free at 16 spp:
// the jittered sub-pixel positions land on different Gaussians, and the specular-only
// target keeps that noise; demodulating by F0 changes nothing for a uniform F0 (the colour
// distance is relative) and only blurs less across F0 edges.
enum class DenoiseTarget {
  Render,    // the whole render buffer: the default
  Specular,  // the specular buffer only, the diffuse buffer added back unfiltered
  // The specular buffer divided by max(F0, kMinDemodulationF0) before filtering and
  // multiplied back after, so that the reflectance's texture is not blurred.
  SpecularDemodulated,
};

struct DenoiseSettings {
  DenoiseTarget target = DenoiseTarget::Render;
  // Passes of the 5x5 B3-spline kernel; pass i spreads its taps 2^i pixels apart, so 5
  // passes reach 2 (1 + 2 + 4 + 8 + 16) = 62 pixels from the centre at 25 taps each.
  int iterations = 5;
  // Edge-stopping widths of exp(-|a - b|^2 / sigma^2). Colour differences are measured
  // relative to the centre pixel's brightness (root mean square of its channels, at least a
  // tenth of the image's mean value), as
  // Monte Carlo noise grows with the signal; Dammertz halves the width after every pass,
  // as the filtered colour gets smoother.
  float sigmaColor = 1.0f;
  float sigmaNormal = 0.3f;   // between unit normals (|a - b| = 0.3 is about 17 degrees)
  float sigmaDepth = 0.05f;   // relative depth difference |a - b| / a
  float sigmaAlbedo = 0.05f;  // between diffuse colours (absolute, they lie in [0, 1])
};

constexpr float kMinDemodulationF0 = 0.02f;

// The filtered final image of a view (3 channels): settings.target of buffers filtered with
// the guides buffers[Diffuse], [Normal] and [Depth] (pixels with no surface, depth 0, only
// mix with each other), plus the unfiltered diffuse when the target is specular.
Image denoiseView(const ViewBuffers& buffers, const DenoiseSettings& settings = {});

// The filter itself: colour (3 channels) smoothed under the guides, each the same size as
// colour (albedo and normal 3 channels, depth 1).
Image atrousFilter(const Image& colour, const Image& albedo, const Image& normal, const Image& depth,
                   const DenoiseSettings& settings);

}  // namespace glint
