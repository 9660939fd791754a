// TIFF reading (16/32-bit float, 8/16-bit unsigned) and writing (16-bit float) through libtiff.
#include <Imath/half.h>
#include <tiffio.h>

#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/printable_text.h"
#include "io/image_codecs.h"

namespace glint::detail {

namespace {

// libtiff reports problems through callbacks, which by default print to stderr. Each file
// gets handlers that keep the first error message so it can go into the Error we throw.
struct TiffMessages {
  std::string firstError;
};

int onTiffError(TIFF*, void* userData, const char* module, const char* format, va_list args) {
  auto* messages = static_cast<TiffMessages*>(userData);
  if (messages->firstError.empty()) {
    char buffer[512];
    std::vsnprintf(buffer, sizeof(buffer), format, args);
    messages->firstError = buffer;
  }
  return 1;  // handled: do not call the global handler
}

int onTiffWarning(TIFF*, void*, const char*, const char*, va_list) { return 1; }  // unknown tags etc.

// A few libtiff paths report through the global handlers (no file known); silence those too.
void silenceGlobalTiffHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    TIFFSetErrorHandler(nullptr);
    TIFFSetWarningHandler(nullptr);
  });
}

struct TiffCloser {
  void operator()(TIFF* tif) const { TIFFClose(tif); }
};
using TiffHandle = std::unique_ptr<TIFF, TiffCloser>;

TiffHandle openTiff(const std::string& filePath, const char* mode, TiffMessages& messages) {
  silenceGlobalTiffHandlers();
  TIFFOpenOptions* options = TIFFOpenOptionsAlloc();
  TIFFOpenOptionsSetErrorHandlerExtR(options, onTiffError, &messages);
  TIFFOpenOptionsSetWarningHandlerExtR(options, onTiffWarning, nullptr);
  TiffHandle tif(TIFFOpenExt(filePath.c_str(), mode, options));
  TIFFOpenOptionsFree(options);
  return tif;
}

[[noreturn]] void throwTiffError(const std::string& path, const std::string& what, const TiffMessages& messages) {
  // libtiff's messages quote tag and field names from the file.
  std::string detail = printableText(messages.firstError, std::string::npos);
  throw Error(path, what + (detail.empty() ? "" : " (" + detail + ")"));
}

// One sample of a decoded scanline as float: floats as stored, unsigned scaled to [0, 1].
float tiffSample(const uint8_t* row, size_t index, uint16_t format, uint16_t bits) {
  if (format == SAMPLEFORMAT_IEEEFP) {
    if (bits == 16) {
      uint16_t b;
      std::memcpy(&b, row + 2 * index, 2);
      Imath::half h;
      h.setBits(b);
      return float(h);
    }
    float f;
    std::memcpy(&f, row + 4 * index, 4);
    return f;
  }
  if (bits == 8) return row[index] / 255.0f;
  uint16_t u;
  std::memcpy(&u, row + 2 * index, 2);
  return u / 65535.0f;
}

}  // namespace

Image readTiff(const std::string& path) {
  TiffMessages messages;
  TiffHandle tif = openTiff(path, "r", messages);
  if (!tif) throwTiffError(path, "cannot open as TIFF", messages);

  uint32_t width = 0, height = 0;
  uint16_t samples = 1, bits = 1, format = SAMPLEFORMAT_UINT, planar = PLANARCONFIG_CONTIG;
  uint16_t photometric = PHOTOMETRIC_MINISBLACK;
  TIFFGetField(tif.get(), TIFFTAG_IMAGEWIDTH, &width);
  TIFFGetField(tif.get(), TIFFTAG_IMAGELENGTH, &height);
  TIFFGetFieldDefaulted(tif.get(), TIFFTAG_SAMPLESPERPIXEL, &samples);
  TIFFGetFieldDefaulted(tif.get(), TIFFTAG_BITSPERSAMPLE, &bits);
  TIFFGetFieldDefaulted(tif.get(), TIFFTAG_SAMPLEFORMAT, &format);
  TIFFGetFieldDefaulted(tif.get(), TIFFTAG_PLANARCONFIG, &planar);
  TIFFGetField(tif.get(), TIFFTAG_PHOTOMETRIC, &photometric);

  bool floatLayout = format == SAMPLEFORMAT_IEEEFP && (bits == 16 || bits == 32);
  bool unsignedLayout = format == SAMPLEFORMAT_UINT && (bits == 8 || bits == 16);
  if (!floatLayout && !unsignedLayout) {
    throw Error(path, "unsupported TIFF sample type (" + std::to_string(bits) + "-bit " +
                          (format == SAMPLEFORMAT_IEEEFP ? "float" : format == SAMPLEFORMAT_INT ? "signed" : "unsigned") +
                          "; expected 16/32-bit float or 8/16-bit unsigned)");
  }
  if (samples == 2 || samples == 0) {
    throw Error(path, "unsupported TIFF with " + std::to_string(samples) + " samples per pixel (expected 1, or 3 or more)");
  }
  if (photometric == PHOTOMETRIC_PALETTE || photometric == PHOTOMETRIC_YCBCR || photometric == PHOTOMETRIC_SEPARATED) {
    throw Error(path, "unsupported TIFF photometric interpretation " + std::to_string(photometric) +
                          " (expected grey or RGB)");
  }
  if (TIFFIsTiled(tif.get())) throw Error(path, "tiled TIFF files are not supported (expected strips)");
  checkImageSize(path, width, height, samples, bits / 8);

  int channels = samples >= 3 ? 3 : 1;
  Image image(int(width), int(height), channels);
  std::vector<uint8_t> scanline(size_t(TIFFScanlineSize(tif.get())));
  for (uint32_t y = 0; y < height; ++y) {
    if (planar == PLANARCONFIG_CONTIG) {
      if (TIFFReadScanline(tif.get(), scanline.data(), y, 0) < 0) {
        throwTiffError(path, "cannot read TIFF row " + std::to_string(y) + " (truncated or corrupt file?)", messages);
      }
      for (uint32_t x = 0; x < width; ++x) {
        for (int c = 0; c < channels; ++c) {
          image.at(int(x), int(y), c) = tiffSample(scanline.data(), size_t(x) * samples + c, format, bits);
        }
      }
    } else {  // one plane per sample
      for (int c = 0; c < channels; ++c) {
        if (TIFFReadScanline(tif.get(), scanline.data(), y, uint16_t(c)) < 0) {
          throwTiffError(path, "cannot read TIFF row " + std::to_string(y) + " (truncated or corrupt file?)", messages);
        }
        for (uint32_t x = 0; x < width; ++x) image.at(int(x), int(y), c) = tiffSample(scanline.data(), x, format, bits);
      }
    }
  }
  // Grey where white is 0: flip unsigned data so larger still means brighter.
  if (photometric == PHOTOMETRIC_MINISWHITE && unsignedLayout) {
    for (float& v : image.pixels) v = 1.0f - v;
  }
  return image;
}

void writeTiff(const std::string& filePath, const std::string& displayPath, const Image& image) {
  TiffMessages messages;
  TiffHandle tif = openTiff(filePath, "w", messages);
  if (!tif) throwTiffError(displayPath, "cannot open for writing", messages);

  uint16_t samples = uint16_t(image.channels);
  uint16_t compression = TIFFIsCODECConfigured(COMPRESSION_ADOBE_DEFLATE) ? COMPRESSION_ADOBE_DEFLATE : COMPRESSION_NONE;
  bool ok = TIFFSetField(tif.get(), TIFFTAG_IMAGEWIDTH, uint32_t(image.width)) &&
            TIFFSetField(tif.get(), TIFFTAG_IMAGELENGTH, uint32_t(image.height)) &&
            TIFFSetField(tif.get(), TIFFTAG_SAMPLESPERPIXEL, samples) &&
            TIFFSetField(tif.get(), TIFFTAG_BITSPERSAMPLE, uint16_t(16)) &&
            TIFFSetField(tif.get(), TIFFTAG_SAMPLEFORMAT, uint16_t(SAMPLEFORMAT_IEEEFP)) &&
            TIFFSetField(tif.get(), TIFFTAG_PLANARCONFIG, uint16_t(PLANARCONFIG_CONTIG)) &&
            TIFFSetField(tif.get(), TIFFTAG_PHOTOMETRIC,
                         uint16_t(samples == 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK)) &&
            TIFFSetField(tif.get(), TIFFTAG_COMPRESSION, compression) &&
            TIFFSetField(tif.get(), TIFFTAG_ROWSPERSTRIP, TIFFDefaultStripSize(tif.get(), 0));
  if (!ok) throwTiffError(displayPath, "cannot set up the TIFF header", messages);

  // Values beyond half's range (|v| > 65504) become infinity, as in any half-float file.
  std::vector<uint16_t> row(size_t(image.width) * samples);
  for (int y = 0; y < image.height; ++y) {
    const float* source = &image.pixels[image.index(0, y)];
    for (size_t i = 0; i < row.size(); ++i) row[i] = Imath::half(source[i]).bits();
    if (TIFFWriteScanline(tif.get(), row.data(), uint32_t(y), 0) < 0) {
      throwTiffError(displayPath, "cannot write TIFF row " + std::to_string(y), messages);
    }
  }
  // Flush explicitly: TIFFClose cannot report a failed final write (disk full).
  if (!TIFFFlush(tif.get())) throwTiffError(displayPath, "write failed (disk full?)", messages);
}

}  // namespace glint::detail
