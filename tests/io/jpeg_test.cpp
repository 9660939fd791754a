// JPEG I/O: round trips within JPEG's error, files written by libjpeg itself (progressive,
// subsampled, RGB-coded), and one clear error naming the file for bad ones.
#include <cstdio>  // jpeglib.h uses FILE and size_t without declaring them

#include <gtest/gtest.h>
#include <jpeglib.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "common/expect_error.h"
#include "io/image.h"
#include "math/rng.h"
#include "temp_folder.h"

namespace glint {
namespace {

using test::expectErrorNaming;
using test::TempFolder;

// A smooth image in [0.05, 0.95]: gradients and low-frequency waves, what JPEG is made for.
Image smoothImage(int width, int height, int channels) {
  Image image(width, height, channels);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float u = float(x) / float(width), v = float(y) / float(height);
      for (int c = 0; c < channels; ++c) {
        float wave = std::sin(6.0f * u + 2.0f * float(c)) * std::cos(4.0f * v - float(c));
        image.at(x, y, c) = 0.5f + 0.3f * wave + 0.15f * (u - v);
      }
    }
  }
  return image;
}

// Peak signal-to-noise ratio in dB for values in [0, 1].
double psnr(const Image& a, const Image& b) {
  double squared = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    double difference = double(a.pixels[i]) - double(b.pixels[i]);
    squared += difference * difference;
  }
  return 10.0 * std::log10(double(a.pixels.size()) / squared);
}

// Writes 8-bit samples (width x height x components) as a JPEG with libjpeg directly, after
// configure has adjusted the defaults: the files other tools write, not Glint's writer.
void writeWithLibjpeg(const std::filesystem::path& path, int width, int height, int components, J_COLOR_SPACE space,
                      const std::vector<uint8_t>& samples,
                      const std::function<void(jpeg_compress_struct&)>& configure = {}) {
  jpeg_compress_struct info{};
  jpeg_error_mgr errors{};
  info.err = jpeg_std_error(&errors);
  jpeg_create_compress(&info);
  std::FILE* file = std::fopen(path.c_str(), "wb");
  ASSERT_NE(file, nullptr);
  jpeg_stdio_dest(&info, file);
  info.image_width = JDIMENSION(width);
  info.image_height = JDIMENSION(height);
  info.input_components = components;
  info.in_color_space = space;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, 90, TRUE);
  if (configure) configure(info);
  jpeg_start_compress(&info, TRUE);
  std::vector<uint8_t> row;
  while (info.next_scanline < info.image_height) {
    row.assign(samples.begin() + ptrdiff_t(info.next_scanline) * width * components,
               samples.begin() + ptrdiff_t(info.next_scanline + 1) * width * components);
    JSAMPROW rows[1] = {row.data()};
    jpeg_write_scanlines(&info, rows, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  std::fclose(file);
}

std::vector<uint8_t> toBytes(const Image& image) {
  std::vector<uint8_t> bytes(image.pixels.size());
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = uint8_t(std::lround(image.pixels[i] * 255.0f));
  return bytes;
}

Image fromBytes(const std::vector<uint8_t>& bytes, int width, int height, int channels) {
  Image image(width, height, channels);
  for (size_t i = 0; i < bytes.size(); ++i) image.pixels[i] = bytes[i] / 255.0f;
  return image;
}

TEST(ImageJpeg, ExtensionsAreRecognised) {
  EXPECT_EQ(imageFormatFromPath("photo.jpg"), ImageFormat::Jpeg);
  EXPECT_EQ(imageFormatFromPath("a/IMG_0001.JPG"), ImageFormat::Jpeg);
  EXPECT_EQ(imageFormatFromPath("b.jpeg"), ImageFormat::Jpeg);
  EXPECT_EQ(imageFormatFromPath("b.JPeg"), ImageFormat::Jpeg);
  EXPECT_STREQ(imageFormatExtension(ImageFormat::Jpeg), ".jpg");
  expectErrorNaming([] { imageFormatFromPath("photo.jpe"); }, "photo.jpe", ".jpg or .jpeg");
}

TEST(ImageJpeg, ColourRoundTripAboveFortyDecibels) {
  TempFolder folder;
  Image image = smoothImage(64, 48, 3);
  for (const char* name : {"smooth.jpg", "smooth.JPEG"}) {
    writeImage(folder / name, image);
    Image read = readImage(folder / name);
    EXPECT_EQ(read.width, 64);
    EXPECT_EQ(read.height, 48);
    ASSERT_EQ(read.channels, 3);
    EXPECT_GT(psnr(read, image), 40.0) << name;
  }
}

TEST(ImageJpeg, GreyRoundTripStaysOneChannel) {
  TempFolder folder;
  Image image = smoothImage(40, 24, 1);
  writeImage(folder / "grey.jpg", image);
  Image read = readImage(folder / "grey.jpg");
  EXPECT_EQ(read.width, 40);
  EXPECT_EQ(read.height, 24);
  ASSERT_EQ(read.channels, 1);
  EXPECT_GT(psnr(read, image), 40.0);
}

TEST(ImageJpeg, OddSizesAndClampedValues) {
  TempFolder folder;
  // Sizes that are not multiples of the 8x8 blocks; out-of-range values clamp like PNG.
  for (auto [width, height] : {std::pair{1, 1}, std::pair{13, 7}, std::pair{9, 17}}) {
    for (int channels : {1, 3}) {
      Image image(width, height, channels, 0.5f);
      image.pixels[0] = -3.0f;
      if (image.pixels.size() > 1) image.pixels[1] = 7.0f;
      auto path = folder / ("odd_" + std::to_string(width) + "x" + std::to_string(height) + ".jpg");
      writeImage(path, image);
      Image read = readImage(path);
      EXPECT_EQ(read.width, width);
      EXPECT_EQ(read.height, height);
      EXPECT_EQ(read.channels, channels);
      for (float v : read.pixels) {
        EXPECT_GE(v, 0.0f);
        EXPECT_LE(v, 1.0f);
      }
    }
  }
}

TEST(ImageJpeg, WritesFullResolutionChroma) {
  TempFolder folder;
  auto path = folder / "chroma.jpg";
  writeImage(path, smoothImage(16, 16, 3));
  jpeg_decompress_struct info{};
  jpeg_error_mgr errors{};
  info.err = jpeg_std_error(&errors);
  jpeg_create_decompress(&info);
  std::FILE* file = std::fopen(path.c_str(), "rb");
  ASSERT_NE(file, nullptr);
  jpeg_stdio_src(&info, file);
  jpeg_read_header(&info, TRUE);
  ASSERT_EQ(info.num_components, 3);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(info.comp_info[c].h_samp_factor, 1) << c;
    EXPECT_EQ(info.comp_info[c].v_samp_factor, 1) << c;
  }
  jpeg_destroy_decompress(&info);
  std::fclose(file);
}

TEST(ImageJpeg, ReadsProgressiveSubsampledAndRgbCodedFiles) {
  TempFolder folder;
  const int width = 37, height = 21;
  Image colour = smoothImage(width, height, 3);
  std::vector<uint8_t> samples = toBytes(colour);
  Image exact = fromBytes(samples, width, height, 3);
  struct Variant {
    const char* name;
    J_COLOR_SPACE space;
    std::function<void(jpeg_compress_struct&)> configure;
  };
  std::vector<Variant> variants = {
      {"baseline_420.jpg", JCS_RGB, {}},  // libjpeg's defaults: YCbCr, chroma halved both ways
      {"progressive.jpg", JCS_RGB, [](jpeg_compress_struct& info) { jpeg_simple_progression(&info); }},
      {"rgb_coded.jpg", JCS_RGB, [](jpeg_compress_struct& info) { jpeg_set_colorspace(&info, JCS_RGB); }},
      {"restart_markers.jpg", JCS_RGB, [](jpeg_compress_struct& info) { info.restart_in_rows = 1; }},
      {"arithmetic.jpg", JCS_RGB, [](jpeg_compress_struct& info) { info.arith_code = TRUE; }},
  };
  for (const Variant& variant : variants) {
    auto path = folder / variant.name;
    writeWithLibjpeg(path, width, height, 3, variant.space, samples, variant.configure);
    Image read = readImage(path);
    EXPECT_EQ(read.width, width) << variant.name;
    EXPECT_EQ(read.height, height) << variant.name;
    ASSERT_EQ(read.channels, 3) << variant.name;
    EXPECT_GT(psnr(read, exact), 30.0) << variant.name;  // quality 90, some with halved chroma
  }
  {  // progressive greyscale
    Image grey = smoothImage(width, height, 1);
    auto path = folder / "progressive_grey.jpg";
    writeWithLibjpeg(path, width, height, 1, JCS_GRAYSCALE, toBytes(grey),
                     [](jpeg_compress_struct& info) { jpeg_simple_progression(&info); });
    Image read = readImage(path);
    ASSERT_EQ(read.channels, 1);
    EXPECT_GT(psnr(read, fromBytes(toBytes(grey), width, height, 1)), 35.0);
  }
}

TEST(ImageJpeg, RefusesCmykClearly) {
  TempFolder folder;
  auto path = folder / "print.jpg";
  writeWithLibjpeg(path, 8, 8, 4, JCS_CMYK, std::vector<uint8_t>(8 * 8 * 4, 100));
  expectErrorNaming([&] { readImage(path); }, path, "CMYK");
}

TEST(ImageJpeg, TruncatedFilesNameTheFile) {
  TempFolder folder;
  auto baseline = folder / "cut.jpg";
  writeImage(baseline, smoothImage(64, 48, 3));
  test::truncateToHalf(baseline);
  expectErrorNaming([&] { readImage(baseline); }, baseline, "truncated");

  auto progressive = folder / "cut_progressive.jpg";
  writeWithLibjpeg(progressive, 64, 48, 3, JCS_RGB, toBytes(smoothImage(64, 48, 3)),
                   [](jpeg_compress_struct& info) { jpeg_simple_progression(&info); });
  test::truncateToHalf(progressive);
  expectErrorNaming([&] { readImage(progressive); }, progressive, "truncated");

  // Cut inside the header, and cut just before the end-of-image marker.
  auto header = folder / "cut_header.jpg";
  writeImage(header, smoothImage(16, 16, 3));
  std::string bytes = test::readBytes(header);
  test::writeBytes(header, bytes.substr(0, 30));
  expectErrorNaming([&] { readImage(header); }, header);
  auto end = folder / "cut_end.jpg";
  test::writeBytes(end, bytes.substr(0, bytes.size() - 2));
  expectErrorNaming([&] { readImage(end); }, end, "truncated");
}

TEST(ImageJpeg, CorruptScanDataIsAnErrorNotGreyBlocks) {
  TempFolder folder;
  auto path = folder / "corrupt.jpg";
  writeImage(path, smoothImage(64, 48, 3));
  std::string bytes = test::readBytes(path);
  // An end-of-image marker in the middle of the entropy-coded data, which follows the
  // start-of-scan segment (FF DA, then its length): libjpeg would warn and fill the rest of
  // the image with grey.
  size_t sos = bytes.find("\xff\xda");
  ASSERT_NE(sos, std::string::npos);
  size_t scanStart = sos + 2 + size_t((uint8_t(bytes[sos + 2]) << 8) | uint8_t(bytes[sos + 3]));
  size_t middle = (scanStart + bytes.size()) / 2;
  bytes[middle] = '\xff';
  bytes[middle + 1] = '\xd9';
  test::writeBytes(path, bytes);
  expectErrorNaming([&] { readImage(path); }, path, "Corrupt JPEG data");
}

TEST(ImageJpeg, OtherBytesWithAJpegExtensionAreRefused) {
  TempFolder folder;
  auto garbage = folder / "garbage.jpg";
  std::string noise;
  Rng rng(8);
  for (int i = 0; i < 4096; ++i) noise.push_back(char(rng.nextUint()));
  noise[0] = 'G';  // so it cannot start with the JPEG marker by chance
  test::writeBytes(garbage, noise);
  expectErrorNaming([&] { readImage(garbage); }, garbage, "not a JPEG file");

  // A PNG saved under a .jpg name: the message says what the file really is.
  auto png = folder / "really_png.png";
  writeImage(png, Image(4, 4, 3, 0.5f));
  auto misnamed = folder / "misnamed.jpg";
  std::filesystem::copy_file(png, misnamed);
  expectErrorNaming([&] { readImage(misnamed); }, misnamed, {"not a JPEG file", "PNG"});

  auto empty = folder / "empty.jpeg";
  test::writeBytes(empty, "");
  expectErrorNaming([&] { readImage(empty); }, empty, "not a JPEG file");

  // The start-of-image marker and then nothing a decoder can use.
  auto soiOnly = folder / "soi_only.jpg";
  test::writeBytes(soiOnly, std::string("\xff\xd8\xff\xd9", 4));
  expectErrorNaming([&] { readImage(soiOnly); }, soiOnly, "cannot read JPEG");
}

// The frame header of a 16 x 16 file relabelled 30000 x 30000: refused from the header,
// before 2.7 GB of samples are allocated.
TEST(ImageJpeg, HeaderSizesBeyondTheFileAreRefusedBeforeAllocating) {
  TempFolder folder;
  auto path = folder / "relabelled.jpg";
  writeImage(path, smoothImage(16, 16, 3));
  std::string bytes = test::readBytes(path);
  // Baseline start of frame: FF C0, length (2), precision (1), height (2), width (2).
  size_t sof = bytes.find("\xff\xc0");
  ASSERT_NE(sof, std::string::npos);
  for (size_t at : {sof + 5, sof + 7}) {
    bytes[at] = char(30000 >> 8);
    bytes[at + 1] = char(30000 & 0xff);
  }
  test::writeBytes(path, bytes);
  expectErrorNaming([&] { readImage(path); }, path, "more than a file of");
}

// A progressive file may hold any number of scans; each one re-reads every block, so a
// flood of them is refused (here 631 valid scans: one bit of one coefficient at a time).
TEST(ImageJpeg, RefusesAFloodOfProgressiveScans) {
  TempFolder folder;
  auto path = folder / "many_scans.jpg";
  std::vector<jpeg_scan_info> script;
  script.push_back({1, {0}, 0, 0, 0, 0});  // DC, all bits
  for (int k = 1; k <= 63; ++k) {
    script.push_back({1, {0}, k, k, 0, 9});  // coefficient k, all but the low 9 bits
    for (int bit = 9; bit >= 1; --bit) script.push_back({1, {0}, k, k, bit, bit - 1});
  }
  ASSERT_EQ(script.size(), 631u);
  std::vector<uint8_t> samples = toBytes(smoothImage(8, 8, 1));
  writeWithLibjpeg(path, 8, 8, 1, JCS_GRAYSCALE, samples, [&](jpeg_compress_struct& info) {
    info.scan_info = script.data();
    info.num_scans = int(script.size());
  });
  expectErrorNaming([&] { readImage(path); }, path, "progressive scans");
}

TEST(ImageJpeg, WriteRefusesWhatJpegCannotHold) {
  TempFolder folder;
  expectErrorNaming([&] { writeImage(folder / "rgba.jpg", Image(2, 2, 4)); }, folder / "rgba.jpg", "4 channels");
  expectErrorNaming([&] { writeImage(folder / "deep.jpg", Image(2, 2, 1), {.pngBitDepth = 16}); },
                    folder / "deep.jpg", "8-bit");
  EXPECT_TRUE(std::filesystem::is_empty(folder.path()));
}

}  // namespace
}  // namespace glint
