// JPEG encoding through stb_image_write (Debian's libstb-dev); its functions are compiled
// static here so they cannot clash with another copy linked elsewhere.
#include "app/viewer/frame_encoding.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/error.h"

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb_image_write.h>
#pragma GCC diagnostic pop

namespace glint {

std::string encodeJpeg(const Image& image, int quality) {
  GLINT_CHECK(!image.empty() && image.channels == 3, "JPEG frames are RGB");
  std::vector<uint8_t> bytes(image.pixels.size());
  for (size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = uint8_t(std::lround(std::clamp(image.pixels[i], 0.0f, 1.0f) * 255.0f));
  std::string out;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
  };
  if (!stbi_write_jpg_to_func(append, &out, image.width, image.height, 3, bytes.data(), quality))
    throw Error("JPEG encoder", "failed to encode a frame");
  return out;
}

}  // namespace glint
