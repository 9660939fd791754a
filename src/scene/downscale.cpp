// Box-filtered downscaling of dataset views: cameras, radiance and the G-buffers.
#include "scene/downscale.h"

#include <cmath>

#include "core/error.h"

namespace glint {

Camera downscaleCamera(const Camera& camera, int n) {
  GLINT_CHECK(n >= 1 && n <= camera.width && n <= camera.height, "downscaleCamera: n out of range");
  Camera small = camera;
  small.width = camera.width / n;
  small.height = camera.height / n;
  small.fx = camera.fx / n, small.fy = camera.fy / n;
  small.cx = camera.cx / n, small.cy = camera.cy / n;
  return small;
}

namespace {

// Does pixel (x, y) of `image` describe a surface (for depth and normals), or count at all?
bool counts(const Image& image, Buffer buffer, int x, int y) {
  if (buffer == Buffer::Depth) return hasSurface(image.at(x, y));
  if (buffer == Buffer::Normal)
    return image.at(x, y, 0) != 0.0f || image.at(x, y, 1) != 0.0f || image.at(x, y, 2) != 0.0f;
  return true;
}

}  // namespace

Image downscaleBuffer(const Image& image, Buffer buffer, int n) {
  GLINT_CHECK(n >= 1 && n <= image.width && n <= image.height, "downscaleBuffer: n out of range");
  GLINT_CHECK(image.channels <= 4, "downscaleBuffer: at most 4 channels");
  if (n == 1) return image;
  const bool surfaceOnly = buffer == Buffer::Depth || buffer == Buffer::Normal;
  Image small(image.width / n, image.height / n, image.channels);
  for (int y = 0; y < small.height; ++y)
    for (int x = 0; x < small.width; ++x) {
      double sum[4] = {0, 0, 0, 0};
      int used = 0;
      for (int dy = 0; dy < n; ++dy)
        for (int dx = 0; dx < n; ++dx) {
          const int sx = x * n + dx, sy = y * n + dy;
          if (!counts(image, buffer, sx, sy)) continue;
          ++used;
          for (int c = 0; c < image.channels && c < 4; ++c) sum[c] += image.at(sx, sy, c);
        }
      // A surface pixel needs at least half its block on a surface; otherwise it keeps the
      // zeros of "no surface".
      if (used == 0 || (surfaceOnly && 2 * used < n * n)) continue;
      for (int c = 0; c < image.channels; ++c) small.at(x, y, c) = float(sum[c] / used);
      if (buffer == Buffer::Normal) {
        const double length = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
        if (length < 1e-6 * used) {
          // Opposite normals cancelled (a thin sheet seen edge-on): keep the block's first one.
          for (int dy = 0, found = 0; dy < n && !found; ++dy)
            for (int dx = 0; dx < n && !found; ++dx)
              if ((found = counts(image, buffer, x * n + dx, y * n + dy)))
                for (int c = 0; c < 3; ++c) small.at(x, y, c) = image.at(x * n + dx, y * n + dy, c);
        } else {
          for (int c = 0; c < 3; ++c) small.at(x, y, c) = float(sum[c] / length);
        }
      }
    }
  return small;
}

}  // namespace glint
