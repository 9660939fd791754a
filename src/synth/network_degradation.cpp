// The network-like degradation's parameters, and its application to one view.
#include "synth/network_degradation.h"

#include <numbers>

#include "math/rng.h"

namespace glint {

BufferDegradation networkLikeDegradation(int width, uint64_t seed, uint64_t view) {
  const double pixelScale = width / 320.0;
  BufferDegradation g;
  g.blurSigma = 1.0 * pixelScale;
  Rng rng = Rng::forKeys({seed, view, 0xdeb7});
  g.depthScale = 0.95 + 0.1 * rng.uniformDouble();
  g.depthOffset = -0.1 + 0.2 * rng.uniformDouble();
  g.depthNoise = 0.01;
  g.normalMeanAngle = 4.0 * std::numbers::pi / 180.0;
  g.normalCorrelation = 3.0 * pixelScale;
  g.roughnessScale = 0.8;
  g.roughnessOffset = 0.1;
  g.roughnessNoise = 0.03;
  g.seed = seed;
  return g;
}

ViewBuffers networkLikePriors(const ViewBuffers& exact, uint64_t seed, uint64_t view) {
  const BufferDegradation g = networkLikeDegradation(exact[Buffer::Render].width, seed, view);
  ViewBuffers out = degradeBuffers(exact, g, view);
  // degradeBuffers keeps the radiance buffers; a predictor's diffuse/specular split is as
  // smooth as its G-buffers, while the photograph itself is what the camera saw.
  out[Buffer::Diffuse] = gaussianBlur(exact[Buffer::Diffuse], g.blurSigma);
  out[Buffer::Specular] = gaussianBlur(exact[Buffer::Specular], g.blurSigma);
  out[Buffer::Render] = exact[Buffer::Render];
  return out;
}

}  // namespace glint
