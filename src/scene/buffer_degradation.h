// Degradations that make exact buffers look like a network's predictions (blur, noise, a
// per-view depth scale and offset, tilted normals, biased roughness), to build test data
// for real-capture training from synthetic scenes. Each is deterministic given its seed.
#pragma once

#include <cstdint>

#include "io/image.h"
#include "scene/buffers.h"

namespace glint {

// Separable Gaussian blur of every channel, sigma in pixels (0 returns the image as it is).
// The kernel reaches 3 sigma; borders repeat the edge pixel.
Image gaussianBlur(const Image& image, double sigma);

// The blur of `image` using only pixels where depth has a surface; other pixels keep their
// values, so "no surface" never bleeds into surfaces nor surfaces into the background (but
// nearer and farther surfaces mix across depth edges).
Image blurSurfaces(const Image& image, const Image& depth, double sigma);

// Adds independent zero-mean Gaussian noise of standard deviation sigma to every value; the
// noise of value (pixel, channel) depends only on (seed, pixel, channel).
Image addGaussianNoise(const Image& image, double sigma, uint64_t seed);

// A field of unit-variance Gaussian values per pixel and channel, depending only on (seed,
// pixel, channel): white for correlation 0, else blurred with that sigma in pixels and
// rescaled to unit variance (away from the borders).
Image smoothGaussianField(int width, int height, int channels, uint64_t seed, double correlation);

// A per-view affine depth error, d' = scale d + offset, on surface pixels only ("no
// surface" values are kept; a result <= 0 becomes 0, no surface).
Image affineDepthError(const Image& depth, double scale, double offset);

// Tilts every unit normal by a random angle whose mean is meanAngle (radians) in a random
// direction; zero normals stay zero. The tilt is a 3D Gaussian vector field projected on
// each normal's tangent plane, with angle proportional to its length (Rayleigh
// distributed). correlationPixels = 0 draws the field per pixel; > 0 blurs it with that
// sigma first (and rescales it to unit variance), giving smooth errors like a network's.
Image perturbNormals(const Image& normals, double meanAngle, uint64_t seed, double correlationPixels = 0);

// r' = clamp(scale r + offset, 0, 1).
Image biasRoughness(const Image& roughness, double scale, double offset);

// All of the above for one view's buffers. Radiance buffers are left as they are (they
// are the photographs' stand-ins); f0 gets the blur only.
struct BufferDegradation {
  double blurSigma = 0;  // pixels, applied to the G-buffers before the rest
  double depthScale = 1, depthOffset = 0;
  double depthNoise = 0;         // standard deviation, depth units
  double normalMeanAngle = 0;    // radians
  double normalCorrelation = 0;  // pixels, see perturbNormals
  double roughnessScale = 1, roughnessOffset = 0;
  double roughnessNoise = 0;
  uint64_t seed = 0;
};
// The view index joins the seed, so views of one dataset get independent errors.
ViewBuffers degradeBuffers(const ViewBuffers& exact, const BufferDegradation& degradation, uint64_t view);

}  // namespace glint
