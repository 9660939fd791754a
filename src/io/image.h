// Float images and their file encodings: OpenEXR (float32), 16-bit float TIFF, 8/16-bit PNG, JPEG.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "math/vec.h"

namespace glint {

// A row-major image with interleaved channels, top row first. Values are whatever the
// caller stores (linear radiance, depth, normals, ...): no encoding is implied.
struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> pixels;

  Image() = default;
  Image(int w, int h, int c, float fill = 0.0f) : width(w), height(h), channels(c), pixels(size_t(w) * h * c, fill) {}

  bool empty() const { return pixels.empty(); }
  size_t index(int x, int y, int c = 0) const { return (size_t(y) * width + x) * channels + c; }
  float& at(int x, int y, int c = 0) { return pixels[index(x, y, c)]; }
  float at(int x, int y, int c = 0) const { return pixels[index(x, y, c)]; }
  // RGB of a 3-channel image, or the single value replicated for a 1-channel image.
  Rgb rgb(int x, int y) const {
    const float* p = &pixels[index(x, y)];
    return channels >= 3 ? Rgb(p[0], p[1], p[2]) : Rgb(p[0]);
  }
  void setRgb(int x, int y, const Rgb& v) {
    float* p = &pixels[index(x, y)];
    p[0] = v.x;
    if (channels >= 3) p[1] = v.y, p[2] = v.z;
  }
};

enum class ImageFormat { Exr, Tiff, Png, Jpeg };

// Format from the file extension (.exr, .tif/.tiff, .png, .jpg/.jpeg, case-insensitive);
// throws Error naming the file for any other extension.
ImageFormat imageFormatFromPath(const std::filesystem::path& path);
const char* imageFormatExtension(ImageFormat format);  // ".exr", ".tiff", ".png", ".jpg"

// Reads an image. EXR: half or float, channels R,G,B (A ignored) or one channel (Y or any
// single name). TIFF: 16- or 32-bit float, or 8/16-bit unsigned (scaled to [0,1]), 1 or 3+
// samples. PNG: 8- or 16-bit gray/RGB (alpha ignored), scaled to [0,1]. JPEG: 8-bit
// greyscale (1 channel) or colour (3 channels, YCbCr or RGB), scaled to [0,1]; CMYK is
// refused. Values are the file's display-referred codes: no transfer is undone here (see
// io/transfer.h), embedded ICC profiles are ignored, and the EXIF orientation is not
// applied, so pixels are in stored order, as COLMAP and other photogrammetry tools use
// them. Throws Error naming the file and the problem (missing, truncated, unsupported
// layout, ...).
Image readImage(const std::filesystem::path& path);
// readImage, except that a PNG with alpha comes back as RGBA (4 channels; a grey one as RGB
// plus alpha): for images whose alpha is coverage, composited by the caller.
Image readImageWithAlpha(const std::filesystem::path& path);
// readImage, except that a PNG comes back with the channels it stores: 1 grey, 2 grey and
// alpha, 3 RGB or 4 RGBA. For loaders that check a file's layout before they use it.
Image readImageAsStored(const std::filesystem::path& path);

// The bytes of an 8-bit PNG of the image (values clamped to [0,1] and rounded, as
// writeImage does), encoded in memory: for embedding in a page as a data: URI. The image
// must be non-empty with 1, 3 or 4 channels.
std::string encodePng(const Image& image);

// How writeImage stores samples where a format offers a choice.
struct ImageWriteOptions {
  // Bits per PNG sample, 8 or 16. 16 is for data a byte cannot resolve (a predictor's depth
  // or normals). EXR and TIFF store floats and ignore it; JPEG holds only 8 bits, so asking
  // it for 16 is an error rather than a silent loss of precision.
  int pngBitDepth = 8;
};

// Writes an image atomically in the format of the extension: EXR float32, TIFF 16-bit
// float (half), PNG 8- or 16-bit, JPEG 8-bit at quality 95 without chroma subsampling
// (PNG and JPEG clamp values to [0,1] and round them). Images with 1 or 3 channels (PNG
// also 4). Throws Error naming the file.
void writeImage(const std::filesystem::path& path, const Image& image, const ImageWriteOptions& options = {});

}  // namespace glint
