// Label rendering with stb_easy_font: it emits axis-aligned quads, which we fill.
#include "eval/text_overlay.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <stb_easy_font.h>

namespace glint {

void drawText(Image& image, int x, int y, const std::string& text, const Rgb& color, int scale) {
  // stb_easy_font writes 4 vertices per quad, 16 bytes each (x, y, z floats + colour).
  std::vector<char> buffer(text.size() * 300 + 1024);
  int quads = stb_easy_font_print(0, 0, const_cast<char*>(text.c_str()), nullptr, buffer.data(), int(buffer.size()));
  const float* v = reinterpret_cast<const float*>(buffer.data());
  for (int q = 0; q < quads; ++q) {
    const float* quad = v + q * 16;
    float x0 = quad[0], y0 = quad[1], x1 = quad[8], y1 = quad[9];  // opposite corners
    int px0 = x + int(std::lround(std::min(x0, x1) * scale)), px1 = x + int(std::lround(std::max(x0, x1) * scale));
    int py0 = y + int(std::lround(std::min(y0, y1) * scale)), py1 = y + int(std::lround(std::max(y0, y1) * scale));
    for (int py = std::max(0, py0); py < std::min(image.height, py1); ++py)
      for (int px = std::max(0, px0); px < std::min(image.width, px1); ++px) image.setRgb(px, py, color);
  }
}

int textWidth(const std::string& text, int scale) {
  return stb_easy_font_width(const_cast<char*>(text.c_str())) * scale;
}

}  // namespace glint
