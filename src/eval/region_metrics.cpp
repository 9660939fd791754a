// Pixel masks from a world-space box and PSNR over them.
#include "eval/region_metrics.h"

#include <cmath>

#include "core/error.h"
#include "eval/image_metrics.h"

namespace glint {

std::vector<uint8_t> regionMask(const Camera& camera, const Image& truthDepth, const WorldBox& box) {
  if (truthDepth.channels != 1 || truthDepth.width != camera.width || truthDepth.height != camera.height)
    throw Error("region mask: the depth image does not match the camera's image size");
  std::vector<uint8_t> mask(size_t(camera.width) * size_t(camera.height), 0);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      float depth = truthDepth.at(x, y);
      if (!hasSurface(depth)) continue;
      Ray ray = camera.generateRay(x + 0.5, y + 0.5);
      if (box.contains(ray.origin + ray.direction * double(depth))) mask[size_t(y) * size_t(camera.width) + size_t(x)] = 1;
    }
  return mask;
}

double MaskedError::psnr() const {
  if (values == 0) return NAN;
  if (squaredError == 0) return INFINITY;
  return 10.0 * std::log10(values / squaredError);
}

MaskedError maskedError(const Image& a, const Image& b, const std::vector<uint8_t>& mask) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels ||
      mask.size() != size_t(a.width) * size_t(a.height))
    throw Error("masked PSNR: the images and the mask differ in size");
  MaskedError e;
  for (size_t p = 0; p < mask.size(); ++p) {
    if (!mask[p]) continue;
    for (int c = 0; c < a.channels; ++c) {
      double d = double(a.pixels[p * a.channels + c]) - double(b.pixels[p * b.channels + c]);
      e.squaredError += d * d;
    }
    e.values += a.channels;
  }
  return e;
}

RegionMetrics& RegionMetrics::operator+=(const RegionMetrics& o) {
  pixels += o.pixels;
  diffuse += o.diffuse;
  final += o.final;
  diffuseTonemapped += o.diffuseTonemapped;
  finalTonemapped += o.finalTonemapped;
  return *this;
}

RegionMetrics evaluateRegion(const ViewBuffers& rendered, const ViewBuffers& truth, const std::vector<uint8_t>& mask) {
  RegionMetrics m;
  for (uint8_t inside : mask) m.pixels += inside;
  m.diffuse = maskedError(rendered[Buffer::Diffuse], truth[Buffer::Diffuse], mask);
  m.final = maskedError(rendered[Buffer::Render], truth[Buffer::Render], mask);
  m.diffuseTonemapped = maskedError(tonemapTo8Bit(rendered[Buffer::Diffuse]), tonemapTo8Bit(truth[Buffer::Diffuse]), mask);
  m.finalTonemapped = maskedError(tonemapTo8Bit(rendered[Buffer::Render]), tonemapTo8Bit(truth[Buffer::Render]), mask);
  return m;
}

nlohmann::json toJson(const RegionMetrics& m) {
  auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  return {{"pixels", m.pixels},
          {"diffuse_psnr", number(m.diffuse.psnr())},
          {"diffuse_psnr_tonemapped", number(m.diffuseTonemapped.psnr())},
          {"final_psnr", number(m.final.psnr())},
          {"final_psnr_tonemapped", number(m.finalTonemapped.psnr())}};
}

}  // namespace glint
