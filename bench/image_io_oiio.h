// OpenImageIO's side of image_io_bench, kept in its own file so that the benchmark builds
// without OpenImageIO and only this file pays for its headers.
#pragma once

#include <filesystem>
#include <string>

#include "io/image.h"

namespace glint {

// "OpenImageIO 2.4.7" and the codec libraries it was built with, for the report.
std::string oiioDescription();

// Thread settings for everything below. One thread also keeps OpenEXR's decoding in the
// calling thread, as Glint's reader does (Glint never starts OpenEXR's thread pool).
void useOiioSingleThread();
// OpenImageIO's own defaults (as many threads as cores, for OIIO and for OpenEXR).
void useOiioDefaultThreads();

// The first `channels` channels of the file as interleaved float: the Image readImage
// returns. Alpha is kept as stored (straight): OpenImageIO would otherwise premultiply it
// into the colour on reading a PNG. Throws std::runtime_error with OpenImageIO's message.
Image readWithOiio(const std::filesystem::path& path, int channels);

// The image shrunk by n with a box filter one output pixel wide: each output pixel the
// mean of the n x n pixels it covers, as Glint's downscaleBuffer computes for radiance.
Image downscaleWithOiio(const Image& image, int n);

}  // namespace glint
