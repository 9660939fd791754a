// JPEG reading (8-bit greyscale, YCbCr or RGB; baseline or progressive) and 8-bit writing
// through libjpeg-turbo.
#include <cstdio>  // jpeglib.h uses FILE and size_t without declaring them

#include <jerror.h>
#include <jpeglib.h>

#include <cerrno>
#include <csetjmp>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/printable_text.h"
#include "io/image_codecs.h"

namespace glint::detail {

namespace {

// Quality of written JPEGs: high enough that a smooth render survives above 40 dB PSNR.
constexpr int kJpegQuality = 95;

// A progressive JPEG may legally hold thousands of scans, each re-reading every block, so a
// small file can keep the decoder busy for minutes. Encoders write about ten (libjpeg's
// default progression for colour has 10); past this many the file is refused.
constexpr int kMaxJpegScans = 500;

// libjpeg reports a fatal error by calling error_exit, which must not return (the default
// exits the process). Ours longjmps back to the setjmp of the function that called into
// libjpeg (readHeader, decodePixels, encodeJpeg). Those functions and the callbacks below
// hold only trivially destructible locals, and the message goes into a char array, so a
// longjmp skips no destructor, and no C++ exception ever passes through libjpeg's C frames.
struct JpegErrors {
  jpeg_error_mgr manager{};
  std::jmp_buf jump{};
  char message[JMSG_LENGTH_MAX] = {};
  bool truncated = false;  // the source ran out of bytes before the image did
};

[[noreturn]] void failWith(JpegErrors& errors, const char* message) {
  std::snprintf(errors.message, sizeof(errors.message), "%s", message);
  std::longjmp(errors.jump, 1);
}

JpegErrors& errorsOf(j_common_ptr info) { return *static_cast<JpegErrors*>(info->client_data); }

void onJpegError(j_common_ptr info) {
  JpegErrors& errors = errorsOf(info);
  (*info->err->format_message)(info, errors.message);
  std::longjmp(errors.jump, 1);
}

// Warnings that leave every pixel decoded: metadata libjpeg could not parse, or junk bytes
// between segments. Every other warning means lost or corrupt image data, which libjpeg
// would paper over with grey blocks; a photograph like that must not train a scene.
bool isHarmlessWarning(int code) {
  return code == JWRN_ADOBE_XFORM || code == JWRN_JFIF_MAJOR || code == JWRN_BOGUS_ICC || code == JWRN_EXTRANEOUS_DATA;
}

// msgLevel -1 is a warning; 0 and above are trace messages, which are dropped.
void onJpegMessage(j_common_ptr info, int msgLevel) {
  if (msgLevel >= 0 || isHarmlessWarning(info->err->msg_code)) return;
  JpegErrors& errors = errorsOf(info);
  // The stdio source reports a file that ends early as this warning and pads it with an
  // end-of-image marker, so without this check a truncated file would decode as grey.
  errors.truncated = info->err->msg_code == JWRN_JPEG_EOF;
  (*info->err->format_message)(info, errors.message);
  std::longjmp(errors.jump, 1);
}

// Called by libjpeg as it works through the file; stops the scan flood described above.
void limitScans(j_common_ptr info) {
  if (info->is_decompressor && reinterpret_cast<j_decompress_ptr>(info)->input_scan_number > kMaxJpegScans) {
    failWith(errorsOf(info), "more progressive scans than any encoder writes (corrupt or hostile file)");
  }
}

// Points info's error manager at errors; called before jpeg_create_*, which keeps err and
// client_data.
template <typename Info>
void routeErrors(Info& info, JpegErrors& errors) {
  info.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = onJpegError;
  errors.manager.emit_message = onJpegMessage;
  info.client_data = &errors;
}

// Everything a read needs, owned by readJpeg so that its destructor frees the decoder and
// closes the file however the read ends (a longjmp, or an Error thrown between phases).
struct JpegReadJob {
  std::FILE* file = nullptr;
  JpegErrors errors;
  jpeg_decompress_struct info{};  // value-initialised: jpeg_destroy is a no-op until created
  jpeg_progress_mgr progress{};
  int channels = 0;
  std::vector<uint8_t> data;  // output_width x output_height x channels, row-major

  JpegReadJob() = default;
  JpegReadJob(const JpegReadJob&) = delete;
  JpegReadJob& operator=(const JpegReadJob&) = delete;
  ~JpegReadJob() {
    jpeg_destroy_decompress(&info);
    if (file) std::fclose(file);
  }
};

// Phase 1: reads the markers up to the first scan (size, components, colour space).
// Returns false (job.errors set) on any libjpeg error.
bool readHeader(JpegReadJob& job) {
  routeErrors(job.info, job.errors);
  if (setjmp(job.errors.jump)) return false;
  jpeg_create_decompress(&job.info);
  job.progress.progress_monitor = limitScans;
  job.info.progress = &job.progress;
  jpeg_stdio_src(&job.info, job.file);
  jpeg_read_header(&job.info, TRUE);
  return true;
}

// Phase 2: decodes every scanline into job.data, which the caller has sized for
// job.channels samples per pixel. Returns false (job.errors set) on any libjpeg error.
bool decodePixels(JpegReadJob& job) {
  if (setjmp(job.errors.jump)) return false;
  jpeg_start_decompress(&job.info);
  if (job.info.output_width != job.info.image_width || job.info.output_height != job.info.image_height ||
      job.info.output_components != job.channels) {
    failWith(job.errors, "unexpected layout after conversion");  // cannot happen at scale 1/1
  }
  size_t rowBytes = size_t(job.info.output_width) * size_t(job.channels);
  while (job.info.output_scanline < job.info.output_height) {
    JSAMPROW row = job.data.data() + rowBytes * job.info.output_scanline;
    jpeg_read_scanlines(&job.info, &row, 1);
  }
  jpeg_finish_decompress(&job.info);  // reads on to the end marker, so a cut-off file is noticed
  return true;
}

// The format whose signature starts bytes, for telling the user what a mislabelled file
// really is; nullptr if none Glint reads.
const char* formatBySignature(const std::string& bytes) {
  auto startsWith = [&](const char* signature, size_t length) {
    return bytes.compare(0, length, signature, length) == 0;
  };
  if (startsWith("\x89PNG", 4)) return "PNG";
  if (startsWith("II*\0", 4) || startsWith("MM\0*", 4)) return "TIFF";
  if (startsWith("\x76\x2f\x31\x01", 4)) return "OpenEXR";
  return nullptr;
}

}  // namespace

Image readJpeg(const std::string& path) {
  JpegReadJob job;
  job.file = std::fopen(path.c_str(), "rb");
  if (!job.file) throw Error(path, std::string("cannot open for reading: ") + std::strerror(errno));
  // Every JPEG starts with the start-of-image marker FF D8.
  std::string start(4, '\0');
  start.resize(std::fread(start.data(), 1, start.size(), job.file));
  if (start.compare(0, 2, "\xff\xd8", 2) != 0) {
    const char* actual = formatBySignature(start);
    throw Error(path, actual ? std::string("not a JPEG file: its bytes are ") + actual + ", so give it that extension"
                             : std::string("not a JPEG file (bad signature)"));
  }
  std::rewind(job.file);

  bool ok = readHeader(job);
  if (ok) {
    // Colour is converted to RGB whether stored as YCbCr (nearly every file) or RGB.
    switch (job.info.jpeg_color_space) {
      case JCS_GRAYSCALE: job.channels = 1; break;
      case JCS_YCbCr:
      case JCS_RGB: job.channels = 3, job.info.out_color_space = JCS_RGB; break;
      case JCS_CMYK:
      case JCS_YCCK: throw Error(path, "CMYK JPEG is not supported (convert it to RGB)");
      default:
        throw Error(path, "unsupported JPEG colour layout (" + std::to_string(job.info.num_components) +
                              " components of unknown meaning)");
    }
    // Checked before allocating: the header of a 200-byte file can declare 65500 x 65500.
    checkImageSize(path, job.info.image_width, job.info.image_height, size_t(job.channels), 1);
    job.data.resize(size_t(job.info.image_width) * job.info.image_height * size_t(job.channels));
    ok = decodePixels(job);
  }
  if (!ok && job.errors.truncated) throw Error(path, "truncated JPEG: the file ends before the image data does");
  if (!ok) throw Error(path, "cannot read JPEG: " + printableText(job.errors.message, std::string::npos));

  Image image(int(job.info.output_width), int(job.info.output_height), job.channels);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = job.data[i] / 255.0f;
  return image;
}

namespace {

// Everything a write needs; the destructor frees the encoder however the write ends.
struct JpegWriteJob {
  std::FILE* file = nullptr;  // closed by writeJpeg, which checks that the close succeeded
  JpegErrors errors;
  jpeg_compress_struct info{};
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> data;  // quantised samples, row-major

  JpegWriteJob() = default;
  JpegWriteJob(const JpegWriteJob&) = delete;
  JpegWriteJob& operator=(const JpegWriteJob&) = delete;
  ~JpegWriteJob() { jpeg_destroy_compress(&info); }
};

// Encodes job.data into job.file. Returns false (job.errors set) on any libjpeg error.
bool encodeJpeg(JpegWriteJob& job) {
  routeErrors(job.info, job.errors);
  if (setjmp(job.errors.jump)) return false;
  jpeg_create_compress(&job.info);
  jpeg_stdio_dest(&job.info, job.file);
  job.info.image_width = JDIMENSION(job.width);
  job.info.image_height = JDIMENSION(job.height);
  job.info.input_components = job.channels;
  job.info.in_color_space = job.channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&job.info);
  jpeg_set_quality(&job.info, kJpegQuality, TRUE);
  // Chroma at full resolution (4:4:4) instead of libjpeg's default 4:2:0: renders have
  // colour edges as sharp as their brightness edges, and halving chroma would cost more
  // than the quality setting gains.
  for (int c = 0; c < job.info.num_components; ++c) {
    job.info.comp_info[c].h_samp_factor = 1;
    job.info.comp_info[c].v_samp_factor = 1;
  }
  job.info.optimize_coding = TRUE;  // per-image Huffman tables: smaller files, same pixels
  jpeg_start_compress(&job.info, TRUE);
  size_t rowBytes = size_t(job.width) * size_t(job.channels);
  while (job.info.next_scanline < job.info.image_height) {
    JSAMPROW row = job.data.data() + rowBytes * job.info.next_scanline;
    jpeg_write_scanlines(&job.info, &row, 1);
  }
  jpeg_finish_compress(&job.info);
  return true;
}

}  // namespace

void writeJpeg(const std::string& filePath, const std::string& displayPath, const Image& image) {
  JpegWriteJob job;
  job.width = image.width;
  job.height = image.height;
  job.channels = image.channels;
  job.data.resize(image.pixels.size());
  for (size_t i = 0; i < image.pixels.size(); ++i) job.data[i] = quantize8(image.pixels[i]);
  job.file = std::fopen(filePath.c_str(), "wb");
  if (!job.file) throw Error(displayPath, std::string("cannot open for writing: ") + std::strerror(errno));
  bool ok = encodeJpeg(job);
  bool flushed = std::fflush(job.file) == 0 && !std::ferror(job.file);
  bool closed = std::fclose(job.file) == 0;
  job.file = nullptr;
  if (!ok) throw Error(displayPath, "cannot write JPEG: " + printableText(job.errors.message, std::string::npos));
  if (!flushed || !closed) throw Error(displayPath, "write failed (disk full?)");
}

}  // namespace glint::detail
