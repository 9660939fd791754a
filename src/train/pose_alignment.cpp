// Direct image alignment of a view's camera to the model's render (train/pose_alignment.h).
#include "train/pose_alignment.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "math/cholesky.h"
#include "math/nearest_rotation.h"
#include "math/percentile.h"
#include "scene/buffers.h"

namespace glint {

namespace {

// Residuals are compared in c / (1 + c): bounded, so a bright highlight does not outweigh the
// texture the alignment needs, and close to linear in the dark.
float displayValue(float c) { return std::max(c, 0.0f) / (1.0f + std::max(c, 0.0f)); }

// One level of the pyramid: the target in display values with its per-channel derivatives
// along x and y, and the render's surface pixels as camera-space points with their colours.
struct Level {
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  Image target, gradientX, gradientY;  // 3 channels each
  std::vector<Vec3d> points;           // camera coordinates under the given camera
  std::vector<Vec3f> colours;          // display values
};

Image toDisplay(const Image& linear) {
  Image d(linear.width, linear.height, 3);
  for (int y = 0; y < linear.height; ++y)
    for (int x = 0; x < linear.width; ++x) {
      const Rgb c = linear.rgb(x, y);
      d.setRgb(x, y, Rgb(displayValue(c.x), displayValue(c.y), displayValue(c.z)));
    }
  return d;
}

// The box filter of each 2x2 block (the odd last row or column dropped).
Image halve(const Image& image) {
  Image h(image.width / 2, image.height / 2, image.channels);
  for (int y = 0; y < h.height; ++y)
    for (int x = 0; x < h.width; ++x)
      for (int c = 0; c < image.channels; ++c)
        h.at(x, y, c) = 0.25f * (image.at(2 * x, 2 * y, c) + image.at(2 * x + 1, 2 * y, c) +
                                 image.at(2 * x, 2 * y + 1, c) + image.at(2 * x + 1, 2 * y + 1, c));
  return h;
}

// Depth halved where all four pixels see one surface (within 5% of each other); elsewhere no
// surface, so that no coarse point floats between a foreground and a background.
Image halveDepth(const Image& depth) {
  Image h(depth.width / 2, depth.height / 2, 1);
  for (int y = 0; y < h.height; ++y)
    for (int x = 0; x < h.width; ++x) {
      const float d[4] = {depth.at(2 * x, 2 * y), depth.at(2 * x + 1, 2 * y), depth.at(2 * x, 2 * y + 1),
                          depth.at(2 * x + 1, 2 * y + 1)};
      if (!std::all_of(d, d + 4, hasSurface)) continue;
      const auto [lo, hi] = std::minmax_element(d, d + 4);
      if (*hi > 1.05f * *lo) continue;
      h.at(x, y) = 0.25f * (d[0] + d[1] + d[2] + d[3]);
    }
  return h;
}

// Central differences (one-sided at the border), per channel.
void imageGradients(const Image& image, Image* gx, Image* gy) {
  *gx = Image(image.width, image.height, image.channels);
  *gy = Image(image.width, image.height, image.channels);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const int x0 = std::max(x - 1, 0), x1 = std::min(x + 1, image.width - 1);
      const int y0 = std::max(y - 1, 0), y1 = std::min(y + 1, image.height - 1);
      for (int c = 0; c < image.channels; ++c) {
        gx->at(x, y, c) = (image.at(x1, y, c) - image.at(x0, y, c)) / float(std::max(x1 - x0, 1));
        gy->at(x, y, c) = (image.at(x, y1, c) - image.at(x, y0, c)) / float(std::max(y1 - y0, 1));
      }
    }
}

// The bilinear interpolation of the three channels of `image` at a continuous pixel position
// (pixel centres at i + 0.5), inside [0.5, size - 0.5] in both axes.
Vec3d sampleBilinear(const Image& image, double u, double v) {
  const double x = u - 0.5, y = v - 0.5;
  const int x0 = std::clamp(int(std::floor(x)), 0, image.width - 2);
  const int y0 = std::clamp(int(std::floor(y)), 0, image.height - 2);
  const double fx = x - x0, fy = y - y0;
  Vec3d s(0.0);
  for (int c = 0; c < 3; ++c)
    s[c] = (1 - fy) * ((1 - fx) * image.at(x0, y0, c) + fx * image.at(x0 + 1, y0, c)) +
           fy * ((1 - fx) * image.at(x0, y0 + 1, c) + fx * image.at(x0 + 1, y0 + 1, c));
  return s;
}

double huberCost(double r, double delta) {
  const double a = std::abs(r);
  return a <= delta ? 0.5 * r * r : delta * (a - 0.5 * delta);
}

double huberWeight(double r, double delta) {
  const double a = std::abs(r);
  return a <= delta ? 1.0 : delta / a;
}

// A point that leaves the image costs as a residual of twice the Huber threshold in every
// channel: moving points out of view is no way to lower the cost.
double outsideCost(double delta) { return 3.0 * huberCost(2.0 * delta, delta); }

struct Pose {
  Mat3d r;  // identity
  Vec3d t{0.0, 0.0, 0.0};
};

bool insideImage(const Level& level, const Vec2d& p) {
  return p.x >= 0.5 && p.x <= level.width - 0.5 && p.y >= 0.5 && p.y <= level.height - 0.5;
}

// Mean robust cost per residual of `pose` at `level`.
double levelCost(const Level& level, const Pose& pose, double delta) {
  double cost = 0;
  double unused[2][6];
  for (size_t i = 0; i < level.points.size(); ++i) {
    const Vec3d q = pose.r * level.points[i] + pose.t;
    Vec2d p;
    if (!projectWithPoseJacobian(q, level.fx, level.fy, level.cx, level.cy, &p, unused) || !insideImage(level, p)) {
      cost += outsideCost(delta);
      continue;
    }
    const Vec3d t = sampleBilinear(level.target, p.x, p.y);
    for (int c = 0; c < 3; ++c) cost += huberCost(t[c] - double(level.colours[i][c]), delta);
  }
  return cost / double(std::max<size_t>(1, 3 * level.points.size()));
}

// The damped Gauss-Newton step (H + lambda diag(H)) x = -g at `pose`; false when singular.
bool poseStep(const Level& level, const Pose& pose, double delta, double lambda, std::array<double, 6>* step) {
  double h[6][6] = {}, g[6] = {};
  for (size_t i = 0; i < level.points.size(); ++i) {
    const Vec3d q = pose.r * level.points[i] + pose.t;
    Vec2d p;
    double j[2][6];
    if (!projectWithPoseJacobian(q, level.fx, level.fy, level.cx, level.cy, &p, j) || !insideImage(level, p)) continue;
    const Vec3d t = sampleBilinear(level.target, p.x, p.y);
    const Vec3d tx = sampleBilinear(level.gradientX, p.x, p.y), ty = sampleBilinear(level.gradientY, p.x, p.y);
    for (int c = 0; c < 3; ++c) {
      const double r = t[c] - double(level.colours[i][c]);
      const double w = huberWeight(r, delta);
      double row[6];
      for (int k = 0; k < 6; ++k) row[k] = tx[c] * j[0][k] + ty[c] * j[1][k];
      for (int a = 0; a < 6; ++a) {
        g[a] += w * row[a] * r;
        for (int b = 0; b <= a; ++b) h[a][b] += w * row[a] * row[b];
      }
    }
  }
  double x[6];
  for (int a = 0; a < 6; ++a) {
    h[a][a] *= 1.0 + lambda;
    h[a][a] += 1e-12;
    x[a] = -g[a];
  }
  if (!choleskyFactor(&h[0][0], 6, 6)) return false;
  choleskySolve(&h[0][0], 6, 6, x);
  for (int a = 0; a < 6; ++a) (*step)[a] = x[a];
  return true;
}

// Levenberg-Marquardt at one level from `pose`.
Pose alignLevel(const Level& level, Pose pose, const PoseAlignmentOptions& options) {
  if (level.points.empty()) return pose;
  double cost = levelCost(level, pose, options.huberDelta);
  double lambda = 1e-3;
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    std::array<double, 6> x;
    if (!poseStep(level, pose, options.huberDelta, lambda, &x)) break;
    const Mat3d dr = rotationFromVector(Vec3d(x[0], x[1], x[2]));
    Pose trial{dr * pose.r, dr * pose.t + Vec3d(x[3], x[4], x[5])};
    const double trialCost = levelCost(level, trial, options.huberDelta);
    if (trialCost < cost) {
      pose = trial, cost = trialCost;
      lambda = std::max(lambda * 0.25, 1e-7);
      if (std::abs(x[0]) + std::abs(x[1]) + std::abs(x[2]) < 1e-9) break;
    } else {
      lambda *= 4.0;
      if (lambda > 1e6) break;
    }
  }
  return pose;
}

Level makeLevel(const Camera& camera, int level, const Image& target, const Image& colour, const Image& depth) {
  Level l;
  const double scale = std::ldexp(1.0, -level);
  l.width = target.width, l.height = target.height;
  l.fx = camera.fx * scale, l.fy = camera.fy * scale, l.cx = camera.cx * scale, l.cy = camera.cy * scale;
  // The level's camera at the origin: its rays' directions are camera coordinates.
  Camera local = camera;
  local.cameraToWorld = Mat4::identity();
  local.width = l.width, local.height = l.height;
  local.fx = l.fx, local.fy = l.fy, local.cx = l.cx, local.cy = l.cy;
  l.target = target;
  imageGradients(target, &l.gradientX, &l.gradientY);
  for (int y = 0; y < depth.height; ++y)
    for (int x = 0; x < depth.width; ++x) {
      const float d = depth.at(x, y);
      if (!hasSurface(d)) continue;
      l.points.push_back(local.generateRay(x + 0.5, y + 0.5).direction * double(d));
      const Rgb c = colour.rgb(x, y);
      l.colours.push_back(Vec3f(c.x, c.y, c.z));
    }
  return l;
}

}  // namespace

Mat3d rotationFromVector(const Vec3d& w) {
  const double angle = length(w);
  Mat3d k;  // [w]x / angle (every row set below)
  Mat3d r;  // identity
  if (angle < 1e-12) {  // first order: I + [w]x
    k.m[0] = {0.0, -w.z, w.y}, k.m[1] = {w.z, 0.0, -w.x}, k.m[2] = {-w.y, w.x, 0.0};
    for (int i = 0; i < 3; ++i) r.m[i] += k.m[i];
    return r;
  }
  const Vec3d a = w / angle;
  k.m[0] = {0.0, -a.z, a.y}, k.m[1] = {a.z, 0.0, -a.x}, k.m[2] = {-a.y, a.x, 0.0};
  const Mat3d k2 = k * k;
  const double s = std::sin(angle), c = 1.0 - std::cos(angle);
  for (int i = 0; i < 3; ++i) r.m[i] += k.m[i] * s + k2.m[i] * c;
  return r;
}

bool projectWithPoseJacobian(const Vec3d& q, double fx, double fy, double cx, double cy, Vec2d* pixel,
                             double jacobian[2][6]) {
  const double z = -q.z;  // distance in front of the camera
  if (!(z > 1e-9)) return false;
  const double iz = 1.0 / z;
  *pixel = Vec2d(cx + fx * q.x * iz, cy - fy * q.y * iz);
  // d(u, v)/dq: u = cx + fx x / z, v = cy - fy y / z with z = -q.z.
  const double du[3] = {fx * iz, 0.0, fx * q.x * iz * iz};
  const double dv[3] = {0.0, -fy * iz, -fy * q.y * iz * iz};
  // dq/dw = -[q]x, dq/dv = I.
  const double dqdw[3][3] = {{0.0, q.z, -q.y}, {-q.z, 0.0, q.x}, {q.y, -q.x, 0.0}};
  for (int k = 0; k < 3; ++k) {
    jacobian[0][k] = du[0] * dqdw[0][k] + du[1] * dqdw[1][k] + du[2] * dqdw[2][k];
    jacobian[1][k] = dv[0] * dqdw[0][k] + dv[1] * dqdw[1][k] + dv[2] * dqdw[2][k];
    jacobian[0][3 + k] = du[k];
    jacobian[1][3 + k] = dv[k];
  }
  return true;
}

Camera movedCamera(const Camera& camera, const Mat3d& r, const Vec3d& t) {
  // cameraToWorld after = cameraToWorld before * (R, t)^-1, with (R, t)^-1 = (R^T, -R^T t).
  Mat4 inverse = Mat4::identity();
  const Vec3d back = r.transposeTimes(t);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) inverse.m[i][j] = r.m[j][i];
    inverse.m[i][3] = -back[i];
  }
  Camera moved = camera;
  moved.cameraToWorld = camera.cameraToWorld * inverse;
  return moved;
}

PoseAlignment alignCameraPose(const Camera& camera, const Image& renderColour, const Image& renderDepth,
                              const Image& target, const PoseAlignmentOptions& options) {
  PoseAlignment result;
  result.camera = camera;
  const int w = camera.width, h = camera.height;
  if (renderColour.width != w || renderColour.height != h || renderDepth.width != w || renderDepth.height != h ||
      target.width != w || target.height != h) {
    result.refusal = "the render and the target are not the camera's size";
    return result;
  }
  std::vector<float> depths;
  for (float d : renderDepth.pixels)
    if (hasSurface(d)) depths.push_back(d);
  result.pixels = int(depths.size());
  if (result.pixels < options.minPixels) {
    result.refusal = "too few pixels with a surface (" + std::to_string(result.pixels) + ")";
    return result;
  }

  // The pyramid, finest first; a level stops halving below 16 pixels on a side.
  std::vector<Image> targets{toDisplay(target)}, colours{toDisplay(renderColour)}, depthImages{renderDepth};
  while (int(targets.size()) < options.levels && targets.back().width >= 32 && targets.back().height >= 32) {
    targets.push_back(halve(targets.back()));
    colours.push_back(halve(colours.back()));
    depthImages.push_back(halveDepth(depthImages.back()));
  }
  const Level finest = makeLevel(camera, 0, targets[0], colours[0], depthImages[0]);
  Pose pose;
  for (int l = int(targets.size()) - 1; l >= 0; --l)
    pose = alignLevel(l == 0 ? finest : makeLevel(camera, l, targets[size_t(l)], colours[size_t(l)], depthImages[size_t(l)]),
                      pose, options);

  result.costBefore = levelCost(finest, Pose{}, options.huberDelta);
  result.costAfter = levelCost(finest, pose, options.huberDelta);
  result.rotationDegrees = rotationAngleDegrees(pose.r);
  result.translation = length(pose.t);
  const double medianDepth = percentileOf(depths, 0.5);
  if (!(result.costAfter < result.costBefore * (1.0 - options.minImprovement)))
    result.refusal = "the cost did not fall";
  else if (result.rotationDegrees > options.maxRotationDegrees)
    result.refusal = "a turn beyond the bound", result.beyondBounds = true;
  else if (result.translation > options.maxTranslation * medianDepth)
    result.refusal = "a move beyond the bound", result.beyondBounds = true;
  if (!result.refusal.empty()) return result;
  result.accepted = true;
  result.camera = movedCamera(camera, pose.r, pose.t);
  return result;
}

}  // namespace glint
