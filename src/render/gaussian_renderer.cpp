// Gaussian rendering: the camera rays of a tile of rows, one sample of every pixel at a
// time, traced as a wavefront of paths (PathBatch), and their per-pixel means.
#include "render/gaussian_renderer.h"

#include <algorithm>
#include <array>

#include "core/parallel.h"
#include "render/device_view_renderer.h"
#include "render/pixel_sample.h"

namespace glint {


std::vector<std::vector<PathSegment>> tracePixelPaths(const GaussianTracer& tracer, const Camera& camera,
                                                      const RenderSettings& settings, uint64_t viewKey, int x, int y) {
  uint64_t pixel = uint64_t(y) * uint64_t(camera.width) + uint64_t(x);
  std::vector<std::vector<PathSegment>> paths(size_t(settings.spp));
  for (int s = 0; s < settings.spp; ++s) {
    Vec2f offset = pixelSampleOffset(settings.jitter, settings.seed, viewKey, pixel, uint32_t(settings.firstSample + s));
    Ray ray = camera.generateRay(x + offset.x, y + offset.y);
    PathResult path = tracePath(tracer, {Vec3f(ray.origin), Vec3f(ray.direction), 0.0f}, settings.path,
                                settings.seed, viewKey, pixel, uint64_t(settings.firstSample + s), &paths[size_t(s)]);
    paths[size_t(s)].resize(size_t(path.segments));
  }
  return paths;
}

namespace {

// Camera rays per wavefront: a tile of whole rows this large keeps a tile's records and
// accumulators in a few megabytes at any image size, and still gives every thread
// hundreds of bundles.
constexpr size_t kRaysPerTile = size_t(1) << 16;

}  // namespace

std::pair<int, int> renderedRows(const Camera& camera, const RenderSettings& settings) {
  const int first = std::clamp(settings.rowBegin, 0, camera.height);
  return {first, settings.rowEnd < 0 ? camera.height : std::clamp(settings.rowEnd, first, camera.height)};
}

size_t renderTileRays() { return kRaysPerTile; }

size_t renderTileBytes(int bounces) {
  const size_t perRay = sizeof(TraceRay) + sizeof(PathKey) + sizeof(PathResult) +  // inputs and outputs
                        4 * sizeof(Rgb) + 2 * sizeof(float) + size_t(std::clamp(bounces, 0, kSeparateBounces)) * sizeof(Rgb) +
                        PathBatch::bytesPerPath(/*record=*/false);
  return kRaysPerTile * perRay;
}

ViewBuffers renderGaussianView(const GaussianTracer& tracer, const Camera& camera, const RenderSettings& settings,
                               uint64_t viewKey, std::vector<Image>* bounceLight) {
  const auto [rowBegin, rowEnd] = renderedRows(camera, settings);
  ViewBuffers out = ViewBuffers::allocate(camera.width, rowEnd - rowBegin);
  const float invSpp = 1.0f / float(settings.spp);
  const int separate = bounceLight ? std::clamp(settings.path.bounces, 0, kSeparateBounces) : 0;
  if (bounceLight) bounceLight->assign(size_t(separate), Image(camera.width, rowEnd - rowBegin, 3));
  const size_t width = size_t(camera.width);
  PixelSums sums;
  // The averages of rows [y0, y1), whose sums `sums` holds.
  auto writeRows = [&](int y0, int y1) {
    const size_t pixels = size_t(y1 - y0) * width;
    parallelForChunks(int64_t(pixels), 1024, [&](int64_t begin, int64_t end) {
      for (int64_t j = begin; j < end; ++j) {
        const int x = int(size_t(j) % width), y = y0 - rowBegin + int(size_t(j) / width);  // row in the band
        const Rgb diffuse = sums.diffuse[size_t(j)], specular = sums.specular[size_t(j)];
        out[Buffer::Diffuse].setRgb(x, y, diffuse * invSpp);
        out[Buffer::Specular].setRgb(x, y, specular * invSpp);
        out[Buffer::Render].setRgb(x, y, (diffuse + specular) * invSpp);
        out[Buffer::Depth].at(x, y) = sums.depth[size_t(j)] * invSpp;
        const Rgb normal = sums.normal[size_t(j)];
        out[Buffer::Normal].setRgb(x, y, settings.normalizeNormals ? normalize(normal) : normal * invSpp);
        out[Buffer::Roughness].at(x, y) = sums.roughness[size_t(j)] * invSpp;
        out[Buffer::F0].setRgb(x, y, sums.f0[size_t(j)] * invSpp);
        for (int k = 0; k < separate; ++k)
          (*bounceLight)[size_t(k)].setRgb(x, y, sums.bounces[size_t(k)][size_t(j)] * invSpp);
      }
    });
  };
  // A tracer with its own device (the GPU) sums the whole band there, in one piece.
  if (const auto* device = dynamic_cast<const DeviceViewRenderer*>(&tracer)) {
    if (rowEnd > rowBegin) {
      device->sumView(camera, settings, viewKey, rowBegin, rowEnd, separate, &sums);
      writeRows(rowBegin, rowEnd);
    }
    return out;
  }
  const int rowsPerTile = int(std::max<size_t>(1, kRaysPerTile / std::max<size_t>(width, 1)));
  PathBatch batch;
  std::vector<TraceRay> rays;
  std::vector<PathKey> keys;
  std::vector<PathResult> paths;
  // Tile by tile, sample by sample: each pass traces one sample of every pixel of the tile
  // as one wavefront, and the pixel sums add the samples in order (as a per-pixel loop would).
  for (int y0 = rowBegin; y0 < rowEnd; y0 += rowsPerTile) {
    const int y1 = std::min(rowEnd, y0 + rowsPerTile);
    const size_t pixels = size_t(y1 - y0) * width;
    sums.reset(pixels, separate);
    rays.resize(pixels);
    keys.resize(pixels);
    paths.resize(pixels);
    for (int s = 0; s < settings.spp; ++s) {
      const uint32_t sample = uint32_t(settings.firstSample + s);
      parallelForChunks(int64_t(pixels), 1024, [&](int64_t begin, int64_t end) {
        for (int64_t j = begin; j < end; ++j) {
          const int x = int(size_t(j) % width), y = y0 + int(size_t(j) / width);
          const uint64_t pixel = uint64_t(y) * uint64_t(width) + uint64_t(x);
          Vec2f offset = pixelSampleOffset(settings.jitter, settings.seed, viewKey, pixel, sample);
          Ray ray = camera.generateRay(x + offset.x, y + offset.y);
          rays[size_t(j)] = {Vec3f(ray.origin), Vec3f(ray.direction), 0.0f};
          keys[size_t(j)] = {viewKey, pixel, sample};
        }
      });
      batch.trace(tracer, rays, keys, settings.seed, settings.path, paths, /*record=*/false);
      parallelForChunks(int64_t(pixels), 1024, [&](int64_t begin, int64_t end) {
        for (int64_t j = begin; j < end; ++j) {
          const PathResult& path = paths[size_t(j)];
          const RayResult& r = path.first;
          sums.diffuse[size_t(j)] += r.diffuse;
          sums.specular[size_t(j)] += path.specular;
          for (int k = 0; k < separate; ++k) sums.bounces[size_t(k)][size_t(j)] += path.bounceLight[size_t(k)];
          sums.depth[size_t(j)] += r.depth;
          sums.normal[size_t(j)] += r.normal;
          sums.roughness[size_t(j)] += r.roughness;
          sums.f0[size_t(j)] += r.f0;
        }
      });
    }
    writeRows(y0, y1);
  }
  return out;
}

}  // namespace glint
