// Metrics restricted to the pixels that see a world-space box: how well one object is
// reconstructed (issue 5: the object seen only in the mirror, scored in test views that
// see it directly).
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/image.h"
#include "math/vec.h"
#include "scene/buffers.h"
#include "scene/camera.h"

namespace glint {

struct WorldBox {
  Vec3d lo, hi;
  bool contains(const Vec3d& p) const {
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
  }
};

// 1 where the ground-truth surface point of the pixel-centre ray (origin + depth x
// direction; docs/data-format.md's depth is the distance along the ray) lies inside the box.
std::vector<uint8_t> regionMask(const Camera& camera, const Image& truthDepth, const WorldBox& box);

// Squared error summed over the masked pixels and channels, and their number of values:
// the parts of a PSNR that can be pooled over views.
struct MaskedError {
  double squaredError = 0;
  double values = 0;
  MaskedError& operator+=(const MaskedError& o) {
    squaredError += o.squaredError;
    values += o.values;
    return *this;
  }
  // 10 log10(1 / MSE) with data range 1 as psnr(); NaN without pixels.
  double psnr() const;
};
MaskedError maskedError(const Image& a, const Image& b, const std::vector<uint8_t>& mask);

struct RegionMetrics {
  size_t pixels = 0;
  MaskedError diffuse, final;                     // linear
  MaskedError diffuseTonemapped, finalTonemapped;  // on the tonemapped 8-bit images
  RegionMetrics& operator+=(const RegionMetrics& o);
};
RegionMetrics evaluateRegion(const ViewBuffers& rendered, const ViewBuffers& truth, const std::vector<uint8_t>& mask);

// {"pixels", "diffuse_psnr", "diffuse_psnr_tonemapped", "final_psnr", "final_psnr_tonemapped"}
// (null for NaN).
nlohmann::json toJson(const RegionMetrics& metrics);

}  // namespace glint
