// Sums of progressive samples and their display mapping.
#include "app/viewer/frame_accumulator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "io/tonemap.h"
#include "render/denoise.h"

namespace glint {

namespace {

void addInto(Image& sum, const Image& add) {
  GLINT_CHECK(add.width == sum.width && add.height == sum.height && add.channels == sum.channels,
              "accumulated sample differs in size");
  for (size_t i = 0; i < sum.pixels.size(); ++i) sum.pixels[i] += add.pixels[i];
}

// sum / samples; black with no samples.
Image meanOf(const Image& sum, int samples) {
  Image out = sum;
  float scale = samples > 0 ? 1.0f / float(samples) : 0.0f;
  for (float& v : out.pixels) v *= scale;
  return out;
}

}  // namespace

void FrameAccumulator::reset(int width, int height, int bounces) {
  sums_ = ViewBuffers::allocate(width, height);
  bounceSums_.assign(size_t(std::clamp(bounces, 0, kSeparateBounces)), Image(width, height, 3));
  samples_ = 0;
}

void FrameAccumulator::add(const ViewBuffers& sample, std::span<const Image> bounceLight) {
  GLINT_CHECK(bounceLight.size() == bounceSums_.size(), "accumulated sample has another bounce count");
  for (Buffer b : kAllBuffers) addInto(sums_[b], sample[b]);
  for (size_t k = 0; k < bounceSums_.size(); ++k) addInto(bounceSums_[k], bounceLight[k]);
  ++samples_;
}

Image FrameAccumulator::meanBounce(int bounce) const {
  if (bounce < 1 || size_t(bounce) > bounceSums_.size()) return Image(width(), height(), 3);
  return meanOf(bounceSums_[size_t(bounce - 1)], samples_);
}

Image FrameAccumulator::mean(Buffer buffer) const {
  Image out = meanOf(sums_[buffer], samples_);
  if (buffer == Buffer::Normal)  // a mean of unit normals is shorter than 1 at edges
    for (int y = 0; y < out.height; ++y)
      for (int x = 0; x < out.width; ++x) out.setRgb(x, y, normalize(out.rgb(x, y)));
  return out;
}

Image FrameAccumulator::display(const DisplaySettings& settings) const {
  Image m;
  if (settings.denoise && settings.mode == Buffer::Render && samples_ > 0) {
    // The a-trous filter of the final image, guided by the means of the other buffers.
    ViewBuffers means;
    for (Buffer b : kAllBuffers) means[b] = mean(b);
    m = denoiseView(means);
  } else if (settings.bounce > 0) {
    m = meanBounce(settings.bounce);
  } else {
    m = mean(settings.mode);
  }
  Image out(m.width, m.height, 3);
  if (isRadianceBuffer(settings.mode)) {  // bounce modes have mode Specular
    float gain = float(std::exp2(settings.exposure));
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x) out.setRgb(x, y, tonemapFilmic(m.rgb(x, y) * gain));
  } else if (settings.mode == Buffer::Normal) {
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x) {
        Rgb n = m.rgb(x, y);
        out.setRgb(x, y, dot(n, n) > 0 ? n * 0.5f + Rgb(0.5f) : Rgb(0.0f));
      }
  } else if (settings.mode == Buffer::Depth) {
    float nearest = std::numeric_limits<float>::max(), farthest = 0;
    for (float d : m.pixels)
      if (hasSurface(d)) nearest = std::min(nearest, d), farthest = std::max(farthest, d);
    float range = std::max(farthest - nearest, 1e-6f);
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x) {
        float d = m.at(x, y);
        out.setRgb(x, y, Rgb(hasSurface(d) ? 1.0f - 0.8f * (d - nearest) / range : 0.0f));
      }
  } else {  // roughness (grey) and F0
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x) out.setRgb(x, y, m.rgb(x, y));
  }
  return out;
}

}  // namespace glint
