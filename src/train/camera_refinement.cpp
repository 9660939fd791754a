// One round of camera pose refinement over the training views (train/camera_refinement.h).
#include "train/camera_refinement.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "core/parallel.h"
#include "math/percentile.h"
#include "render/gaussian_renderer.h"
#include "train/training_eval.h"

namespace glint {

namespace {
constexpr int kAlignmentSpp = 4;
}  // namespace

std::string CameraRefinementRound::summary() const {
  char line[400];
  std::snprintf(line, sizeof(line),
                "cameras refined: %d of %d views moved, median %.3f deg and %.4g (at most %.3f deg and %.4g), "
                "image cost %.3g -> %.3g%s",
                moved, views, medianDegrees, medianDistance, maxDegrees, maxDistance, costBefore, costAfter,
                refusedBeyondBounds > 0
                    ? (", " + std::to_string(refusedBeyondBounds) + " refused beyond the bounds").c_str()
                    : "");
  return line;
}

CameraRefinementRound refineTrainingCameras(const GaussianTracer& tracer, const PathSettings& path,
                                            TrainingViews* views, bool normalsFromCamera,
                                            const PoseAlignmentOptions& options) {
  const size_t count = views->viewCount();
  const bool finalColour = views->supervised().finalColour;
  std::vector<PoseAlignment> aligned(count);
  // The renders one view at a time (each in parallel over its pixels), then the alignments of
  // a chunk of views in parallel (each serial, so its result does not depend on scheduling):
  // a chunk's images, not every view's, are held at once.
  const size_t chunk = size_t(std::max(1, maxThreads()));
  for (size_t first = 0; first < count; first += chunk) {
    const size_t last = std::min(count, first + chunk);
    std::vector<ViewBuffers> rendered(last - first);
    std::vector<Image> targets(last - first);
    for (size_t v = first; v < last; ++v) {
      const Camera& camera = views->camera(v);
      // The targets average their pixels (radiance buffers cover the whole pixel), so the
      // colour is rendered so too, from kAlignmentSpp jittered samples; the depth that carries
      // the pixels into the target comes from the pixel centre (renderScoredView). Centre
      // samples alone alias the model's pixel-sized Gaussians into a biased alignment.
      PathSettings colourPath = path;
      if (!finalColour) colourPath.bounces = 0;  // the diffuse pass is the first segment's
      rendered[v - first] = renderScoredView(tracer, camera, scoringSettings(kAlignmentSpp, colourPath), uint64_t(v));
      Image& target = targets[v - first];
      target = Image(camera.width, camera.height, 3);
      for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x)
          target.setRgb(x, y, views->target(v, size_t(y) * size_t(camera.width) + size_t(x)).diffuse);
    }
    parallelFor(int64_t(last - first), 1, [&](int64_t k) {
      const ViewBuffers& r = rendered[size_t(k)];
      aligned[first + size_t(k)] = alignCameraPose(views->camera(first + size_t(k)),
                                                   r[finalColour ? Buffer::Render : Buffer::Diffuse],
                                                   r[Buffer::Depth], targets[size_t(k)], options);
    });
  }

  CameraRefinementRound round;
  round.views = int(count);
  std::vector<float> degrees, distances;
  for (size_t v = 0; v < count; ++v) {
    const PoseAlignment& a = aligned[v];
    if (a.refusal == "a turn beyond the bound" || a.refusal == "a move beyond the bound") ++round.refusedBeyondBounds;
    if (!a.accepted) continue;
    views->setCamera(v, a.camera, normalsFromCamera);
    ++round.moved;
    degrees.push_back(float(a.rotationDegrees));
    distances.push_back(float(a.translation));
    round.maxDegrees = std::max(round.maxDegrees, a.rotationDegrees);
    round.maxDistance = std::max(round.maxDistance, a.translation);
    round.costBefore += a.costBefore / double(count);
    round.costAfter += a.costAfter / double(count);
  }
  if (round.moved > 0) {
    round.costBefore *= double(count) / round.moved;
    round.costAfter *= double(count) / round.moved;
  }
  round.medianDegrees = percentileOf(degrees, 0.5);
  round.medianDistance = percentileOf(distances, 0.5);
  return round;
}

}  // namespace glint
