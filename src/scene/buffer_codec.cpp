// Per-buffer file encodings (tonemapped radiance, offset normals, float depth) and value checks.
#include "scene/buffer_codec.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <system_error>

#include "core/error.h"
#include "io/tonemap.h"

namespace glint {

std::optional<std::filesystem::path> findBufferFileAt(const std::filesystem::path& base) {
  for (ImageFormat format : {ImageFormat::Exr, ImageFormat::Tiff, ImageFormat::Png}) {
    std::filesystem::path candidate = base;
    candidate += imageFormatExtension(format);
    if (std::filesystem::is_regular_file(candidate)) return candidate;
  }
  return std::nullopt;
}

std::string missingBufferMessage(const std::filesystem::path& base, Buffer buffer) {
  std::string message = std::string(bufferName(buffer)) + " buffer not found (tried .exr, .tiff and .png)";
  std::error_code ec;
  std::string others;
  for (std::filesystem::directory_iterator it(base.parent_path(), ec), end; !ec && it != end; it.increment(ec))
    if (it->path().stem() == base.filename() && it->path().has_extension())
      others += (others.empty() ? "" : ", ") + it->path().filename().string();
  if (!others.empty()) message += "; found " + others + ", which is not a supported buffer format";
  return message;
}

ImageFormat bufferStorageFormat(Buffer buffer, ImageFormat requested) {
  return buffer == Buffer::Depth && requested == ImageFormat::Png ? ImageFormat::Exr : requested;
}

Image encodeBuffer(const Image& linear, Buffer buffer, ImageFormat format) {
  GLINT_CHECK(format == bufferStorageFormat(buffer, format), "depth is never stored as PNG");
  Image encoded = linear;
  if (format != ImageFormat::Png) return encoded;
  if (isRadianceBuffer(buffer))
    for (float& v : encoded.pixels) v = tonemapFilmic(v);
  else if (buffer == Buffer::Normal)
    for (float& v : encoded.pixels) v = v * 0.5f + 0.5f;
  return encoded;
}

Image readBufferFile(const std::filesystem::path& path, Buffer buffer) {
  // The extension decides the encoding; check it before decoding pixels.
  ImageFormat format = imageFormatFromPath(path);
  if (buffer == Buffer::Depth && format == ImageFormat::Png)
    throw Error(path.string(), "depth must be stored as float (EXR or TIFF), found PNG");

  Image image = readImage(path);
  int expected = bufferChannels(buffer);
  if (image.channels != expected)
    throw Error(path.string(), "a " + std::string(bufferName(buffer)) + " buffer needs " + std::to_string(expected) +
                                   (expected == 1 ? " channel" : " channels") + ", found " +
                                   std::to_string(image.channels));

  if (format == ImageFormat::Png) {
    if (isRadianceBuffer(buffer))
      for (float& v : image.pixels) v = untonemapFilmic(v);
    else if (buffer == Buffer::Normal)
      for (float& v : image.pixels) v = v * 2.0f - 1.0f;
  }
  if (buffer == Buffer::Depth)
    for (float& v : image.pixels)
      if (v == std::numeric_limits<float>::infinity()) v = 0.0f;
  return image;
}

namespace {

// Normals must be unit length within this where depth says there is a surface
// (8-bit PNG normals are off by up to ~0.01; anything beyond 0.1 is a wrong encoding).
constexpr float kNormalLengthTolerance = 0.1f;
// Roughness and f0 must lie in [0, 1] up to this (rounding in conversions).
constexpr float kUnitRangeTolerance = 1e-3f;

std::string pixelName(const Image& image, size_t valueIndex) {
  size_t pixel = valueIndex / image.channels;
  std::ostringstream s;
  s << "pixel (" << pixel % image.width << ", " << pixel / image.width << ")";
  if (image.channels > 1) s << " channel " << valueIndex % image.channels;
  return s.str();
}

std::optional<std::string> findOutsideUnitRange(const Image& image) {
  size_t bad = 0, first = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    float v = image.pixels[i];
    if ((v < -kUnitRangeTolerance || v > 1.0f + kUnitRangeTolerance) && bad++ == 0) first = i;
  }
  if (bad == 0) return std::nullopt;
  std::ostringstream s;
  s << bad << " of " << image.pixels.size() << " values lie outside [0, 1]; the first is "
    << pixelName(image, first) << " = " << image.pixels[first];
  return s.str();
}

}  // namespace

std::optional<std::string> findNonUnitNormal(const Image& normal, const Image& depth) {
  size_t bad = 0, surface = 0, first = 0;
  float firstLength = 0;
  for (int y = 0; y < normal.height; ++y)
    for (int x = 0; x < normal.width; ++x) {
      if (!hasSurface(depth.at(x, y))) continue;
      ++surface;
      float len = length(normal.rgb(x, y));
      if (std::abs(len - 1.0f) > kNormalLengthTolerance && bad++ == 0)
        first = normal.index(x, y), firstLength = len;
    }
  if (bad == 0) return std::nullopt;
  std::ostringstream s;
  s << bad << " of " << surface << " surface pixels (depth > 0) have normals that are not unit length within "
    << kNormalLengthTolerance << "; the first is " << pixelName(normal, first) << " with length " << firstLength;
  return s.str();
}

std::optional<std::string> findInvalidValue(const Image& image, Buffer buffer) {
  size_t bad = 0;
  size_t first = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    float v = image.pixels[i];
    bool invalid = !std::isfinite(v) || (buffer == Buffer::Depth && v < 0.0f);
    if (invalid && bad++ == 0) first = i;
  }
  if (bad == 0) return buffer == Buffer::Roughness || buffer == Buffer::F0 ? findOutsideUnitRange(image) : std::nullopt;

  int c = int(first % image.channels);
  size_t pixel = first / image.channels;
  int x = int(pixel % image.width), y = int(pixel / image.width);
  float v = image.pixels[first];
  std::ostringstream s;
  s << "pixel (" << x << ", " << y << ") channel " << c << " is " << v;
  if (std::isfinite(v))
    s << ", but depth must not be negative";
  else
    s << ", but values must be finite";
  if (bad > 1) s << " (" << bad << " bad values in total)";
  return s.str();
}

}  // namespace glint
