// The image files image_io_bench reads: one of each kind Glint loads, generated from a seed
// so that every run times the same bytes.
#pragma once

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "io/image.h"
#include "io/tonemap.h"
#include "math/rng.h"

namespace glint {

// The buffers of a synthetic view: a floor, a sky and a few shaded spheres, with per-pixel
// noise like a path tracer's. The content matters because every codec here compresses:
// pure noise would not compress at all and a flat image would compress to nothing, and
// neither is what a dataset holds.
struct SampleView {
  Image radiance;  // RGB, linear, highlights above 1
  Image depth;     // 1 channel, distance; 0 where the sky is ("no surface")
  Image normal;    // RGB, n / 2 + 0.5 as a PNG stores it
  Image coverage;  // 1 channel, 1 on the spheres with soft edges, 0 elsewhere
};

inline SampleView makeSampleView(int size, uint64_t seed) {
  SampleView v{Image(size, size, 3), Image(size, size, 1), Image(size, size, 3), Image(size, size, 1)};
  struct Sphere {
    float cx, cy, r;  // in units of the image width
    Rgb albedo;
  };
  Rng layout(seed);
  std::vector<Sphere> spheres;
  for (int i = 0; i < 5; ++i) {
    spheres.push_back({0.15f + 0.7f * layout.uniform(), 0.35f + 0.45f * layout.uniform(), 0.06f + 0.1f * layout.uniform(),
                       Rgb(0.2f + 0.7f * layout.uniform(), 0.2f + 0.7f * layout.uniform(), 0.2f + 0.7f * layout.uniform())});
  }
  const Vec3f light = normalize(Vec3f(-0.4f, 0.7f, 0.6f));
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      // One stream per pixel, so a pixel's noise does not depend on the image size's loop order.
      Rng noise = Rng::forKeys({seed, uint64_t(x), uint64_t(y)});
      const float u = (float(x) + 0.5f) / float(size), w = (float(y) + 0.5f) / float(size);
      const bool floor = w > 0.4f;
      Rgb colour = floor ? Rgb(0.45f, 0.4f, 0.35f) * (0.6f + 0.8f * (w - 0.4f)) : Rgb(0.5f, 0.7f, 1.1f) * (1.2f - w);
      Vec3f n = floor ? Vec3f(0, 1, 0) : Vec3f(0, 0, 0);
      float depth = floor ? 1.5f / (w - 0.38f) : 0.0f;
      float cover = 0.0f;
      for (const Sphere& s : spheres) {
        const float dx = (u - s.cx) / s.r, dy = (w - s.cy) / s.r, d2 = dx * dx + dy * dy;
        if (d2 >= 1.0f) continue;
        n = Vec3f(dx, -dy, std::sqrt(1.0f - d2));
        const float lambert = std::max(0.0f, dot(n, light));
        const float highlight = 4.0f * std::pow(std::max(0.0f, n.z * 0.9f + dot(n, light) * 0.1f), 60.0f);
        colour = s.albedo * (0.1f + lambert) + Rgb(highlight);
        depth = 3.0f - 2.0f * s.r * n.z;
        cover = std::min(1.0f, (1.0f - std::sqrt(d2)) * s.r * float(size) / 1.5f);  // about 1.5 pixels of edge
      }
      colour = colour * (0.9f + 0.2f * noise.uniform());
      v.radiance.setRgb(x, y, colour);
      v.depth.at(x, y) = depth;
      v.normal.setRgb(x, y, n == Vec3f(0, 0, 0) ? Rgb(0.0f) : n * 0.5f + Vec3f(0.5f));
      v.coverage.at(x, y) = cover;
    }
  return v;
}

// The tonemapped radiance an 8-bit file holds, with alpha appended when coverage is given.
inline Image displayImage(const SampleView& v, bool withAlpha) {
  Image out(v.radiance.width, v.radiance.height, withAlpha ? 4 : 3);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const Rgb c = tonemapFilmic(v.radiance.rgb(x, y));
      out.at(x, y, 0) = c.x, out.at(x, y, 1) = c.y, out.at(x, y, 2) = c.z;
      if (withAlpha) out.at(x, y, 3) = v.coverage.at(x, y);
    }
  return out;
}

// A one-channel half-float EXR (ZIP, as writeImage compresses), the layout depth maps from
// other tools come in. writeImage writes float32 only, so OpenEXR is called directly.
inline void writeHalfExr(const std::filesystem::path& path, const Image& image) {
  std::vector<Imath::half> halves(image.pixels.begin(), image.pixels.end());
  Imf::Header header(image.width, image.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  header.channels().insert("Y", Imf::Channel(Imf::HALF));
  Imf::FrameBuffer frame;
  frame.insert("Y", Imf::Slice(Imf::HALF, reinterpret_cast<char*>(halves.data()), sizeof(Imath::half),
                               sizeof(Imath::half) * size_t(image.width)));
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(frame);
  file.writePixels(image.height);
}

// One file of the benchmark and how Glint reads it.
struct SampleFile {
  std::string kind;  // e.g. "PNG 8-bit RGBA"
  std::filesystem::path path;
  bool keepAlpha;  // read with readImageWithAlpha (4 channels) rather than readImage
  int channels;    // what Glint returns for it, and so what the other reader must return
};

// Writes one file of each kind into folder, with Glint's own writer wherever it can make
// that kind.
inline std::vector<SampleFile> writeSampleFiles(const std::filesystem::path& folder, int size, uint64_t seed) {
  const SampleView v = makeSampleView(size, seed);
  const Image display = displayImage(v, false), displayWithAlpha = displayImage(v, true);
  auto at = [&](const char* name) { return folder / name; };
  writeImage(at("render.exr"), v.radiance);
  writeHalfExr(at("depth_half.exr"), v.depth);
  writeImage(at("render.tiff"), v.radiance);
  writeImage(at("render.png"), display);
  writeImage(at("normal16.png"), v.normal, ImageWriteOptions{.pngBitDepth = 16});
  writeImage(at("render_alpha.png"), displayWithAlpha);
  writeImage(at("photo.jpg"), display);
  return {
      {"EXR float32 RGB (render)", at("render.exr"), false, 3},
      {"EXR half Y (depth)", at("depth_half.exr"), false, 1},
      {"TIFF half RGB", at("render.tiff"), false, 3},
      {"PNG 8-bit RGB", at("render.png"), false, 3},
      {"PNG 16-bit RGB (normals)", at("normal16.png"), false, 3},
      {"PNG 8-bit RGBA, alpha kept", at("render_alpha.png"), true, 4},
      {"PNG 8-bit RGBA, alpha dropped", at("render_alpha.png"), false, 3},
      {"JPEG q95 RGB (photo)", at("photo.jpg"), false, 3},
  };
}

}  // namespace glint
