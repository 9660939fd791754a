// Contact sheets: a grid of a dataset's buffers (rows = views, columns = buffers), each
// shown the way a person reads it, with labels.
#pragma once

#include <vector>

#include "io/image.h"
#include "scene/dataset.h"

namespace glint {

// Display encoding of one buffer: radiance through the filmic tonemap (the paper's 8-bit
// curve), depth as a colour ramp over [0, maxDepth] (black = no surface), normals as
// n/2+0.5, roughness and F0 as they are. Returns an RGB image with values in [0,1].
Image visualizeBuffer(const Image& buffer, Buffer kind, float maxDepth);

// A labelled grid of the given views' seven buffers.
Image makeContactSheet(const Dataset& dataset, const DatasetSplit& split, const std::vector<size_t>& views);

}  // namespace glint
