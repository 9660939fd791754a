// The random "room of Gaussians" of issue 3's prototype, shared by the tracer and render
// benchmarks so that their figures are of the same scene.
#pragma once

#include <cmath>
#include <cstdint>

#include "math/rng.h"
#include "scene/gaussians.h"

namespace glint {

// The room: a 10 x 3 x 8 m box filled uniformly with Gaussians whose size and opacity give,
// seen from the centre, about 36 hits per ray at 100k Gaussians and 180 at 500k, of
// which about 90 are composited before the ray terminates (the prototype's 36 and 185/88).
inline constexpr float kRoomHalf[3] = {5.0f, 1.5f, 4.0f};

inline GaussianScene makeRoom(size_t n, uint64_t seed) {
  Rng rng(seed);
  auto uniform = [&](float a, float b) { return a + (b - a) * rng.uniform(); };
  GaussianScene scene;
  scene.resize(n);
  for (size_t i = 0; i < n; ++i) {
    scene.position[i] = {uniform(-kRoomHalf[0], kRoomHalf[0]), uniform(-kRoomHalf[1], kRoomHalf[1]),
                         uniform(-kRoomHalf[2], kRoomHalf[2])};
    Quatf q;
    do q = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
    while (q.norm() > 1.0f || q.norm() < 1e-2f);
    scene.rotation[i] = q;
    float base = std::log(0.048f);
    scene.logScale[i] = {base + uniform(-0.7f, 0.7f), base + uniform(-0.7f, 0.7f), base + uniform(-0.7f, 0.7f)};
    scene.opacityLogit[i] = logit(uniform(0.02f, 0.13f));
    scene.diffuse[i] = {rng.uniform(), rng.uniform(), rng.uniform()};
    scene.normal[i] = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
    scene.roughness[i] = rng.uniform();
    scene.f0[i] = {rng.uniform(), rng.uniform(), rng.uniform()};
  }
  return scene;
}

}  // namespace glint
