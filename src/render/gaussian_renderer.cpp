// Pixel loop of Gaussian rendering: rays per pixel, traced in parallel rows.
#include "render/gaussian_renderer.h"

#include <algorithm>
#include <array>

#include "core/parallel.h"
#include "math/owen_sobol.h"

namespace glint {

namespace {

// The sub-pixel positions of a pixel's samples: dimension 0 of its stratified stream (the
// path's segments use dimensions 1, 2, ...), so they cover the pixel evenly.
class PixelSamples {
 public:
  PixelSamples(const RenderSettings& settings, uint64_t viewKey, uint64_t pixel)
      : stream_(hashKeys({settings.seed, viewKey, pixel, 0})), index_(uint32_t(settings.firstSample)),
        jitter_(settings.jitter) {}
  Vec2f next() { return jitter_ ? stratifiedSample2(stream_, index_++) : Vec2f(0.5f, 0.5f); }

 private:
  uint64_t stream_;
  uint32_t index_;
  bool jitter_;
};

}  // namespace

std::vector<std::vector<PathSegment>> tracePixelPaths(const GaussianTracer& tracer, const Camera& camera,
                                                      const RenderSettings& settings, uint64_t viewKey, int x, int y) {
  uint64_t pixel = uint64_t(y) * uint64_t(camera.width) + uint64_t(x);
  PixelSamples samples(settings, viewKey, pixel);
  std::vector<std::vector<PathSegment>> paths(size_t(settings.spp));
  for (int s = 0; s < settings.spp; ++s) {
    Vec2f offset = samples.next();
    Ray ray = camera.generateRay(x + offset.x, y + offset.y);
    PathResult path = tracePath(tracer, {Vec3f(ray.origin), Vec3f(ray.direction), 0.0f}, settings.path,
                                settings.seed, viewKey, pixel, uint64_t(settings.firstSample + s), &paths[size_t(s)]);
    paths[size_t(s)].resize(size_t(path.segments));
  }
  return paths;
}

ViewBuffers renderGaussianView(const GaussianTracer& tracer, const Camera& camera, const RenderSettings& settings,
                               uint64_t viewKey, std::vector<Image>* bounceLight) {
  ViewBuffers out = ViewBuffers::allocate(camera.width, camera.height);
  const float invSpp = 1.0f / float(settings.spp);
  const int separate = bounceLight ? std::clamp(settings.path.bounces, 0, kSeparateBounces) : 0;
  if (bounceLight) bounceLight->assign(size_t(separate), Image(camera.width, camera.height, 3));
  parallelForChunks(camera.height, 1, [&](int64_t rowBegin, int64_t rowEnd) {
    for (int64_t y = rowBegin; y < rowEnd; ++y)
      for (int x = 0; x < camera.width; ++x) {
        uint64_t pixel = uint64_t(y) * uint64_t(camera.width) + uint64_t(x);
        PixelSamples samples(settings, viewKey, pixel);
        Rgb diffuse(0.0f), specular(0.0f), normal(0.0f), f0(0.0f);
        std::array<Rgb, kSeparateBounces> bounces{};
        float depth = 0, roughness = 0;
        for (int s = 0; s < settings.spp; ++s) {
          Vec2f offset = samples.next();
          Ray ray = camera.generateRay(x + offset.x, y + offset.y);
          PathResult path = tracePath(tracer, {Vec3f(ray.origin), Vec3f(ray.direction), 0.0f}, settings.path,
                                      settings.seed, viewKey, pixel, uint64_t(settings.firstSample + s));
          const RayResult& r = path.first;
          diffuse += r.diffuse;
          specular += path.specular;
          for (int k = 0; k < separate; ++k) bounces[size_t(k)] += path.bounceLight[size_t(k)];
          depth += r.depth;
          normal += r.normal;
          roughness += r.roughness;
          f0 += r.f0;
        }
        int yi = int(y);
        out[Buffer::Diffuse].setRgb(x, yi, diffuse * invSpp);
        out[Buffer::Specular].setRgb(x, yi, specular * invSpp);
        out[Buffer::Render].setRgb(x, yi, (diffuse + specular) * invSpp);
        out[Buffer::Depth].at(x, yi) = depth * invSpp;
        out[Buffer::Normal].setRgb(x, yi, settings.normalizeNormals ? normalize(normal) : normal * invSpp);
        out[Buffer::Roughness].at(x, yi) = roughness * invSpp;
        out[Buffer::F0].setRgb(x, yi, f0 * invSpp);
        for (int k = 0; k < separate; ++k) (*bounceLight)[size_t(k)].setRgb(x, yi, bounces[size_t(k)] * invSpp);
      }
  });
  return out;
}

}  // namespace glint
