// How one colour or roughness value changes under an edit operation (docs/edit-files.md),
// for every kind of primitive an edit can touch.
#pragma once

#include <algorithm>

#include "edit/edit_document.h"
#include "edit/hsv.h"

namespace glint {

// The colour after a `set` (mixed by blend), `hsv_shift` or `hsv_multiply`; unclamped.
inline Rgb changeColor(const Rgb& c, const ColorChange& change) {
  switch (change.mode) {
    case ColorChange::Mode::Set: return lerp(c, change.value, change.blend);
    case ColorChange::Mode::HsvShift: return hsvToRgb(rgbToHsv(c) + change.value);
    case ColorChange::Mode::HsvMultiply: return hsvToRgb(rgbToHsv(c) * change.value);
  }
  return c;
}

// The roughness after a roughness operation, clamped to [0, 1].
inline float changeRoughness(float r, const Operation& op) {
  switch (op.roughnessMode) {
    case Operation::RoughnessMode::Set: r = op.amount; break;
    case Operation::RoughnessMode::Shift: r += op.amount; break;
    case Operation::RoughnessMode::Multiply: r *= op.amount; break;
  }
  return std::clamp(r, 0.0f, 1.0f);
}

// F0 and diffuse limits of docs/edit-files.md: F0 in [0, 1], diffuse >= 0.
inline Rgb clampF0(const Rgb& c) { return min(max(c, Rgb(0.0f)), Rgb(1.0f)); }
inline Rgb clampDiffuse(const Rgb& c) { return max(c, Rgb(0.0f)); }

}  // namespace glint
