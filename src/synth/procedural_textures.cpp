// The dead-leaves texture generator.
#include "synth/procedural_textures.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "math/rng.h"

namespace glint {

Texture makeDeadLeavesTexture(const std::string& name, int size, uint64_t seed, float darkest, float brightest,
                              float minRadius) {
  GLINT_CHECK(size > 0 && minRadius > 0 && brightest >= darkest, "valid dead-leaves parameters");
  Texture texture;
  texture.name = name;
  texture.image = Image(size, size, 3, 0.5f * (darkest + brightest));
  Rng rng = Rng::forKeys({seed, 0x1eaf});
  const float maxRadius = std::max(minRadius, size / 8.0f);
  // Inverse-CDF sampling of p(r) ~ 1/r^3 on [minRadius, maxRadius]: 1/r^2 is uniform
  // between 1/maxRadius^2 and 1/minRadius^2.
  const float invMin2 = 1.0f / (minRadius * minRadius), invMax2 = 1.0f / (maxRadius * maxRadius);
  // Enough discs that the expected painted area is about six times the image, so almost
  // no texel keeps the fill colour. With p(r) = c / r^3, c = 2 / (invMin2 - invMax2), the
  // mean disc area is pi c ln(maxRadius / minRadius).
  const double meanArea = 2.0 * 3.14159265358979 * std::log(maxRadius / minRadius) / (invMin2 - invMax2);
  const int64_t discs = int64_t(6.0 * double(size) * size / meanArea) + 1;
  for (int64_t k = 0; k < discs; ++k) {
    float u = rng.uniform();
    float r = 1.0f / std::sqrt(invMax2 + u * (invMin2 - invMax2));
    float cx = rng.uniform() * size, cy = rng.uniform() * size;
    // A random hue at moderate saturation: mix a random colour with its grey.
    Rgb colour(rng.uniform(), rng.uniform(), rng.uniform());
    float grey = (colour.x + colour.y + colour.z) / 3.0f;
    float saturation = 0.3f + 0.6f * rng.uniform();
    colour = Rgb(grey) + (colour - Rgb(grey)) * saturation;
    float level = darkest + (brightest - darkest) * rng.uniform();
    colour = colour * (level / std::max(1e-3f, grey));
    colour = min(max(colour, Rgb(darkest)), Rgb(brightest));
    // A linear shading gradient across the disc, up to +-25%, so each disc has an interior.
    float angle = 6.2831853f * rng.uniform(), strength = 0.25f * rng.uniform();
    float gx = std::cos(angle) * strength / r, gy = std::sin(angle) * strength / r;
    int x0 = int(std::floor(cx - r)), x1 = int(std::ceil(cx + r));
    int y0 = int(std::floor(cy - r)), y1 = int(std::ceil(cy + r));
    // Discs wrap around the borders, matching the texture's repeat addressing, so the
    // texture has no seam where uv wraps.
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        float dx = x + 0.5f - cx, dy = y + 0.5f - cy;
        if (dx * dx + dy * dy > r * r) continue;
        int wx = ((x % size) + size) % size, wy = ((y % size) + size) % size;
        texture.image.setRgb(wx, wy, colour * (1.0f + gx * dx + gy * dy));
      }
  }
  return texture;
}

}  // namespace glint
