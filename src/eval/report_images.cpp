// Error maps and G-buffer pictures of the report page.
#include "eval/report_images.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "io/tonemap.h"

namespace glint {

namespace {

void requireSameSize(const Image& truth, const Image& ours, const char* what) {
  if (truth.width != ours.width || truth.height != ours.height)
    throw Error(what, "ground truth is " + std::to_string(truth.width) + "x" + std::to_string(truth.height) +
                          " but ours is " + std::to_string(ours.width) + "x" + std::to_string(ours.height));
}

float clamp01(float v) { return std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f; }
Rgb clamp01(const Rgb& c) { return {clamp01(c.x), clamp01(c.y), clamp01(c.z)}; }

// Maps every pixel of image through f(x, y) -> Rgb into a 3-channel display image.
template <typename F>
Image mapPixels(const Image& image, F f) {
  Image shown(image.width, image.height, 3);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) shown.setRgb(x, y, clamp01(f(x, y)));
  return shown;
}

}  // namespace

Rgb errorRampColour(float t) {
  // Control points of a black-body-like ramp, evenly spaced in t.
  static constexpr std::array<Rgb, 5> kStops = {Rgb(0.0f, 0.0f, 0.0f), Rgb(0.28f, 0.06f, 0.45f),
                                                Rgb(0.75f, 0.2f, 0.38f), Rgb(0.98f, 0.55f, 0.1f),
                                                Rgb(0.99f, 0.97f, 0.7f)};
  float s = clamp01(t) * float(kStops.size() - 1);
  size_t i = std::min(size_t(s), kStops.size() - 2);
  float f = s - float(i);
  return kStops[i] * (1.0f - f) + kStops[i + 1] * f;
}

Image errorMap(const Image& truth, const Image& ours, float fullScale) {
  requireSameSize(truth, ours, "error map");
  return mapPixels(truth, [&](int x, int y) {
    Rgb d = tonemapFilmic(ours.rgb(x, y)) - tonemapFilmic(truth.rgb(x, y));
    float e = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    return errorRampColour(e / fullScale);
  });
}

GBufferPictures gBufferPictures(Buffer buffer, const Image& truth, const Image& ours) {
  requireSameSize(truth, ours, bufferName(buffer));
  GBufferPictures pictures;
  switch (buffer) {
    case Buffer::Normal: {
      auto shown = [](const Image& n) {
        return mapPixels(n, [&](int x, int y) { return n.rgb(x, y) * 0.5f + Rgb(0.5f); });
      };
      pictures = {shown(truth), shown(ours), "world normal n/2 + 1/2"};
      break;
    }
    case Buffer::Depth: {
      float nearest = INFINITY, farthest = 0.0f;
      for (float d : truth.pixels)
        if (hasSurface(d)) nearest = std::min(nearest, d), farthest = std::max(farthest, d);
      if (!(farthest > nearest)) nearest = 0.0f, farthest = std::max(farthest, 1.0f);
      // Near is bright; the farthest surface stays visibly above the black of "no surface".
      auto shown = [&](const Image& depth) {
        return mapPixels(depth, [&](int x, int y) {
          float d = depth.at(x, y);
          if (!hasSurface(d)) return Rgb(0.0f);
          return Rgb(1.0f - 0.85f * clamp01((d - nearest) / (farthest - nearest)));
        });
      };
      char scale[96];
      std::snprintf(scale, sizeof scale, "depth %.3g (white) to %.3g (dark grey), none black", nearest, farthest);
      pictures = {shown(truth), shown(ours), scale};
      break;
    }
    case Buffer::Roughness:
    case Buffer::F0: {
      auto shown = [](const Image& v) { return mapPixels(v, [&](int x, int y) { return v.rgb(x, y); }); };
      pictures = {shown(truth), shown(ours), buffer == Buffer::Roughness ? "roughness 0 (black) to 1 (white)"
                                                                          : "F0 as colour, 0 to 1"};
      break;
    }
    default: GLINT_CHECK(false, std::string("gBufferPictures: not a G-buffer: ") + bufferName(buffer));
  }
  return pictures;
}

}  // namespace glint
