// A CPU denoiser for rendered views: the edge-avoiding a-trous wavelet filter of Dammertz
// et al. 2010 ("Edge-avoiding A-Trous wavelet transform for fast global illumination
// filtering"), guided by the albedo (diffuse), normal and depth buffers.
#pragma once

#include "io/image.h"
#include "scene/buffers.h"

namespace glint {

// Which part of the render the filter smooths (measured in README "Offline rendering").
enum class DenoiseTarget {
  // The whole render buffer.
  Render,
  // The specular buffer only; the diffuse buffer, which comes from the first segment and
  // so carries no path-tracing noise, is added back unfiltered. The default: it wins.
  Specular,
  // The specular buffer divided by max(F0, kMinDemodulationF0) before filtering and
  // multiplied back after, so that the reflectance's texture is not blurred.
  SpecularDemodulated,
};

struct DenoiseSettings {
  DenoiseTarget target = DenoiseTarget::Specular;
  // Passes of the 5x5 B3-spline kernel; pass i spreads its taps 2^i pixels apart, so 5
  // passes reach 2 (1 + 2 + 4 + 8 + 16) = 62 pixels from the centre at 25 taps each.
  int iterations = 5;
  // Edge-stopping widths of exp(-|a - b|^2 / sigma^2). Colour differences are measured
  // relative to the mean luminance of the filtered image, so the width does not depend on
  // exposure; Dammertz halves it after every pass, as the filtered colour gets smoother.
  float sigmaColor = 0.6f;
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
