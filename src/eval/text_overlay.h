// Draws short labels into images (stb_easy_font's vector font, rasterised as rectangles).
#pragma once

#include <string>

#include "io/image.h"

namespace glint {

// Draws text with its top-left corner at (x, y), each font pixel `scale` image pixels.
void drawText(Image& image, int x, int y, const std::string& text, const Rgb& color, int scale = 2);
// Width in image pixels of text drawn at scale.
int textWidth(const std::string& text, int scale = 2);

}  // namespace glint
