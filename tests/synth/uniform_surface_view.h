// A view of one flat, uniform surface for the degradation tests: blur changes nothing on
// it, so what differs between exact and degraded buffers is the stated noise and bias.
#pragma once

#include "scene/buffers.h"

namespace glint::test {

inline ViewBuffers uniformSurfaceView(int width, int height, const Vec3f& normal) {
  ViewBuffers v = ViewBuffers::allocate(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      v[Buffer::Render].setRgb(x, y, Rgb(0.5f, 0.4f, 0.3f));
      v[Buffer::Diffuse].setRgb(x, y, Rgb(0.4f, 0.3f, 0.2f));
      v[Buffer::Specular].setRgb(x, y, Rgb(0.1f));
      v[Buffer::Depth].at(x, y) = 3.0f;
      v[Buffer::Normal].setRgb(x, y, normal);
      v[Buffer::Roughness].at(x, y) = 0.5f;
      v[Buffer::F0].setRgb(x, y, Rgb(0.04f));
    }
  return v;
}

}  // namespace glint::test
