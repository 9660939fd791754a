// Writes Gaussian scenes as the compressed PLY of PlayCanvas (SuperSplat, splat-transform,
// the PlayCanvas engine): chunks of 256 Gaussians, each with float bounds, and per Gaussian
// four packed uint32 (docs/data-format.md, "Compressed splats").
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "scene/gaussians.h"
#include "scene/splat_colour.h"

namespace glint {

constexpr size_t kCompressedPlyChunkSize = 256;

// The order the Gaussians are written in: along a Morton (Z-order) curve through the scene's
// bounding box, so that each chunk of 256 covers a small box and its 11-bit positions are
// fine. order[j] is the index of the Gaussian written j-th; ties keep the scene's order.
std::vector<uint32_t> compressedPlyOrder(const GaussianScene& scene);

// Writes `scene` with `colour` (colour.consistent(scene.size())) atomically, in the order of
// compressedPlyOrder, with an `sh` element of 8-bit f_rest coefficients when
// colour.shDegree > 0. Coordinates are Glint's (PLY axes, as the format expects). Throws
// Error naming the file for a NaN or infinite value.
void writeCompressedPly(const std::filesystem::path& path, const GaussianScene& scene, const SplatColour& colour);

}  // namespace glint
