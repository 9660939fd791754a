// Image I/O: round trips per format, files written by other tools, and clear errors for bad files.
#include "io/image.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfRgbaFile.h>
#include <gtest/gtest.h>
#include <png.h>
#include <tiffio.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

#include "common/expect_error.h"
#include "core/error.h"
#include "math/rng.h"
#include "temp_folder.h"

namespace glint {
namespace {

using test::expectErrorNaming;

using test::TempFolder;

// Deterministic pixels in [lo, hi), with a few special values mixed in when wide is set.
Image makeImage(int width, int height, int channels, float lo, float hi, uint64_t seed) {
  Image image(width, height, channels);
  Rng rng(seed);
  for (float& v : image.pixels) v = lo + (hi - lo) * rng.uniform();
  return image;
}


TEST(ImageFormat, FromExtensionCaseInsensitive) {
  EXPECT_EQ(imageFormatFromPath("a/b.exr"), ImageFormat::Exr);
  EXPECT_EQ(imageFormatFromPath("B.EXR"), ImageFormat::Exr);
  EXPECT_EQ(imageFormatFromPath("c.tif"), ImageFormat::Tiff);
  EXPECT_EQ(imageFormatFromPath("c.TIFF"), ImageFormat::Tiff);
  EXPECT_EQ(imageFormatFromPath("d.Png"), ImageFormat::Png);
  EXPECT_STREQ(imageFormatExtension(ImageFormat::Exr), ".exr");
  EXPECT_STREQ(imageFormatExtension(ImageFormat::Tiff), ".tiff");
  EXPECT_STREQ(imageFormatExtension(ImageFormat::Png), ".png");
  expectErrorNaming([] { imageFormatFromPath("photo.bmp"); }, "photo.bmp", ".bmp");
  expectErrorNaming([] { imageFormatFromPath("noextension"); }, "noextension");
}

TEST(ImageExr, RoundTripIsExactForOneAndThreeChannels) {
  TempFolder folder;
  for (int channels : {1, 3}) {
    Image image = makeImage(7, 5, channels, -2.0f, 2.0f, 1);
    // Values far outside [0, 1] must survive: float32 is stored as is.
    image.at(0, 0, 0) = 1.0e20f;
    image.at(1, 0, 0) = 1.0e-20f;
    image.at(2, 0, 0) = -12345.678f;
    image.at(6, 4, channels - 1) = 0.0f;
    auto path = folder / ("image" + std::to_string(channels) + ".exr");
    writeImage(path, image);
    Image read = readImage(path);
    EXPECT_EQ(read.width, 7);
    EXPECT_EQ(read.height, 5);
    ASSERT_EQ(read.channels, channels);
    EXPECT_EQ(read.pixels, image.pixels);
  }
}

TEST(ImageExr, ReadsHalfRgbaWrittenByOpenExr) {
  TempFolder folder;
  auto path = folder / "half.exr";
  const int width = 6, height = 4;
  std::vector<Imf::Rgba> pixels(width * height);
  for (int i = 0; i < width * height; ++i) pixels[i] = Imf::Rgba(half(0.5f * i), half(-1.0f * i), half(100.0f + i), half(0.25f));
  {
    Imf::RgbaOutputFile file(path.c_str(), width, height, Imf::WRITE_RGBA);
    file.setFrameBuffer(pixels.data(), 1, width);
    file.writePixels(height);
  }
  Image read = readImage(path);
  ASSERT_EQ(read.channels, 3);  // alpha ignored
  ASSERT_EQ(read.width, width);
  ASSERT_EQ(read.height, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      int i = y * width + x;
      EXPECT_EQ(read.rgb(x, y), Rgb(0.5f * i, -1.0f * i, float(half(100.0f + i))));
    }
  }
}

TEST(ImageExr, ReadsSingleHalfChannelOfAnyNameWithOffsetDataWindow) {
  TempFolder folder;
  auto path = folder / "depth.exr";
  // Data window not at the origin: pixel (0, 0) of the image is file pixel (10, 20).
  Imath::Box2i window({10, 20}, {14, 22});
  Imf::Header header(window, window);
  header.channels().insert("Z", Imf::Channel(Imf::HALF));
  std::vector<half> depth(5 * 3);
  for (size_t i = 0; i < depth.size(); ++i) depth[i] = half(1.5f + float(i));
  Imf::FrameBuffer frame;
  frame.insert("Z", Imf::Slice::Make(Imf::HALF, depth.data(), window));
  {
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(3);
  }
  Image read = readImage(path);
  ASSERT_EQ(read.channels, 1);
  ASSERT_EQ(read.width, 5);
  ASSERT_EQ(read.height, 3);
  for (size_t i = 0; i < depth.size(); ++i) EXPECT_EQ(read.pixels[i], 1.5f + float(i));
}

TEST(ImageExr, RejectsUnsupportedChannelLayout) {
  TempFolder folder;
  auto path = folder / "uv.exr";
  Imf::Header header(2, 2);
  header.channels().insert("U", Imf::Channel(Imf::FLOAT));
  header.channels().insert("V", Imf::Channel(Imf::FLOAT));
  std::vector<float> u(4, 0.0f), v(4, 1.0f);
  Imf::FrameBuffer frame;
  frame.insert("U", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(u.data()), sizeof(float), 2 * sizeof(float)));
  frame.insert("V", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(v.data()), sizeof(float), 2 * sizeof(float)));
  {
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(2);
  }
  expectErrorNaming([&] { readImage(path); }, path, "U, V");
}

TEST(ImageTiff, HalfRoundTripWithinHalfPrecision) {
  TempFolder folder;
  for (int channels : {1, 3}) {
    Image image = makeImage(7, 5, channels, 0.001f, 4.0f, 2);
    image.at(0, 0, 0) = 60000.0f;  // near the top of half's range
    image.at(1, 0, 0) = -3.25f;
    image.at(2, 0, 0) = 0.0f;
    for (const char* ext : {".tiff", ".tif"}) {
      auto path = folder / ("image" + std::to_string(channels) + ext);
      writeImage(path, image);
      Image read = readImage(path);
      EXPECT_EQ(read.width, 7);
      EXPECT_EQ(read.height, 5);
      ASSERT_EQ(read.channels, channels);
      for (size_t i = 0; i < image.pixels.size(); ++i) {
        EXPECT_LE(std::abs(read.pixels[i] - image.pixels[i]), 1e-3f * std::abs(image.pixels[i])) << i;
      }
    }
  }
}

// Writes a striped TIFF with the given sample layout, raw little-endian bytes in data.
void writeRawTiff(const std::filesystem::path& path, int width, int height, int samples, int bits, int format,
                  const std::vector<uint8_t>& data) {
  TIFF* tif = TIFFOpen(path.c_str(), "w");
  ASSERT_NE(tif, nullptr);
  TIFFSetField(tif, TIFFTAG_IMAGEWIDTH, uint32_t(width));
  TIFFSetField(tif, TIFFTAG_IMAGELENGTH, uint32_t(height));
  TIFFSetField(tif, TIFFTAG_SAMPLESPERPIXEL, uint16_t(samples));
  TIFFSetField(tif, TIFFTAG_BITSPERSAMPLE, uint16_t(bits));
  TIFFSetField(tif, TIFFTAG_SAMPLEFORMAT, uint16_t(format));
  TIFFSetField(tif, TIFFTAG_PLANARCONFIG, uint16_t(PLANARCONFIG_CONTIG));
  TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, uint16_t(samples >= 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK));
  if (samples == 4) {
    uint16_t extra = EXTRASAMPLE_UNASSALPHA;
    TIFFSetField(tif, TIFFTAG_EXTRASAMPLES, uint16_t(1), &extra);
  }
  size_t rowBytes = size_t(width) * samples * bits / 8;
  for (int y = 0; y < height; ++y) {
    TIFFWriteScanline(tif, const_cast<uint8_t*>(data.data() + rowBytes * y), uint32_t(y), 0);
  }
  TIFFClose(tif);
}

TEST(ImageTiff, ReadsUnsignedAndFloat32Layouts) {
  TempFolder folder;
  const int width = 3, height = 2;
  {  // 8-bit RGBA: alpha dropped, scaled by 1/255
    std::vector<uint8_t> data(width * height * 4);
    for (size_t i = 0; i < data.size(); ++i) data[i] = uint8_t(i * 10);
    auto path = folder / "rgba8.tif";
    writeRawTiff(path, width, height, 4, 8, SAMPLEFORMAT_UINT, data);
    Image read = readImage(path);
    ASSERT_EQ(read.channels, 3);
    for (int p = 0; p < width * height; ++p) {
      for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(read.pixels[p * 3 + c], data[p * 4 + c] / 255.0f);
    }
  }
  {  // 16-bit grey, scaled by 1/65535
    std::vector<uint16_t> values = {0, 1, 1000, 32768, 65000, 65535};
    std::vector<uint8_t> data(values.size() * 2);
    std::memcpy(data.data(), values.data(), data.size());
    auto path = folder / "grey16.tif";
    writeRawTiff(path, width, height, 1, 16, SAMPLEFORMAT_UINT, data);
    Image read = readImage(path);
    ASSERT_EQ(read.channels, 1);
    for (size_t i = 0; i < values.size(); ++i) EXPECT_FLOAT_EQ(read.pixels[i], values[i] / 65535.0f);
  }
  {  // 32-bit float RGB, exact
    Image image = makeImage(width, height, 3, -100.0f, 100.0f, 3);
    std::vector<uint8_t> data(image.pixels.size() * 4);
    std::memcpy(data.data(), image.pixels.data(), data.size());
    auto path = folder / "rgb32.tiff";
    writeRawTiff(path, width, height, 3, 32, SAMPLEFORMAT_IEEEFP, data);
    EXPECT_EQ(readImage(path).pixels, image.pixels);
  }
  {  // signed integers are not a supported layout
    auto path = folder / "signed.tiff";
    writeRawTiff(path, width, height, 1, 16, SAMPLEFORMAT_INT, std::vector<uint8_t>(width * height * 2));
    expectErrorNaming([&] { readImage(path); }, path, "unsupported TIFF sample type");
  }
}

TEST(ImagePng, RoundTripWithinHalfAnEightBitStep) {
  TempFolder folder;
  for (int channels : {1, 3}) {
    Image image = makeImage(7, 5, channels, 0.0f, 1.0f, 4);
    image.at(0, 0, 0) = 0.0f;
    image.at(1, 0, 0) = 1.0f;
    auto path = folder / ("image" + std::to_string(channels) + ".png");
    writeImage(path, image);
    Image read = readImage(path);
    EXPECT_EQ(read.width, 7);
    EXPECT_EQ(read.height, 5);
    ASSERT_EQ(read.channels, channels);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      EXPECT_LE(std::abs(read.pixels[i] - image.pixels[i]), 0.5f / 255.0f + 1e-6f) << i;
    }
  }
}

// PNG's IHDR bit depth: the byte after the signature (8), chunk length and type (8), and
// width and height (8).
int pngBitDepth(const std::filesystem::path& path) { return uint8_t(test::readBytes(path).at(24)); }

TEST(ImagePng, SixteenBitRoundTripIsExactToOneCode) {
  TempFolder folder;
  for (int channels : {1, 3}) {
    // Every value a 16-bit code: read back exactly.
    Image codes(61, 7, channels);
    Rng rng(12);
    for (float& v : codes.pixels) v = float(rng.nextUint() % 65536) / 65535.0f;
    codes.pixels[0] = 0.0f;
    codes.pixels[1] = 1.0f;
    codes.pixels[2] = 1.0f / 65535.0f;  // the smallest step, lost at 8 bits
    auto path = folder / ("codes" + std::to_string(channels) + ".png");
    writeImage(path, codes, {.pngBitDepth = 16});
    EXPECT_EQ(pngBitDepth(path), 16);
    Image read = readImage(path);
    EXPECT_EQ(read.width, 61);
    EXPECT_EQ(read.height, 7);
    ASSERT_EQ(read.channels, channels);
    EXPECT_EQ(read.pixels, codes.pixels);

    // Any other value: within half a 16-bit step, out-of-range values clamped.
    Image image = makeImage(9, 5, channels, -0.1f, 1.1f, 13);
    writeImage(path, image, {.pngBitDepth = 16});
    read = readImage(path);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      EXPECT_NEAR(read.pixels[i], std::clamp(image.pixels[i], 0.0f, 1.0f), 0.5f / 65535.0f + 1e-7f) << i;
    }
  }
  // RGBA: alpha is written, and dropped on reading as for 8 bits.
  Image rgba(2, 1, 4);
  rgba.pixels = {0.1f, 0.2f, 0.3f, 0.4f, 1.0f, 0.0f, 0.5f, 1.0f};
  writeImage(folder / "rgba16.png", rgba, {.pngBitDepth = 16});
  Image read = readImage(folder / "rgba16.png");
  ASSERT_EQ(read.channels, 3);
  EXPECT_NEAR(read.at(1, 0, 2), 0.5f, 0.5f / 65535.0f);
  // The default stays 8-bit.
  writeImage(folder / "default.png", rgba);
  EXPECT_EQ(pngBitDepth(folder / "default.png"), 8);
}

TEST(ImagePng, EncodesInMemoryTheSameBytesAsTheFile) {
  TempFolder folder;
  Image image = makeImage(9, 4, 3, -0.2f, 1.2f, 11);
  std::string bytes = encodePng(image);
  ASSERT_GE(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  writeImage(folder / "file.png", image);
  EXPECT_EQ(bytes, test::readBytes(folder / "file.png"));
  test::writeBytes(folder / "memory.png", bytes);
  Image read = readImage(folder / "memory.png");
  ASSERT_EQ(read.width, 9);
  ASSERT_EQ(read.channels, 3);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    EXPECT_NEAR(read.pixels[i], std::clamp(image.pixels[i], 0.0f, 1.0f), 0.5f / 255.0f + 1e-6f) << i;
}

TEST(ImagePng, ClampsOutOfRangeAndDropsAlpha) {
  TempFolder folder;
  Image image(2, 1, 4);
  image.pixels = {-1.0f, 2.0f, NAN, 0.5f, 0.2f, 0.4f, 0.6f, 0.8f};
  auto path = folder / "rgba.png";
  writeImage(path, image);
  Image read = readImage(path);
  ASSERT_EQ(read.channels, 3);
  EXPECT_EQ(read.rgb(0, 0), Rgb(0.0f, 1.0f, 0.0f));
  EXPECT_NEAR(read.at(1, 0, 2), 0.6f, 0.5f / 255.0f);
}

TEST(ImagePng, ReadsSixteenBitAndPaletteFiles) {
  TempFolder folder;
  {  // 16-bit RGB (the simplified API stores "linear" formats as 16-bit samples unchanged)
    png_image info{};
    info.version = PNG_IMAGE_VERSION;
    info.width = 3;
    info.height = 1;
    info.format = PNG_FORMAT_LINEAR_RGB;
    std::vector<uint16_t> values = {0, 65535, 1000, 20000, 40000, 60000, 1, 2, 3};
    auto path = folder / "rgb16.png";
    ASSERT_TRUE(png_image_write_to_file(&info, path.c_str(), 0, values.data(), 0, nullptr));
    Image read = readImage(path);
    ASSERT_EQ(read.channels, 3);
    for (size_t i = 0; i < values.size(); ++i) EXPECT_FLOAT_EQ(read.pixels[i], values[i] / 65535.0f);
  }
  {  // 8-bit palette: expanded to RGB
    png_image info{};
    info.version = PNG_IMAGE_VERSION;
    info.width = 2;
    info.height = 2;
    info.format = PNG_FORMAT_RGB_COLORMAP;
    info.colormap_entries = 2;
    std::vector<uint8_t> colormap = {255, 0, 0, 10, 20, 30};
    std::vector<uint8_t> indices = {0, 1, 1, 0};
    auto path = folder / "palette.png";
    ASSERT_TRUE(png_image_write_to_file(&info, path.c_str(), 0, indices.data(), 0, colormap.data()));
    Image read = readImage(path);
    ASSERT_EQ(read.channels, 3);
    EXPECT_EQ(read.rgb(0, 0), Rgb(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(read.rgb(1, 0), Rgb(10 / 255.0f, 20 / 255.0f, 30 / 255.0f));
  }
  {  // grey + alpha: alpha dropped
    png_image info{};
    info.version = PNG_IMAGE_VERSION;
    info.width = 2;
    info.height = 1;
    info.format = PNG_FORMAT_GA;
    std::vector<uint8_t> values = {51, 255, 102, 255};
    auto path = folder / "ga.png";
    ASSERT_TRUE(png_image_write_to_file(&info, path.c_str(), 0, values.data(), 0, nullptr));
    Image read = readImage(path);
    ASSERT_EQ(read.channels, 1);
    EXPECT_FLOAT_EQ(read.pixels[0], 0.2f);
    EXPECT_FLOAT_EQ(read.pixels[1], 0.4f);
  }
}

TEST(ImageErrors, MissingFileAndUnknownExtension) {
  TempFolder folder;
  for (const char* name : {"missing.exr", "missing.tiff", "missing.png", "missing.jpg"}) {
    expectErrorNaming([&] { readImage(folder / name); }, folder / name, "not found");
  }
  expectErrorNaming([&] { readImage(folder / "image.bmp"); }, folder / "image.bmp", ".bmp");
  expectErrorNaming([&] { writeImage(folder / "image.bmp", Image(2, 2, 3)); }, folder / "image.bmp", ".bmp");
}

TEST(ImageErrors, TruncatedFilesNameTheFile) {
  TempFolder folder;
  // Large enough that half the file cuts through pixel data, not just the header.
  Image image = makeImage(64, 48, 3, 0.0f, 1.0f, 5);
  for (const char* name : {"cut.exr", "cut.tiff", "cut.png", "cut.jpg"}) {
    auto path = folder / name;
    writeImage(path, image);
    test::truncateToHalf(path);
    expectErrorNaming([&] { readImage(path); }, path);
  }
  auto png = folder / "cut.png";
  expectErrorNaming([&] { readImage(png); }, png, "truncated");
}

TEST(ImageErrors, GarbageBytesNameTheFile) {
  TempFolder folder;
  std::string garbage;
  Rng rng(6);
  for (int i = 0; i < 4096; ++i) garbage.push_back(char(rng.nextUint()));
  for (const char* name : {"garbage.exr", "garbage.tiff", "garbage.png", "garbage.jpg"}) {
    auto path = folder / name;
    test::writeBytes(path, garbage);
    expectErrorNaming([&] { readImage(path); }, path);
  }
  auto empty = folder / "empty.exr";
  test::writeBytes(empty, "");
  expectErrorNaming([&] { readImage(empty); }, empty);
}

// Issue 19: a header's size is checked against the bytes the file holds before anything
// is allocated. A PNG of 8 x 8 pixels relabelled 30000 x 30000 (within kMaxImagePixels) made
// the reader allocate 2.7 GB of rows and 10.8 GB of floats; so did a TIFF with one row.
TEST(ImageErrors, HeaderSizesBeyondTheFileAreRefusedBeforeAllocating) {
  TempFolder folder;
  auto png = folder / "relabelled.png";
  writeImage(png, makeImage(8, 8, 3, 0.0f, 1.0f, 7));
  std::string bytes = test::readBytes(png);
  // IHDR: signature (8), length (4), "IHDR" (4), width and height big-endian, CRC at 29.
  auto put32 = [&](size_t at, uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes[at + i] = char(v >> (24 - 8 * i));
  };
  put32(16, 30000);
  put32(20, 30000);
  put32(29, uint32_t(crc32(0, reinterpret_cast<const Bytef*>(bytes.data() + 12), 17)));
  test::writeBytes(png, bytes);
  expectErrorNaming([&] { readImage(png); }, png, "larger than the file's data can hold");

  auto tiff = folder / "one_row.tiff";
  TIFF* out = TIFFOpen(tiff.c_str(), "w");
  ASSERT_NE(out, nullptr);
  TIFFSetField(out, TIFFTAG_IMAGEWIDTH, 30000u);
  TIFFSetField(out, TIFFTAG_IMAGELENGTH, 30000u);
  TIFFSetField(out, TIFFTAG_SAMPLESPERPIXEL, 3);
  TIFFSetField(out, TIFFTAG_BITSPERSAMPLE, 8);
  TIFFSetField(out, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_RGB);
  TIFFSetField(out, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  TIFFSetField(out, TIFFTAG_ROWSPERSTRIP, 30000u);
  std::vector<uint8_t> row(30000 * 3, 0);
  ASSERT_EQ(TIFFWriteScanline(out, row.data(), 0, 0), 1);
  TIFFClose(out);
  expectErrorNaming([&] { readImage(tiff); }, tiff, "more than a file of");
}

TEST(ImageErrors, BadWritesLeaveNoFile) {
  TempFolder folder;
  expectErrorNaming([&] { writeImage(folder / "empty.exr", Image(0, 5, 3)); }, folder / "empty.exr", "empty");
  expectErrorNaming([&] { writeImage(folder / "two.tiff", Image(2, 2, 2)); }, folder / "two.tiff", "2 channels");
  expectErrorNaming([&] { writeImage(folder / "four.exr", Image(2, 2, 4)); }, folder / "four.exr", "4 channels");
  EXPECT_TRUE(std::filesystem::is_empty(folder.path()));
}

TEST(ImageErrors, WriteCreatesMissingFolders) {
  TempFolder folder;
  auto path = folder / "train" / "depth" / "depth_0000.exr";
  writeImage(path, Image(4, 2, 1, 7.0f));
  EXPECT_EQ(readImage(path).pixels, std::vector<float>(8, 7.0f));
}

TEST(ImageErrors, OverwriteReplacesTheOldFile) {
  TempFolder folder;
  auto path = folder / "image.exr";
  writeImage(path, Image(3, 3, 1, 1.0f));
  writeImage(path, Image(2, 4, 3, 2.0f));
  Image read = readImage(path);
  EXPECT_EQ(read.width, 2);
  EXPECT_EQ(read.channels, 3);
  EXPECT_EQ(read.at(1, 3, 2), 2.0f);
  // Only the image itself: no temporary files left beside it.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(folder.path()), {}), 1);
}

}  // namespace
}  // namespace glint
