// How each dataset buffer is stored in EXR, TIFF and 8-bit PNG files (the encodings table
// of docs/data-format.md), and the value checks every loaded buffer must pass.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "io/image.h"
#include "scene/buffers.h"

namespace glint {

// The format a buffer is written in when a dataset is written as `requested`: depth is
// always float, so PNG becomes EXR for depth.
ImageFormat bufferStorageFormat(Buffer buffer, ImageFormat requested);

// The file of a buffer given its path without extension (root / bufferFilePath(...)):
// tries .exr, then .tiff, then .png (docs/data-format.md). nullopt when none exists.
std::optional<std::filesystem::path> findBufferFileAt(const std::filesystem::path& base);
// "roughness buffer not found (tried .exr, .tiff and .png)", plus the names of files with
// that stem in formats the loader does not read (say a .bmp).
std::string missingBufferMessage(const std::filesystem::path& base, Buffer buffer);

// Linear values -> the values writeImage stores for that format: PNG radiance is filmic
// tonemapped and PNG normals become n/2 + 0.5; everything else is stored as it is.
// `format` must be bufferStorageFormat(buffer, format).
Image encodeBuffer(const Image& linear, Buffer buffer, ImageFormat format);

// Reads a buffer file (format from its extension) and decodes it to linear values: the
// inverse filmic tonemap for PNG radiance, n*2 - 1 for PNG normals; a depth of +inf
// (what a half-float EXR makes of a very large background depth) becomes 0, "no surface",
// so that loaded values are always finite. Throws Error naming the file for an unreadable
// file, a PNG depth or a channel count other than bufferChannels(buffer).
Image readBufferFile(const std::filesystem::path& path, Buffer buffer);

// The first value a loader must reject (NaN or infinite, negative depth, roughness or F0
// outside [0, 1]) as a message naming the pixel (x, y), the channel and how many values
// are bad; nullopt when none.
std::optional<std::string> findInvalidValue(const Image& image, Buffer buffer);

// Where depth records a surface, normals must be unit length (within 0.1): a message
// naming the first pixel that is not and how many are not; nullopt when all are.
std::optional<std::string> findNonUnitNormal(const Image& normal, const Image& depth);

}  // namespace glint
