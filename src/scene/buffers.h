// The seven per-view buffers of a dataset (docs/data-format.md) and their properties.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "io/image.h"

namespace glint {

enum class Buffer { Render, Diffuse, Specular, Depth, Normal, Roughness, F0 };
constexpr int kBufferCount = 7;
constexpr std::array<Buffer, kBufferCount> kAllBuffers = {Buffer::Render, Buffer::Diffuse,   Buffer::Specular,
                                                          Buffer::Depth,  Buffer::Normal,    Buffer::Roughness,
                                                          Buffer::F0};

// Folder and file-name stem: "render", "diffuse", "specular", "depth", "normal", "roughness", "f0".
const char* bufferName(Buffer buffer);
std::optional<Buffer> bufferFromName(const std::string& name);
// 3 for render, diffuse, specular, normal, f0; 1 for depth and roughness.
int bufferChannels(Buffer buffer);
// True for render, diffuse and specular: linear radiance, tonemapped in 8-bit files.
bool isRadianceBuffer(Buffer buffer);

// All buffers of one view, decoded to linear values (see docs/data-format.md).
struct ViewBuffers {
  std::array<Image, kBufferCount> images;

  Image& operator[](Buffer b) { return images[static_cast<int>(b)]; }
  const Image& operator[](Buffer b) const { return images[static_cast<int>(b)]; }
  // Allocates every buffer at the given size with its channel count, filled with zeros.
  static ViewBuffers allocate(int width, int height);
};

// Depth values at or above this are "no surface" (as is 0), per docs/data-format.md.
constexpr float kNoSurfaceDepth = 1.0e9f;
inline bool hasSurface(float depth) { return depth > 0.0f && depth < kNoSurfaceDepth; }

}  // namespace glint
