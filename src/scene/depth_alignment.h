// Robust per-view affine alignment of a predicted depth map to the z-depths of sparse
// (COLMAP) points, depth_metric ~ a d_pred + b, or the same in disparity for predictors of
// inverse depth.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "io/image.h"
#include "math/vec.h"
#include "scene/predicted_buffers.h"

namespace glint {

// One correspondence: the predicted value at the pixel a sparse point projects to, and
// that point's true z-depth (distance along the camera axis, > 0).
struct DepthPair {
  double predicted = 0;
  double zDepth = 0;
};

// What the predictor's values are an affine function of.
enum class DepthFitSpace {
  Depth,      // z ~ a d + b: relative depth (the paper's loaders assume this)
  Disparity,  // 1/z ~ a d + b: relative inverse depth (MiDaS/DPT-style predictors); then
              // z = 1 / (a d + b), and pixels with a d + b <= 0 have no depth
};

struct DepthFitOptions {
  DepthFitSpace space = DepthFitSpace::Depth;
  int minPairs = 20;               // fewer usable pairs: the fit is refused
  double minInlierFraction = 0.5;  // least median of squares breaks down beyond 50% outliers
  int samplingRounds = 256;        // two-pair samples tried by the least-median-of-squares search
  double inlierThreshold = 0;      // residual bound for inliers in fit-space units (z or 1/z); 0 = 2.5 robust sigmas
  // The bound never exceeds this fraction of the median |z| (or |1/z|): when outliers are
  // the majority the robust sigma grows with them, and this keeps them from all becoming
  // inliers, so such data is refused instead of fitted.
  double maxRelativeThreshold = 0.2;
  uint64_t seed = 0;  // the fit is a pure function of (pairs, options)
};

// The fit and how good it is, for the loader to report.
struct DepthFit {
  bool ok = false;
  std::string problem;  // why the fit was refused (empty when ok)
  DepthFitSpace space = DepthFitSpace::Depth;
  double a = 0, b = 0;         // in `space`: z = a d + b, or 1/z = a d + b
  int pairsGiven = 0;          // pairs passed in
  int pairsUsed = 0;           // finite pairs with z > 0 (and d > 0 in disparity space)
  int inliers = 0;             // pairs within the inlier threshold of the final fit
  double inlierThreshold = 0;  // fit-space units
  // Median |z' - z| over the used pairs, in z-depth units: before alignment (the raw
  // prediction read as z, or as 1/z in disparity space) and after.
  double medianAbsResidualBefore = 0;
  double medianAbsResidualAfter = 0;

  // Aligned z-depth of a predicted value; 0 ("no surface") where it is not positive.
  double zDepth(double predicted) const;
};

// Least median of squares over seeded two-pair samples gives a starting line and a robust
// scale; least squares is then refitted on the inliers until the inlier set settles. Both
// measure residuals in the prediction d (the line is fitted as d against z, or 1/z, and
// inverted): the error is the predictor's, and residuals in z let a view that mostly sees
// one wall fit the wall's noise instead of the view (see the .cpp).
// Refused (ok = false, `problem` says why) with fewer than minPairs usable pairs,
// predicted values that do not vary, too few inliers, or a <= 0 (depth must grow with
// the prediction in both spaces).
DepthFit fitDepthAffine(std::span<const DepthPair> pairs, const DepthFitOptions& options = {});

// Pairs from camera-space points (OpenGL camera axes, the camera looks down -z): each point
// in front of the camera is projected with k to the pixel containing it, and paired with
// the predicted value there. Where several points land in one pixel the nearest is kept,
// and, with HiddenPoints::Drop, a point is dropped as hidden when a point nearer by more
// than kOccluderGap of its depth lands within occlusionRadius pixels (the points hold every
// view's surfaces, not only this one's). HiddenPoints::Keep is for points the view is known
// to have observed (a COLMAP track): a surface without points of its own (a mirror, a
// textureless sphere) hides the points behind it from that guess, not from a track. Pixels
// with a non-finite prediction are skipped (0 is kept: relative depth maps use it).
constexpr double kOccluderGap = 0.25;
constexpr int kMaxOcclusionRadius = 8;
// The neighbourhood, in pixels, searched for a nearer point: the mean spacing of the points
// in the image (sqrt of pixels per pixel that holds a point), in [1, kMaxOcclusionRadius].
int occlusionRadius(size_t pixels, size_t pixelsWithPoints);

enum class HiddenPoints { Drop, Keep };
std::vector<DepthPair> depthPairsFromPoints(const Image& predicted, std::span<const Vec3d> cameraPoints,
                                            const RayIntrinsics& k, HiddenPoints hidden = HiddenPoints::Drop);

// The aligned z-depth image of a one-channel prediction (0 where there is no depth).
Image alignDepth(const Image& predicted, const DepthFit& fit);

}  // namespace glint
