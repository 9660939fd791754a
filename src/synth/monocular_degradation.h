// The "monocular" degradation of `glint synth --layout capture --degrade monocular`: a second
// kind of predictor error beside network_degradation.h, made to differ from it where a
// single-image predictor differs from a smooth, affine one.
#pragma once

#include <cstdint>

#include "scene/buffers.h"

namespace glint {

// The amounts, for one view of a width-pixel-wide image (pixel amounts are per 160 pixels
// of width and scale with it):
// - diffuse and specular: blur of sigma 0.7 px over the whole image, then Gaussian noise of
//   kRadianceNoise in filmic display values (8-bit codes: about 1.5 steps);
// - depth: a view-dependent non-affine warp z' = zm (z / zm)^gamma, gamma uniform in
//   [0.85, 1.15] and zm the view's median depth, times a smooth field 1 + 0.04 f (f of unit
//   variance, correlated over 12 px), blurred by 1 px across depth edges (a predictor's
//   "flying pixels"), then noise of 0.5% of the depth: no per-view affine map can undo it;
// - normals: 3 degrees of mean tilt drawn per pixel (no correlation), plus one tilt of
//   1.5 degrees shared by the whole view (a camera-frame bias);
// - roughness: r' = clamp(r + 0.05 + n, 0, 1), n Gaussian of 0.05 (a bias, not a shrink);
// - F0: given as metalness only (the writer stores priors/metalness, no F0), so tinted
//   metals lose their tint as in captures whose predictor gives metalness.
constexpr double kRadianceNoise = 1.5 / 255.0;
struct MonocularDegradation {
  double radianceBlur = 0, radianceNoise = kRadianceNoise;
  double depthGamma = 1, depthFieldAmplitude = 0.04, depthFieldCorrelation = 0;
  double depthEdgeBlur = 0, depthRelativeNoise = 0.005;
  double normalMeanAngle = 0, normalViewTilt = 0;  // radians
  double roughnessOffset = 0.05, roughnessNoise = 0.05;
};
MonocularDegradation monocularDegradation(int width, uint64_t seed, uint64_t view);

// The priors of one view under monocularDegradation; the photograph (render) stays exact and
// F0 is left exact for the writer to turn into metalness.
ViewBuffers monocularPriors(const ViewBuffers& exact, uint64_t seed, uint64_t view);

}  // namespace glint
