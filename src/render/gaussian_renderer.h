// Renders views of a Gaussian scene through a GaussianTracer: pixel sampling, averaging
// of the per-ray outputs, and the buffers of a view.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_path.h"
#include "scene/buffers.h"
#include "scene/camera.h"

namespace glint {

struct RenderSettings {
  int spp = 1;
  // Jittered sub-pixel positions (uniform in the pixel, one stream per pixel); without
  // jitter every sample goes through the pixel centre.
  bool jitter = true;
  uint64_t seed = 0;
  // Index of the first sample: samples firstSample .. firstSample + spp - 1 are traced, with
  // the random numbers they have in a render of firstSample + spp samples. So renders of
  // one sample each with firstSample 0, 1, ..., N-1 average to exactly the render of N
  // samples (the viewer accumulates that way).
  int firstSample = 0;
  PathSettings path;  // bounces 0: first segment only (specular stays zero)
  // Normal buffer: the normalised mean of the blended normals (a direction per pixel), or,
  // when false, their plain mean, so renders of a few samples each can be summed into the
  // normal of one render of all their samples (progressive rendering).
  bool normalizeNormals = true;
  // The rows traced, [rowBegin, rowEnd) of the image (rowEnd -1: through the last row); the
  // buffers hold only these rows. A rank of an MPI job renders its band of a view this way
  // (scene/view_sharing.h); a pixel's samples are the same in any band, since their keys
  // number the pixels of the whole image.
  int rowBegin = 0;
  int rowEnd = -1;
};

// Renders the buffers of one view: diffuse and the G-buffers from each path's first segment,
// specular from its later segments (settings.path), render = diffuse + specular. Each
// buffer averages the spp samples;
// the normal buffer is the average of the blended normals, normalised where non-zero
// (unless settings.normalizeNormals is false). With `bounceLight`, it also receives
// min(bounces, kSeparateBounces) RGB images, image k - 1 averaging the light of reflected
// segment k (PathResult::bounceLight): the terms of the specular buffer.
ViewBuffers renderGaussianView(const GaussianTracer& tracer, const Camera& camera, const RenderSettings& settings,
                               uint64_t viewKey, std::vector<Image>* bounceLight = nullptr);

// The rows [first, second) of camera's image that settings trace (RenderSettings::rowBegin).
std::pair<int, int> renderedRows(const Camera& camera, const RenderSettings& settings);

// Camera rays traced per wavefront (a tile of whole rows), and the bytes a tile's arrays
// take with that many rays (paths, keys, pixel sums and the wavefront's own), for
// benchmarks.
size_t renderTileRays();
size_t renderTileBytes(int bounces);

// Re-runs the paths of one pixel exactly as renderGaussianView traces them (same sample
// positions and random numbers) and returns every segment with its hits, per sample.
std::vector<std::vector<PathSegment>> tracePixelPaths(const GaussianTracer& tracer, const Camera& camera,
                                                      const RenderSettings& settings, uint64_t viewKey, int x, int y);

}  // namespace glint
