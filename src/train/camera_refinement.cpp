// One round of camera pose refinement over the training views (train/camera_refinement.h).
#include "train/camera_refinement.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <vector>

#include "core/parallel.h"
#include "math/nearest_rotation.h"
#include "math/percentile.h"
#include "render/gaussian_renderer.h"
#include "train/training_eval.h"

namespace glint {

namespace {
constexpr int kAlignmentSpp = 4;
}  // namespace

ViewBuffers renderForAlignment(const GaussianTracer& tracer, const Camera& camera, const PathSettings& path,
                               bool finalColour, uint64_t viewKey) {
  PathSettings colourPath = path;
  if (!finalColour) colourPath.bounces = 0;  // the diffuse pass is the first segment's
  return renderScoredView(tracer, camera, scoringSettings(kAlignmentSpp, colourPath), viewKey);
}

std::pair<double, double> removeCommonMotion(const std::vector<Camera>& before, std::vector<Camera>* after) {
  const size_t n = before.size();
  if (n < 3) return {0.0, 1.0};  // a similarity needs three centres
  Mat3d sum;
  for (int i = 0; i < 3; ++i) sum.m[i] = Vec3d(0.0);
  Vec3d meanBefore(0.0), meanAfter(0.0);
  for (size_t v = 0; v < n; ++v) {
    const Mat3d change = (*after)[v].rotation() * before[v].rotation().transposed();
    for (int i = 0; i < 3; ++i) sum.m[i] += change.m[i];
    meanBefore += before[v].position() / double(n);
    meanAfter += (*after)[v].position() / double(n);
  }
  const Mat3d g = nearestRotation(sum);
  double numerator = 0, denominator = 0;
  for (size_t v = 0; v < n; ++v) {
    const Vec3d b = g * (before[v].position() - meanBefore), a = (*after)[v].position() - meanAfter;
    numerator += dot(a, b);
    denominator += dot(b, b);
  }
  const double scale = denominator > 0 && numerator > 0 ? numerator / denominator : 1.0;
  for (size_t v = 0; v < n; ++v) {
    Camera& c = (*after)[v];
    const Mat3d r = g.transposed() * c.rotation();
    const Vec3d centre = g.transposeTimes(c.position() - meanAfter) / scale + meanBefore;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) c.cameraToWorld.m[i][j] = r.m[i][j];
      c.cameraToWorld.m[i][3] = centre[i];
    }
  }
  return {rotationAngleDegrees(g), scale};
}

std::string CameraRefinementRound::summary() const {
  char line[400];
  std::snprintf(line, sizeof(line),
                "cameras refined: %d of %d views moved, median %.3f deg and %.4g (at most %.3f deg and %.4g), "
                "image cost %.3g -> %.3g, common motion taken out %.3f deg and scale %.4f%s",
                moved, views, medianDegrees, medianDistance, maxDegrees, maxDistance, costBefore, costAfter,
                commonDegrees, commonScale,
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
      rendered[v - first] = renderForAlignment(tracer, camera, path, finalColour, uint64_t(v));
      Image& target = targets[v - first];
      target = Image(camera.width, camera.height, 3);
      for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x)
          target.setRgb(x, y, views->target(v, size_t(y) * size_t(camera.width) + size_t(x)).diffuse);
    }
    parallelFor(int64_t(last - first), 1, [&](int64_t k) {
      const ViewBuffers& r = rendered[size_t(k)];
      aligned[first + size_t(k)] = alignCameraPose(views->camera(first + size_t(k)), alignmentColour(r, finalColour),
                                                   r[Buffer::Depth], targets[size_t(k)], options);
    });
  }

  CameraRefinementRound round;
  round.views = int(count);
  std::vector<size_t> moved;
  std::vector<Camera> before, after;
  for (size_t v = 0; v < count; ++v) {
    const PoseAlignment& a = aligned[v];
    if (a.beyondBounds) ++round.refusedBeyondBounds;
    if (!a.accepted) continue;
    moved.push_back(v);
    before.push_back(views->camera(v));
    after.push_back(a.camera);
    round.costBefore += a.costBefore;
    round.costAfter += a.costAfter;
  }
  std::tie(round.commonDegrees, round.commonScale) = removeCommonMotion(before, &after);
  round.moved = int(moved.size());
  std::vector<float> degrees, distances;
  for (size_t k = 0; k < moved.size(); ++k) {
    degrees.push_back(float(rotationAngleDegrees(after[k].rotation() * before[k].rotation().transposed())));
    distances.push_back(float(length(after[k].position() - before[k].position())));
    round.maxDegrees = std::max(round.maxDegrees, double(degrees.back()));
    round.maxDistance = std::max(round.maxDistance, double(distances.back()));
    views->setCamera(moved[k], after[k], normalsFromCamera);
  }
  if (round.moved > 0) {
    round.costBefore /= round.moved;
    round.costAfter /= round.moved;  // of the alignments, before the common motion was taken out
  }
  round.medianDegrees = percentileOf(degrees, 0.5);
  round.medianDistance = percentileOf(distances, 0.5);
  return round;
}

}  // namespace glint
