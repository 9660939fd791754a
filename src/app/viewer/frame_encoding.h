// In-memory image files of the viewer's frames: PNG (lossless, for comparisons) and JPEG
// (small and quick, for interaction).
#pragma once

#include <string>

#include "io/image.h"

namespace glint {

// The bytes of a JPEG of an RGB image with values in [0, 1] (clamped and rounded to 8 bits).
std::string encodeJpeg(const Image& image, int quality = 90);

}  // namespace glint
