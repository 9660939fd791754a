// RGB <-> HSV conversion for colour edits (hue in degrees [0, 360), saturation and value
// as in the hexcone model of Smith 1978; value is max(r, g, b), so linear colours above 1
// keep their intensity).
#pragma once

#include <algorithm>
#include <cmath>

#include "math/vec.h"

namespace glint {

// (h, s, v) of a non-negative RGB colour; grey has hue 0.
inline Vec3f rgbToHsv(const Rgb& c) {
  float maxC = std::max({c.x, c.y, c.z}), minC = std::min({c.x, c.y, c.z});
  float delta = maxC - minC;
  float h = 0.0f;
  if (delta > 0.0f) {
    if (maxC == c.x)
      h = 60.0f * std::fmod((c.y - c.z) / delta + 6.0f, 6.0f);
    else if (maxC == c.y)
      h = 60.0f * ((c.z - c.x) / delta + 2.0f);
    else
      h = 60.0f * ((c.x - c.y) / delta + 4.0f);
  }
  float s = maxC > 0.0f ? delta / maxC : 0.0f;
  return {h, s, maxC};
}

// RGB of (h, s, v); h is wrapped into [0, 360), s clamped to [0, 1], v to >= 0.
inline Rgb hsvToRgb(const Vec3f& hsv) {
  float h = std::fmod(hsv.x, 360.0f);
  if (h < 0.0f) h += 360.0f;
  float s = std::clamp(hsv.y, 0.0f, 1.0f), v = std::max(hsv.z, 0.0f);
  float chroma = v * s;
  float sector = h / 60.0f;
  float x = chroma * (1.0f - std::abs(std::fmod(sector, 2.0f) - 1.0f));
  Rgb rgb;
  switch (int(sector) % 6) {
    case 0: rgb = {chroma, x, 0}; break;
    case 1: rgb = {x, chroma, 0}; break;
    case 2: rgb = {0, chroma, x}; break;
    case 3: rgb = {0, x, chroma}; break;
    case 4: rgb = {x, 0, chroma}; break;
    default: rgb = {chroma, 0, x}; break;
  }
  float m = v - chroma;
  return rgb + Rgb(m);
}

}  // namespace glint
