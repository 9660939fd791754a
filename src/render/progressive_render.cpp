// Pass schedule and running means of progressive rendering.
#include "render/progressive_render.h"

#include <algorithm>

#include "core/error.h"

namespace glint {

ViewAccumulator::ViewAccumulator(int width, int height) : sums_(ViewBuffers::allocate(width, height)) {}

void ViewAccumulator::add(const ViewBuffers& render, int samples) {
  GLINT_CHECK(samples > 0, "a render adds at least one sample");
  const float weight = float(samples);
  for (Buffer b : kAllBuffers) {
    Image& sum = sums_[b];
    const Image& add = render[b];
    GLINT_CHECK(add.width == sum.width && add.height == sum.height && add.channels == sum.channels,
                "accumulated render differs in size");
    for (size_t i = 0; i < sum.pixels.size(); ++i) sum.pixels[i] += weight * add.pixels[i];
  }
  samples_ += samples;
}

ViewBuffers ViewAccumulator::mean() const {
  ViewBuffers out = sums_;
  const float scale = samples_ > 0 ? 1.0f / float(samples_) : 0.0f;
  for (Buffer b : kAllBuffers) {
    Image& image = out[b];
    if (b == Buffer::Normal) {
      for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) image.setRgb(x, y, normalize(image.rgb(x, y)));
    } else {
      for (float& v : image.pixels) v *= scale;
    }
  }
  return out;
}

std::vector<int> progressivePassSizes(int spp) {
  GLINT_CHECK(spp >= 1, "progressive rendering needs at least one sample");
  std::vector<int> sizes;
  int done = 0;
  while (done < spp) {
    int next = std::min(std::max(done, 1), spp - done);  // doubles the total, or ends at spp
    sizes.push_back(next);
    done += next;
  }
  return sizes;
}

ViewBuffers renderProgressively(const GaussianTracer& tracer, const Camera& camera, const RenderSettings& settings,
                                uint64_t viewKey, const ProgressivePassCallback& onPass) {
  const auto [rowBegin, rowEnd] = renderedRows(camera, settings);
  ViewAccumulator accumulator(camera.width, rowEnd - rowBegin);
  RenderSettings pass = settings;
  pass.normalizeNormals = false;  // summed as blended normals, normalised by mean()
  for (int size : progressivePassSizes(settings.spp)) {
    pass.firstSample = settings.firstSample + accumulator.samples();
    pass.spp = size;
    accumulator.add(renderGaussianView(tracer, camera, pass, viewKey), size);
    if (onPass) onPass(accumulator.mean(), accumulator.samples());
  }
  return accumulator.mean();
}

}  // namespace glint
