// Parsers for flag values that CLI11 cannot check alone (resolutions, colours, lists).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "eval/region_metrics.h"
#include "math/vec.h"

namespace glint {

// "256x192" -> (256, 192). Throws Error naming the flag for anything else or sizes
// outside [1, 16384].
Vec2i parseResolution(const std::string& text, const std::string& flag);
// "0.5" -> (0.5, 0.5, 0.5); "1,0.8,0.6" -> RGB. Throws Error naming the flag.
Rgb parseColor(const std::string& text, const std::string& flag);
// "0,5,9" -> {0, 5, 9}. Throws Error naming the flag.
std::vector<size_t> parseIndexList(const std::string& text, const std::string& flag);
// "12,34" -> (12, 34), a pixel position. Throws Error naming the flag.
Vec2i parsePixel(const std::string& text, const std::string& flag);
// "X0,Y0,Z0,X1,Y1,Z1": a world-space box, corners in any order.
WorldBox parseBox(const std::string& text, const std::string& flag);

// A flag value that must be a finite number > 0; the refusal quotes the value as given
// ("--exposure: must be a finite number > 0, found -1"), where CLI::PositiveNumber quotes
// its bound, the largest double, in 309 digits.
CLI::Validator positiveNumber();

}  // namespace glint
