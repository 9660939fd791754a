// The NeRF-synthetic Blender layout as it is shared (docs/data-format.md): transforms files
// whose frames name 8-bit sRGB RGBA PNGs without extension ("./train/r_0"), read as views
// that hold a final image only, composited over a chosen background colour.
#pragma once

#include <filesystem>

#include "io/image.h"
#include "math/vec.h"

namespace glint {

struct CaptureSource;
struct DatasetSplit;

// The colour behind the layout's transparent pixels: NeRF-synthetic practice is white.
enum class AlphaBackground { White, Black };
// Its linear radiance: 1 or 0.
Rgb backgroundRadiance(AlphaBackground background);

// True when root holds the layout: its first transforms file (train, else test, else val)
// names an image directly rather than SPLIT/render/render_NAME (the paper's layout), and
// root holds no COLMAP model beside it (the paper's layout with predicted buffers).
bool isNerfSyntheticFolder(const std::filesystem::path& root);

// Reads the cameras: the train split from transforms_train.json and the test split from
// transforms_test.json, or from transforms_val.json when there is no test file; a split
// without its file stays empty (the caller refuses a folder with neither). Each view's
// final image is its file_path with the first extension found (.png, .exr, .tiff, .tif,
// .jpg, .jpeg, or the one it names), and each split takes its size from its first image.
// With requireImages false, images may be missing (cameras only: no size). Throws Error
// naming the transforms file or image that is missing or malformed.
void openNerfSynthetic(const std::filesystem::path& root, AlphaBackground background, bool requireImages,
                       DatasetSplit* train, DatasetSplit* test, CaptureSource* source);

// Linear radiance over the background where alpha (coverage, straight as PNG stores it)
// leaves the pixel uncovered: alpha C + (1 - alpha) B, per pixel, on linear values.
Image compositeOverBackground(const Image& linearRgb, const Image& alpha, Rgb background);

}  // namespace glint
