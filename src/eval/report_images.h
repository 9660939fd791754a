// Pictures of `glint report` beyond the radiance passes: per-pixel error maps and the
// G-buffers (normal, depth, roughness, F0), turned into display images with values in [0, 1].
#pragma once

#include <string>

#include "io/image.h"
#include "scene/buffers.h"

namespace glint {

// The error map's full scale: an 8-bit error of 64 levels (a quarter of the range) or more
// shows at the top of the colour ramp. Errors that matter to a viewer (a few levels) then
// stay visible, while a misplaced highlight does not flatten the rest to black.
inline constexpr float kErrorMapFullScale = 64.0f / 255.0f;

// The colour of t in [0, 1] on the error ramp: black, violet, orange, pale yellow. Its
// luminance rises monotonically, so the map reads in grey too. t is clamped.
Rgb errorRampColour(float t);

// Per pixel, the largest channel difference between the filmic-tonemapped images (as the
// 8-bit metrics see them), divided by fullScale and coloured with errorRampColour. Both
// images must have the same size (Error otherwise).
Image errorMap(const Image& truth, const Image& ours, float fullScale = kErrorMapFullScale);

// A G-buffer's ground truth and ours, ready to show side by side.
struct GBufferPictures {
  Image truth;
  Image ours;
  std::string scale;  // how values map to colours, e.g. "depth 1.2 (white) to 7.9 (dark)"
};

// Display images of a G-buffer: normals as n/2 + 1/2; depth inverted (near is bright) over
// the range of the ground truth's surfaces, shared by both pictures, with pixels without a
// surface black; roughness as grey; F0 as colour. Values are clamped to [0, 1]. buffer must be
// one of Depth, Normal, Roughness, F0.
GBufferPictures gBufferPictures(Buffer buffer, const Image& truth, const Image& ours);

}  // namespace glint
