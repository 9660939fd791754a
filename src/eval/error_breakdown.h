// Where the error of a rendered view lies: every pixel is put in one kind of region
// (silhouette, highlight edge, flat or curved mirror, glossy, rough) from the ground truth's
// own buffers, and the tonemapped squared error of the specular and final passes, and an
// estimate of the part of it that is Monte Carlo noise, are summed per kind.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "eval/region_metrics.h"
#include "io/image.h"
#include "scene/buffers.h"
#include "scene/camera.h"

namespace glint {

// In order of precedence: a pixel belongs to the first kind whose test it passes.
enum class PixelKind : uint8_t {
  NoSurface,      // the truth has no surface (background)
  Silhouette,     // a depth discontinuity in the 3x3 neighbourhood, or a grazing view of the surface
  HighlightEdge,  // a steep step of the true tonemapped specular in the 3x3 neighbourhood
  FlatMirror,     // roughness below mirrorRoughness, and the normal constant over 5x5
  CurvedMirror,   // roughness below mirrorRoughness otherwise
  Glossy,         // roughness below glossyRoughness
  Rough,          // the rest
  Count
};
constexpr int kPixelKindCount = static_cast<int>(PixelKind::Count);
const char* pixelKindName(PixelKind kind);  // "silhouette", "highlight edge", ...

struct PixelKindThresholds {
  float depthJump = 0.05f;         // relative depth difference to a neighbour
  float grazingCosine = 0.25f;     // |n . view| below this
  float highlightStep = 0.15f;     // tonemapped specular difference to a neighbour (0..1)
  // Every normal of the 5x5 neighbourhood within 1.1 degrees: flat, allowing for normals
  // stored in 8 bits (steps of up to 0.45 degrees).
  float flatNormalCosine = 0.9998f;
  float mirrorRoughness = 0.1f;
  float glossyRoughness = 0.45f;
};

// One PixelKind per pixel, row-major, from the truth's depth, normal, roughness and specular.
std::vector<PixelKind> classifyPixels(const Camera& camera, const ViewBuffers& truth,
                                      const PixelKindThresholds& thresholds = {});

struct KindError {
  size_t pixels = 0;
  MaskedError specular, final;  // on the filmic-tonemapped 8-bit images
  // Expected squared error from Monte Carlo noise alone, on the same tonemapped scale: for
  // a render that is the mean of two independent halves a and b, E|tm(a) - tm(b)|^2 / 4.
  MaskedError specularNoise, finalNoise;
};

struct ErrorBreakdown {
  std::array<KindError, kPixelKindCount> kinds;
  bool hasNoise = false;
  ErrorBreakdown& operator+=(const ErrorBreakdown& o);
  const KindError& operator[](PixelKind k) const { return kinds[static_cast<int>(k)]; }
};

// rendered is scored against truth; halves, when given, are the two independent renders
// whose mean is `rendered` (their difference estimates the noise term).
ErrorBreakdown breakdownView(const std::vector<PixelKind>& kinds, const ViewBuffers& rendered,
                             const ViewBuffers& truth, const ViewBuffers* halfA = nullptr,
                             const ViewBuffers* halfB = nullptr);

// A picture of the classification: one colour per kind (legend in pixelKindColour).
Image pixelKindImage(const std::vector<PixelKind>& kinds, int width, int height);
Rgb pixelKindColour(PixelKind kind);

// Per kind: pixels, share of pixels, share of the specular and final squared error, PSNR
// of each pass over the kind's pixels, and the noise share where measured.
nlohmann::json toJson(const ErrorBreakdown& breakdown);
void printBreakdown(const ErrorBreakdown& breakdown);

}  // namespace glint
