// Internal to src/io: the per-format image readers and writers that image.cpp dispatches to.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/image.h"

namespace glint::detail {

// Largest image a reader will allocate, so a corrupt header cannot ask for terabytes
// (4 gigapixels; Glint's own images are a few megapixels).
constexpr size_t kMaxImagePixels = size_t(1) << 32;

// Readers take the path for error messages and open it themselves; they return an image
// with 1 or 3 channels (readPng: see PngChannels) and throw Error naming the file.
Image readExr(const std::string& path);
Image readTiff(const std::string& path);
// What readPng does with alpha and grey.
enum class PngChannels {
  DropAlpha,  // 1 grey or 3 RGB
  Rgba,       // 3 RGB, or 4 RGBA when the file has alpha (grey expanded to RGB)
  AsStored,   // 1 grey, 2 grey and alpha, 3 RGB, 4 RGBA: as the file holds them
};
Image readPng(const std::string& path, PngChannels channels = PngChannels::DropAlpha);
Image readJpeg(const std::string& path);

// Writers write to filePath (a temporary file) but name displayPath in errors. The image
// has already been checked to be non-empty with a channel count the format supports.
void writeExr(const std::string& filePath, const std::string& displayPath, const Image& image);
void writeTiff(const std::string& filePath, const std::string& displayPath, const Image& image);
void writePng(const std::string& filePath, const std::string& displayPath, const Image& image, int bitDepth);
void writeJpeg(const std::string& filePath, const std::string& displayPath, const Image& image);

// [0, 1] -> 0..255 or 0..65535, rounding to nearest; NaN and negatives -> 0, above 1 -> the
// top code. Shared by the integer writers so PNG and JPEG quantise alike.
inline uint8_t quantize8(float v) {
  if (!(v > 0.0f)) return 0;
  return uint8_t(std::lround(std::min(v, 1.0f) * 255.0f));
}
inline uint16_t quantize16(float v) {
  if (!(v > 0.0f)) return 0;
  return uint16_t(std::lround(std::min(v, 1.0f) * 65535.0f));
}

// The most bytes of samples the file at path can decode to: kMaxCompressionRatio times its
// size, but at least kMinDecodedBytes. No codec Glint reads expands data further (deflate
// at most about 1032 times, LZW about 1400, PackBits and EXR's RLE and PIZ less; Huffman-
// coded JPEG spends at least a bit on each 8x8 block, under 1400 times even with 4x4 chroma
// subsampling), so a header asking for more describes data that is not in the file. Only
// arithmetic-coded JPEG of a nearly uniform image can beat the ratio: not a photograph.
constexpr size_t kMaxCompressionRatio = 4096;
constexpr size_t kMinDecodedBytes = size_t(64) << 20;
size_t maxDecodedBytes(const std::string& path);

// Throws Error naming path unless width x height x channels is a size a reader may allocate:
// at most kMaxImagePixels, and, at bytesPerSample as stored, no more than maxDecodedBytes.
// Called before allocating, so a 100-byte header cannot make the reader allocate gigabytes.
void checkImageSize(const std::string& path, size_t width, size_t height, size_t channels, size_t bytesPerSample);

}  // namespace glint::detail
