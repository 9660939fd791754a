// Exemplar continuation of a surface's texture into a hole: the one in-plane offset at which
// the texture seen around the hole repeats elsewhere on the surface (a checker's period, a
// tiled floor's), found by normalised cross-correlation on a raster of the plane.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "math/vec.h"
#include "scene/gaussians.h"

namespace glint {

// Normals at least this close (cosine) face the same way: one surface for the texture.
inline constexpr float kSameSurfaceCosine = 0.9f;

struct TextureOffsetSettings {
  // The band around the hole whose texture is matched, in raster cells (one cell = spacing).
  int bandCells = 12;
  // Offsets are searched up to this many hole widths away (and at most maxSearchCells).
  float searchWidths = 2.0f;
  int maxSearchCells = 96;
  // Offsets shorter than this many hole widths are not searched (a copy from just beside
  // the hole continues no period).
  float minOffsetWidths = 1.0f;
  // An offset is used only where its correlation with the band reaches this: a uniform
  // surface (noise alone) or a texture that does not repeat keeps the mean continuation.
  float minCorrelation = 0.4f;
  // Fractions of the shifted hole and band that must land on seen surface.
  float minSeenHole = 0.95f;
  float minSeenBand = 0.9f;
  // The search visits (hole + band cells) x offsets cells, which grows as the fourth power of
  // the hole's width; past this many it is not made and the hole keeps the mean continuation
  // (the viewer heals on every edit). builtin:spheres' hole, about 24 cells wide, costs some
  // 3e7, and its whole healing takes 0.06 s on 2 cores.
  double maxWork = 5e8;
};

struct TextureOffset {
  Vec3f offset;              // world-space, in the plane
  float correlation = 0;     // of the band with its shifted copies (the lesser), in [-1, 1]
};

// `hole`: points of the plane to fill (their normals all close to `normal`); `seen`: Gaussians
// of the surface that training views saw (only those within `slab` of the plane through the
// hole's centroid and facing along `normal` are used). Rasterises the plane at `spacing`
// and returns the offset at which the shifted band, and the band shifted by its opposite, best
// correlate (log luminance, the lesser of the two) with the band; nothing when none reaches
// minCorrelation. Deterministic.
std::optional<TextureOffset> findTextureOffset(const GaussianScene& scene, std::span<const uint32_t> seen,
                                               std::span<const Vec3f> hole, const Vec3f& normal, float spacing,
                                               float slab, const TextureOffsetSettings& settings = {});

}  // namespace glint
