// The selectable transfer between a photograph's display-referred codes and linear radiance
// (sRGB, Glint's filmic tonemap, or none); formulas in docs/data-format.md.
#pragma once

#include <string>

#include "io/image.h"

namespace glint {

// How an image's stored values relate to linear radiance. Srgb: the IEC 61966-2-1 curve
// most cameras and phones write. Filmic: the tonemap of Glint's own 8-bit images
// (io/tonemap.h). Linear: stored values are radiance already (e.g. a linear 16-bit PNG).
enum class Transfer { Srgb, Filmic, Linear };

// "srgb", "filmic" or "linear".
const char* transferName(Transfer transfer);
// The transfer of that name (exactly as transferName spells it); throws Error listing the
// valid names otherwise.
Transfer parseTransfer(const std::string& name);

// Display value (a stored code scaled to [0, 1]) -> linear radiance, and back. For Srgb the
// two are inverse over all reals: the linear segment continues below 0 and the power
// segment above 1. For Filmic, toLinear caps at kMaxUntonemapped and toDisplay maps
// negatives to 0 (io/tonemap.h).
float toLinear(Transfer transfer, float display);
float toDisplay(Transfer transfer, float linear);

// The image with toLinear / toDisplay applied to its first three channels (all of a
// 1-channel image); a fourth channel, alpha, is coverage and stays as it is.
Image toLinear(Transfer transfer, Image image);
Image toDisplay(Transfer transfer, Image image);

}  // namespace glint
