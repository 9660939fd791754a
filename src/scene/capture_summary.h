// `glint info` for a real capture (and the NeRF-synthetic layout): cameras, buffers present,
// depth fits, the normal space the data shows, and every problem found loading each buffer.
#pragma once

#include <filesystem>
#include <string>

#include "scene/dataset.h"

namespace glint {

// The human-readable report; never throws for bad data (problems are listed). *clean (if
// given) is set to true when every buffer of every view loaded.
std::string describeCapture(const std::filesystem::path& root, int holdout = Dataset::kDefaultHoldout,
                            bool* clean = nullptr);

// What the normal maps of up to 8 training views look like (world or camera space, which
// camera axes) and, when that contradicts capture.json with confidence, lines starting with
// "warning:". Empty for a dataset without normal maps.
std::string normalSpaceCheck(const Dataset& dataset);

}  // namespace glint
