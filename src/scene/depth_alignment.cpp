// Least median of squares, then least squares on the inliers, for z = a d + b per view,
// with residuals measured in the prediction d.
#include "scene/depth_alignment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/error.h"
#include "math/rng.h"

namespace glint {

namespace {

// One (x, y) sample of the line fitted: x the z-depth or its inverse, y the prediction.
struct FitPoint {
  double x = 0, y = 0;
};

struct Line {
  double a = 0, b = 0;
  double operator()(double x) const { return a * x + b; }
};

// Sigma of a Gaussian from a median absolute value: 1 / Phi^-1(3/4).
constexpr double kMadToSigma = 1.4826;
// Inliers lie within this many robust sigmas (about 1.2% of Gaussian noise falls outside).
constexpr double kInlierSigmas = 2.5;

double medianInPlace(std::vector<double>& v) {
  size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  double upper = v[mid];
  if (v.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + mid));
}

double medianSquaredResidual(const std::vector<FitPoint>& points, const Line& line, std::vector<double>& scratch) {
  scratch.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    double r = points[i].y - line(points[i].x);
    scratch[i] = r * r;
  }
  return medianInPlace(scratch);
}

// Ordinary least squares on the points flagged in `use`; false when their x do not vary.
bool leastSquares(const std::vector<FitPoint>& points, const std::vector<char>& use, Line* line) {
  double n = 0, meanX = 0, meanY = 0;
  for (size_t i = 0; i < points.size(); ++i)
    if (use[i]) n += 1, meanX += points[i].x, meanY += points[i].y;
  if (n < 2) return false;
  meanX /= n, meanY /= n;
  double sxx = 0, sxy = 0;
  for (size_t i = 0; i < points.size(); ++i)
    if (use[i]) {
      double dx = points[i].x - meanX;
      sxx += dx * dx, sxy += dx * (points[i].y - meanY);
    }
  if (!(sxx > 0)) return false;
  line->a = sxy / sxx;
  line->b = meanY - line->a * meanX;
  return true;
}

// The line through two samples with the smallest median squared residual (Rousseeuw's least
// median of squares). Every pair is tried when there are few; otherwise seeded random ones.
std::pair<Line, double> leastMedianOfSquares(const std::vector<FitPoint>& points, const DepthFitOptions& options,
                                             double minDx) {
  std::vector<double> scratch;
  Line best;
  double bestMedian = std::numeric_limits<double>::infinity();
  auto tryPair = [&](size_t i, size_t j) {
    double dx = points[j].x - points[i].x;
    if (std::abs(dx) <= minDx) return;
    Line line;
    line.a = (points[j].y - points[i].y) / dx;
    line.b = points[i].y - line.a * points[i].x;
    double median = medianSquaredResidual(points, line, scratch);
    if (median < bestMedian) bestMedian = median, best = line;
  };
  size_t n = points.size();
  if (n * (n - 1) / 2 <= size_t(std::max(options.samplingRounds, 1))) {
    for (size_t i = 0; i < n; ++i)
      for (size_t j = i + 1; j < n; ++j) tryPair(i, j);
  } else {
    Rng rng = Rng::forKeys({options.seed});
    for (int round = 0; round < options.samplingRounds; ++round) {
      size_t i = rng.uniformInt(uint32_t(n));
      size_t j = rng.uniformInt(uint32_t(n - 1));
      tryPair(i, j >= i ? j + 1 : j);
    }
  }
  return {best, bestMedian};
}

// Flags the points within `threshold` of the line; returns how many.
int markInliers(const std::vector<FitPoint>& points, const Line& line, double threshold, std::vector<char>* inlier) {
  int count = 0;
  inlier->assign(points.size(), 0);
  for (size_t i = 0; i < points.size(); ++i)
    if (std::abs(points[i].y - line(points[i].x)) <= threshold) (*inlier)[i] = 1, ++count;
  return count;
}

// The value a fit-space y stands for as a z-depth.
double zFromFitSpace(double y, DepthFitSpace space) {
  if (space == DepthFitSpace::Depth) return y;
  return y > 0 ? 1.0 / y : 0.0;
}

double medianAbsZResidual(std::span<const DepthPair> used, auto zOf) {
  std::vector<double> r;
  r.reserve(used.size());
  for (const DepthPair& p : used) r.push_back(std::abs(zOf(p.predicted) - p.zDepth));
  return medianInPlace(r);
}

DepthFit refuse(DepthFit fit, std::string problem) {
  fit.ok = false;
  fit.problem = std::move(problem);
  return fit;
}

}  // namespace

double DepthFit::zDepth(double predicted) const {
  double z = zFromFitSpace(a * predicted + b, space);
  return std::isfinite(z) && z > 0 ? z : 0.0;
}

DepthFit fitDepthAffine(std::span<const DepthPair> pairs, const DepthFitOptions& options) {
  DepthFit fit;
  fit.space = options.space;
  fit.pairsGiven = int(pairs.size());

  // Usable pairs, and the same as fit points (x = z, or 1/z for disparity; y = d).
  std::vector<DepthPair> used;
  std::vector<FitPoint> points;
  for (const DepthPair& p : pairs) {
    bool finite = std::isfinite(p.predicted) && std::isfinite(p.zDepth) && p.zDepth > 0;
    if (!finite || (options.space == DepthFitSpace::Disparity && !(p.predicted > 0))) continue;
    used.push_back(p);
    points.push_back({options.space == DepthFitSpace::Depth ? p.zDepth : 1.0 / p.zDepth, p.predicted});
  }
  fit.pairsUsed = int(used.size());
  if (fit.pairsUsed < std::max(options.minPairs, 2))
    return refuse(fit, "only " + std::to_string(fit.pairsUsed) + " usable depth pairs (need " +
                           std::to_string(std::max(options.minPairs, 2)) + ")");
  fit.medianAbsResidualBefore = medianAbsZResidual(used, [&](double d) { return zFromFitSpace(d, options.space); });

  auto [minD, maxD] =
      std::minmax_element(points.begin(), points.end(), [](const FitPoint& p, const FitPoint& q) { return p.y < q.y; });
  double rangeD = maxD->y - minD->y;
  if (!(rangeD > 1e-12 * std::max(1.0, std::abs(maxD->y)))) return refuse(fit, "the predicted depths do not vary");

  // The line is fitted as d = c x + e, the prediction against the points' depth x (z or
  // 1/z), and turned into x = a d + b (a = 1 / c): the error is the prediction's (the sparse points' depths
  // are triangulated from many views), so residuals are measured in it. Measured in z they
  // let a wall the view mostly sees, a few percent deep, choose the slope: across it the
  // prediction's own error varies more than the true depth, a line nearly flat in z fits it
  // more tightly than the true one does, and least median of squares, which fits the
  // tightest half of the pairs, took it (a monocular capture had 5 of 120 views fitted with
  // a negative scale and 20 more with under half the true one; docs/captures.md). In d, the
  // wall's spread is the same for every line through it, and the rest of the view decides.
  auto [minX, maxX] =
      std::minmax_element(points.begin(), points.end(), [](const FitPoint& p, const FitPoint& q) { return p.x < q.x; });

  // Robust start and scale (Rousseeuw and Leroy 1987: the small-sample factor 1 + 5/(n - 2)).
  auto [line, medianSq] = leastMedianOfSquares(points, options, 1e-9 * (maxX->x - minX->x));
  if (!std::isfinite(medianSq)) return refuse(fit, "no two pairs with distinct sparse-point depths");
  double n = double(points.size());
  double sigma = kMadToSigma * (1.0 + 5.0 / std::max(n - 2.0, 1.0)) * std::sqrt(medianSq);
  // The bounds given in fit-space units (z or 1/z) become bounds in d through the slope.
  const double slope = std::abs(line.a);
  double threshold = options.inlierThreshold > 0 ? options.inlierThreshold * slope : kInlierSigmas * sigma;
  std::vector<double> absX;
  for (const FitPoint& p : points) absX.push_back(std::abs(p.x));
  double medianX = medianInPlace(absX);
  if (options.maxRelativeThreshold > 0) threshold = std::min(threshold, options.maxRelativeThreshold * medianX * slope);
  // Exact data has sigma 0: keep a bound at rounding level so that its pairs count as inliers.
  threshold = std::max(threshold, 1e-12 * std::max(rangeD, medianX * slope));

  // Least squares on the inliers, until the inlier set stops changing.
  std::vector<char> inlier, previous;
  int count = markInliers(points, line, threshold, &inlier);
  for (int iteration = 0; iteration < 20 && inlier != previous; ++iteration) {
    Line refit;
    if (!leastSquares(points, inlier, &refit)) break;
    line = refit;
    previous = inlier;
    count = markInliers(points, line, threshold, &inlier);
  }

  // d = c x + e  <=>  x = d / c - e / c.
  if (line.a != 0) fit.a = 1.0 / line.a, fit.b = -line.b / line.a;
  fit.inliers = count;
  fit.inlierThreshold = line.a != 0 ? threshold / std::abs(line.a) : 0.0;
  fit.medianAbsResidualAfter = medianAbsZResidual(used, [&](double d) { return fit.zDepth(d); });
  int minInliers = std::max(3, int(std::ceil(options.minInlierFraction * n)));
  if (count < minInliers)
    return refuse(fit, "only " + std::to_string(count) + " of " + std::to_string(fit.pairsUsed) +
                           " depth pairs agree with one affine map (need " + std::to_string(minInliers) + ")");
  if (!(fit.a > 0))
    return refuse(fit, "the fitted scale a = " + std::to_string(fit.a) +
                           " is not positive: depth would not grow with the prediction");
  fit.ok = true;
  return fit;
}

int occlusionRadius(size_t pixels, size_t pixelsWithPoints) {
  if (pixelsWithPoints == 0) return 0;
  const double spacing = std::sqrt(double(pixels) / double(pixelsWithPoints));
  return std::clamp(int(std::lround(spacing)), 1, kMaxOcclusionRadius);
}

std::vector<DepthPair> depthPairsFromPoints(const Image& predicted, std::span<const Vec3d> cameraPoints,
                                            const RayIntrinsics& k, HiddenPoints hiddenPoints) {
  GLINT_CHECK(predicted.channels == 1, "a predicted depth map has one channel");
  // (pixel index, z) of every point that lands in the image, nearest first within a pixel.
  std::vector<std::pair<size_t, double>> hits;
  for (const Vec3d& p : cameraPoints) {
    double z = -p.z;
    if (!(z > 0) || !isFinite(p)) continue;
    double px = k.cx + k.fx * p.x / z, py = k.cy - k.fy * p.y / z;
    if (!(px >= 0 && px < predicted.width && py >= 0 && py < predicted.height)) continue;
    size_t i = size_t(px), j = size_t(py);  // pixel i spans [i, i + 1)
    hits.push_back({j * size_t(predicted.width) + i, z});
  }
  std::sort(hits.begin(), hits.end());
  // The nearest point of each pixel: a sparse cloud's z-buffer.
  const int width = predicted.width, height = predicted.height;
  std::vector<double> nearest(size_t(width) * size_t(height), std::numeric_limits<double>::infinity());
  size_t pixelsWithPoints = 0;
  for (size_t h = 0; h < hits.size(); ++h)
    if (h == 0 || hits[h].first != hits[h - 1].first) nearest[hits[h].first] = hits[h].second, ++pixelsWithPoints;
  // A point seen through the gaps between nearer points is hidden behind the surface they
  // lie on: paired with the predicted depth of that surface it would be an outlier, and in
  // a small capture those can be the majority. So a point is dropped when a nearer one lies
  // within about the cloud's own spacing in the image.
  const int radius = occlusionRadius(size_t(width) * size_t(height), pixelsWithPoints);
  auto hiddenBehindNearer = [&](int i, int j, double z) {
    for (int y = std::max(0, j - radius); y <= std::min(height - 1, j + radius); ++y)
      for (int x = std::max(0, i - radius); x <= std::min(width - 1, i + radius); ++x)
        if (nearest[size_t(y) * size_t(width) + size_t(x)] < z * (1.0 - kOccluderGap)) return true;
    return false;
  };
  std::vector<DepthPair> pairs;
  for (size_t h = 0; h < hits.size(); ++h) {
    if (h > 0 && hits[h].first == hits[h - 1].first) continue;
    const double z = hits[h].second;
    const int i = int(hits[h].first % size_t(width)), j = int(hits[h].first / size_t(width));
    if (hiddenPoints == HiddenPoints::Drop && hiddenBehindNearer(i, j, z)) continue;
    float d = predicted.pixels[hits[h].first];
    if (std::isfinite(d)) pairs.push_back({d, z});
  }
  return pairs;
}

Image alignDepth(const Image& predicted, const DepthFit& fit) {
  GLINT_CHECK(predicted.channels == 1, "a predicted depth map has one channel");
  Image z = predicted;
  for (float& v : z.pixels) v = std::isfinite(v) ? float(fit.zDepth(v)) : 0.0f;
  return z;
}

}  // namespace glint
