// Writes Gaussian scenes as .spz, Niantic's compressed splat format (gzip over quantised
// attribute arrays; docs/data-format.md, "Compressed splats"), which Scaniverse, SuperSplat
// and PlayCanvas's splat-transform read.
#pragma once

#include <filesystem>

#include "scene/gaussians.h"
#include "scene/splat_colour.h"

namespace glint {

// Fractional bits of .spz's 24-bit fixed-point positions when the scene fits (1/4096 m);
// fewer when a coordinate would not fit in 2^23 steps.
constexpr int kSpzFractionalBits = 12;

// Writes `scene` with `colour` (colour.consistent(scene.size())) atomically as .spz version 3.
// Positions, rotations and SH coefficients are turned half a turn about x into the
// format's y-up, z-back axes, so a reader that converts .spz to PLY axes (as splat-transform
// does) gets Glint's coordinates back. Throws Error naming the file when a coordinate lies
// beyond +-2^23 m (no fixed point can hold it) or a value is NaN.
void writeSpz(const std::filesystem::path& path, const GaussianScene& scene, const SplatColour& colour);

}  // namespace glint
