// Image format detection and the checks shared by every format before dispatching to its codec.
#include "io/image.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <system_error>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/input_file.h"
#include "io/image_codecs.h"

namespace glint {

namespace fs = std::filesystem;

ImageFormat imageFormatFromPath(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".exr") return ImageFormat::Exr;
  if (ext == ".tif" || ext == ".tiff") return ImageFormat::Tiff;
  if (ext == ".png") return ImageFormat::Png;
  if (ext == ".jpg" || ext == ".jpeg") return ImageFormat::Jpeg;
  throw Error(path.string(), "unknown image extension '" + ext + "' (expected .exr, .tif, .tiff, .png, .jpg or .jpeg)");
}

const char* imageFormatExtension(ImageFormat format) {
  switch (format) {
    case ImageFormat::Exr: return ".exr";
    case ImageFormat::Tiff: return ".tiff";
    case ImageFormat::Png: return ".png";
    case ImageFormat::Jpeg: return ".jpg";
  }
  return "";
}

Image readImageWithAlpha(const fs::path& path) {
  if (imageFormatFromPath(path) != ImageFormat::Png) return readImage(path);
  checkInputFile(path);
  return detail::readPng(path.string(), detail::PngChannels::Rgba);
}

Image readImageAsStored(const fs::path& path) {
  if (imageFormatFromPath(path) != ImageFormat::Png) return readImage(path);
  checkInputFile(path);
  return detail::readPng(path.string(), detail::PngChannels::AsStored);
}

Image readImage(const fs::path& path) {
  ImageFormat format = imageFormatFromPath(path);
  std::string name = path.string();
  checkInputFile(path);

  Image image;
  switch (format) {
    case ImageFormat::Exr: image = detail::readExr(name); break;
    case ImageFormat::Tiff: image = detail::readTiff(name); break;
    case ImageFormat::Png: image = detail::readPng(name); break;
    case ImageFormat::Jpeg: image = detail::readJpeg(name); break;
  }
  // The codecs check this already; kept as the one place the Image invariant is stated.
  GLINT_CHECK(image.width > 0 && image.height > 0 && (image.channels == 1 || image.channels == 3) &&
                  image.pixels.size() == size_t(image.width) * image.height * image.channels,
              name);
  return image;
}

void writeImage(const fs::path& path, const Image& image, const ImageWriteOptions& options) {
  ImageFormat format = imageFormatFromPath(path);
  std::string name = path.string();
  GLINT_CHECK(options.pngBitDepth == 8 || options.pngBitDepth == 16,
              "PNG bit depth must be 8 or 16, writing " + name);
  if (format == ImageFormat::Jpeg && options.pngBitDepth == 16)
    throw Error(name, "JPEG holds 8-bit samples only; write 16-bit samples as .png");
  GLINT_CHECK(image.pixels.size() == size_t(std::max(image.width, 0)) * std::max(image.height, 0) *
                                         std::max(image.channels, 0),
              "image pixel count does not match its size, writing " + name);
  if (image.width <= 0 || image.height <= 0) {
    throw Error(name, "cannot write an empty image (" + std::to_string(image.width) + "x" +
                          std::to_string(image.height) + " pixels)");
  }
  bool pngAlpha = format == ImageFormat::Png && image.channels == 4;
  if (image.channels != 1 && image.channels != 3 && !pngAlpha) {
    throw Error(name, "cannot write an image with " + std::to_string(image.channels) + " channels (" +
                          std::string(format == ImageFormat::Png ? "PNG takes 1, 3 or 4" : "expected 1 or 3") + ")");
  }
  writeAtomically(path, [&](const std::string& temp) {
    switch (format) {
      case ImageFormat::Exr: detail::writeExr(temp, name, image); break;
      case ImageFormat::Tiff: detail::writeTiff(temp, name, image); break;
      case ImageFormat::Png: detail::writePng(temp, name, image, options.pngBitDepth); break;
      case ImageFormat::Jpeg: detail::writeJpeg(temp, name, image); break;
    }
  });
}

namespace detail {

size_t maxDecodedBytes(const std::string& path) {
  std::error_code ec;
  uintmax_t fileBytes = fs::file_size(path, ec);
  if (ec) return kMinDecodedBytes;  // the reader itself reports the unreadable file
  uintmax_t bound = fileBytes > SIZE_MAX / kMaxCompressionRatio ? SIZE_MAX : fileBytes * kMaxCompressionRatio;
  return std::max(size_t(bound), kMinDecodedBytes);
}

void checkImageSize(const std::string& path, size_t width, size_t height, size_t channels, size_t bytesPerSample) {
  if (width == 0 || height == 0) {
    throw Error(path, "image has no pixels (" + std::to_string(width) + "x" + std::to_string(height) + ")");
  }
  channels = std::max<size_t>(channels, 1);
  if (width > kMaxImagePixels / height || width * height > kMaxImagePixels / channels) {
    throw Error(path, "image size " + std::to_string(width) + "x" + std::to_string(height) +
                          " is implausibly large (corrupt header?)");
  }
  // width * height * channels <= 2^32 here, so the product below cannot overflow.
  size_t sampleBytes = width * height * channels * std::max<size_t>(bytesPerSample, 1);
  if (sampleBytes > maxDecodedBytes(path)) {
    throw Error(path, "image size " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                          std::to_string(sampleBytes) + " bytes of samples, more than a file of " +
                          std::to_string(fs::file_size(path)) + " bytes can hold (truncated or corrupt header?)");
  }
}

}  // namespace detail

}  // namespace glint
