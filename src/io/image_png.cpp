// PNG reading (8/16-bit grey, RGB, palette; alpha dropped or, on request, kept as RGBA) and 8/16-bit writing, to a file
// or to memory, through libpng.
#include <png.h>

#include <algorithm>
#include <cerrno>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/printable_text.h"
#include "io/image_codecs.h"

namespace glint::detail {

namespace {

// libpng reports errors by calling onPngError, which must not return: it longjmps back to
// the setjmp in decodePng/encodePng. Those two functions therefore hold only trivially
// destructible locals; everything with a destructor lives in this job, owned by the caller.
struct PngJob {
  std::FILE* file = nullptr;
  std::string* memory = nullptr;  // write: the encoded bytes go here when file is null
  std::string error;
  // Read: filled by decodePng. Write: filled by the caller.
  png_uint_32 width = 0, height = 0;
  int channels = 0;  // after transforms, as `layout` says (write: 1, 3 or 4 RGBA)
  PngChannels layout = PngChannels::DropAlpha;  // read: what happens to alpha and grey
  int bitDepth = 8;  // read: 8 or 16 after transforms; write: as asked
  size_t maxBytes = 0;  // read: the most decoded bytes the file can justify (maxDecodedBytes)
  std::vector<png_byte> data;
  std::vector<png_bytep> rows;
};

void onPngError(png_structp png, png_const_charp message) {
  auto* job = static_cast<PngJob*>(png_get_error_ptr(png));
  job->error = message;
  png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {}  // e.g. unknown or slightly malformed ancillary chunks

// Sizes job.data and points job.rows into it; false if memory runs out. Kept apart from
// decodePng so no exception ever has to pass through libpng's frames.
bool allocateRows(PngJob& job, size_t rowBytes) {
  try {
    job.data.resize(rowBytes * job.height);
    job.rows.resize(job.height);
  } catch (const std::bad_alloc&) {
    return false;
  }
  for (png_uint_32 y = 0; y < job.height; ++y) job.rows[y] = job.data.data() + rowBytes * y;
  return true;
}

// Decodes job.file into job.data. Returns false (job.error set) on any libpng error.
bool decodePng(PngJob& job) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &job, onPngError, onPngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    job.error = "out of memory";
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_init_io(png, job.file);
  png_read_info(png, info);

  // Normalise every layout to 8- or 16-bit grey or RGB without alpha, or to RGB(A) when
  // the caller wants the alpha.
  png_set_expand(png);  // palette -> RGB, grey < 8 bits -> 8 bits, tRNS -> alpha
  if (job.layout == PngChannels::Rgba)
    png_set_gray_to_rgb(png);
  else if (job.layout == PngChannels::DropAlpha)
    png_set_strip_alpha(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);

  job.width = png_get_image_width(png, info);
  job.height = png_get_image_height(png, info);
  job.channels = png_get_channels(png, info);
  job.bitDepth = png_get_bit_depth(png, info);
  const bool layoutOk = job.layout == PngChannels::Rgba        ? job.channels == 3 || job.channels == 4
                        : job.layout == PngChannels::DropAlpha ? job.channels == 1 || job.channels == 3
                                                               : job.channels >= 1 && job.channels <= 4;
  if (!layoutOk || (job.bitDepth != 8 && job.bitDepth != 16)) {
    png_error(png, "unexpected layout after conversion");
  }
  if (job.width == 0 || job.height == 0 ||
      size_t(job.width) * job.height > kMaxImagePixels / size_t(job.channels)) {
    png_error(png, "implausible image size");
  }
  // Checked before allocating: the IHDR of a 100-byte file can declare 65535 x 65535.
  size_t rowBytes = png_get_rowbytes(png, info);
  if (rowBytes > job.maxBytes / job.height) png_error(png, "image size larger than the file's data can hold");
  if (!allocateRows(job, rowBytes)) png_error(png, "out of memory");
  png_read_image(png, job.rows.data());
  png_read_end(png, nullptr);  // checks the trailing chunks, so a cut-off file is noticed
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

// Appends encoded bytes to job.memory; false if memory runs out. Kept apart from
// appendToMemory so no exception ever has to pass through libpng's frames.
bool appendBytes(PngJob& job, const png_byte* data, size_t length) {
  try {
    job.memory->append(reinterpret_cast<const char*>(data), length);
  } catch (const std::bad_alloc&) {
    return false;
  }
  return true;
}

void appendToMemory(png_structp png, png_bytep data, png_size_t length) {
  if (!appendBytes(*static_cast<PngJob*>(png_get_io_ptr(png)), data, length)) png_error(png, "out of memory");
}

// Encodes job.rows (job.bitDepth, job.channels) into job.file, or job.memory when there is
// no file. Returns false (job.error set) on failure.
bool encodePng(PngJob& job) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &job, onPngError, onPngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    job.error = "out of memory";
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  if (job.file)
    png_init_io(png, job.file);
  else
    png_set_write_fn(png, &job, appendToMemory, nullptr);
  int colorType = job.channels == 1 ? PNG_COLOR_TYPE_GRAY
                  : job.channels == 3 ? PNG_COLOR_TYPE_RGB
                                      : PNG_COLOR_TYPE_RGB_ALPHA;
  png_set_IHDR(png, info, job.width, job.height, job.bitDepth, colorType, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, job.rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

Image readPng(const std::string& path, PngChannels layout) {
  PngJob job;
  job.layout = layout;
  job.file = std::fopen(path.c_str(), "rb");
  if (!job.file) throw Error(path, std::string("cannot open for reading: ") + std::strerror(errno));
  png_byte signature[8] = {};
  size_t got = std::fread(signature, 1, sizeof(signature), job.file);
  if (got != sizeof(signature) || png_sig_cmp(signature, 0, sizeof(signature)) != 0) {
    std::fclose(job.file);
    throw Error(path, "not a PNG file (bad signature)");
  }
  std::rewind(job.file);
  job.maxBytes = maxDecodedBytes(path);
  bool ok = decodePng(job);
  bool endedEarly = std::feof(job.file);
  std::fclose(job.file);
  if (!ok && endedEarly) throw Error(path, "truncated PNG: the file ends before the image data does");
  if (!ok) throw Error(path, "cannot read PNG: " + printableText(job.error, std::string::npos));

  Image image(int(job.width), int(job.height), job.channels);
  size_t count = image.pixels.size();
  if (job.bitDepth == 8) {
    for (size_t i = 0; i < count; ++i) image.pixels[i] = job.data[i] / 255.0f;
  } else {  // 16-bit samples are big-endian in PNG
    for (size_t i = 0; i < count; ++i) image.pixels[i] = ((job.data[2 * i] << 8) | job.data[2 * i + 1]) / 65535.0f;
  }
  return image;
}

namespace {

// Quantises the image to bitDepth (8 or 16) into job.data and points job.rows at it.
void fillRows(PngJob& job, const Image& image, int bitDepth) {
  job.width = png_uint_32(image.width);
  job.height = png_uint_32(image.height);
  job.channels = image.channels;
  job.bitDepth = bitDepth;
  size_t bytesPerSample = bitDepth / 8;
  job.data.resize(image.pixels.size() * bytesPerSample);
  if (bitDepth == 8) {
    std::transform(image.pixels.begin(), image.pixels.end(), job.data.begin(), quantize8);
  } else {  // PNG stores 16-bit samples big-endian
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      uint16_t v = quantize16(image.pixels[i]);
      job.data[2 * i] = png_byte(v >> 8);
      job.data[2 * i + 1] = png_byte(v & 0xff);
    }
  }
  size_t rowBytes = size_t(image.width) * image.channels * bytesPerSample;
  job.rows.resize(job.height);
  for (png_uint_32 y = 0; y < job.height; ++y) job.rows[y] = job.data.data() + rowBytes * y;
}

}  // namespace

void writePng(const std::string& filePath, const std::string& displayPath, const Image& image, int bitDepth) {
  PngJob job;
  fillRows(job, image, bitDepth);
  job.file = std::fopen(filePath.c_str(), "wb");
  if (!job.file) throw Error(displayPath, std::string("cannot open for writing: ") + std::strerror(errno));
  bool ok = encodePng(job);
  bool flushed = std::fflush(job.file) == 0 && !std::ferror(job.file);
  bool closed = std::fclose(job.file) == 0;
  if (!ok) throw Error(displayPath, "cannot write PNG: " + job.error);
  if (!flushed || !closed) throw Error(displayPath, "write failed (disk full?)");
}

}  // namespace glint::detail

namespace glint {

std::string encodePng(const Image& image) {
  GLINT_CHECK(image.width > 0 && image.height > 0 &&
                  (image.channels == 1 || image.channels == 3 || image.channels == 4) &&
                  image.pixels.size() == size_t(image.width) * image.height * image.channels,
              "encodePng needs a non-empty image with 1, 3 or 4 channels");
  std::string bytes;
  detail::PngJob job;
  detail::fillRows(job, image, 8);
  job.memory = &bytes;
  if (!detail::encodePng(job)) throw Error("cannot encode a PNG in memory: " + job.error);
  return bytes;
}

}  // namespace glint
