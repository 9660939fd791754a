// Orbit, spiral and dataset camera paths.
#include "render/camera_path.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.h"

namespace glint {

namespace {

// Solves A x = b for a 3x3 matrix given by its columns (Cramer's rule); false when A is
// too close to singular relative to its size.
bool solve3(const Vec3d columns[3], const Vec3d& b, Vec3d* x) {
  double det = dot(columns[0], cross(columns[1], columns[2]));
  double scale = length(columns[0]) * length(columns[1]) * length(columns[2]);
  if (!(std::abs(det) > 1e-6 * scale)) return false;
  *x = Vec3d(dot(b, cross(columns[1], columns[2])), dot(columns[0], cross(b, columns[2])),
             dot(columns[0], cross(columns[1], b))) /
       det;
  return true;
}

// A unit vector perpendicular to the unit vector n.
Vec3d anyPerpendicular(const Vec3d& n) {
  Vec3d a = std::abs(n.x) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
  return normalize(cross(n, a));
}

// Uniform Catmull-Rom interpolation between p1 and p2 (t in [0, 1]).
Vec3d catmullRom(const Vec3d& p0, const Vec3d& p1, const Vec3d& p2, const Vec3d& p3, double t) {
  double t2 = t * t, t3 = t2 * t;
  return 0.5 * ((2.0 * p1) + (p2 - p0) * t + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2 +
                (3.0 * p1 - p0 - 3.0 * p2 + p3) * t3);
}

// A camera at eye looking at target, with `up` as the ring's up (lookAt handles the rare
// case of looking straight along it).
Mat4 lookingAt(const Vec3d& eye, const CameraRing& ring) { return Mat4::lookAt(eye, ring.target, ring.up); }

Vec3d ringPoint(const CameraRing& ring, double angle, double radius, double height) {
  Vec3d u = ring.startDirection, v = cross(ring.up, u);
  return ring.target + (u * std::cos(angle) + v * std::sin(angle)) * radius + ring.up * height;
}

}  // namespace

const char* cameraPathName(CameraPathKind kind) {
  switch (kind) {
    case CameraPathKind::Orbit: return "orbit";
    case CameraPathKind::Spiral: return "spiral";
    case CameraPathKind::DatasetTest: return "dataset-test";
  }
  return "?";
}

std::optional<CameraPathKind> cameraPathFromName(const std::string& name) {
  for (CameraPathKind k : {CameraPathKind::Orbit, CameraPathKind::Spiral, CameraPathKind::DatasetTest})
    if (name == cameraPathName(k)) return k;
  return std::nullopt;
}

CameraRing cameraRing(const std::vector<Mat4>& cameras) {
  GLINT_CHECK(!cameras.empty(), "a camera ring needs cameras");
  // Least-squares point nearest to every optical axis: sum_i (I - d_i d_i^T)(x - o_i) = 0.
  Vec3d columns[3] = {Vec3d(0.0), Vec3d(0.0), Vec3d(0.0)};
  Vec3d rhs(0.0), centroid(0.0), meanForward(0.0), meanUp(0.0);
  for (const Mat4& c : cameras) {
    Vec3d o = c.column(3), d = normalize(-c.column(2));
    for (int j = 0; j < 3; ++j) {
      Vec3d e(0.0);
      e[j] = 1.0;
      columns[j] += e - d * d[j];  // column j of I - d d^T
    }
    rhs += o - d * dot(d, o);
    centroid += o;
    meanForward += d;
    meanUp += normalize(c.column(1));
  }
  double n = double(cameras.size());
  centroid /= n;
  CameraRing ring;
  ring.up = length(meanUp) > 1e-9 ? normalize(meanUp) : Vec3d(0, 1, 0);
  if (!solve3(columns, rhs, &ring.target)) {
    // Parallel axes (one camera, or a translated rig): look one rig size ahead.
    double spread = 0;
    for (const Mat4& c : cameras) spread += length(c.column(3) - centroid) / n;
    double meanDistance = std::max(spread, 1.0);
    ring.target = centroid + normalize(meanForward) * meanDistance;
  }
  // Heights along up and distances from the up axis through the target.
  double radiusSum = 0, heightSum = 0;
  ring.lowest = 1e300, ring.highest = -1e300;
  for (const Mat4& c : cameras) {
    Vec3d offset = c.column(3) - ring.target;
    double h = dot(offset, ring.up);
    radiusSum += length(offset - ring.up * h);
    heightSum += h;
    ring.lowest = std::min(ring.lowest, h), ring.highest = std::max(ring.highest, h);
  }
  ring.radius = std::max(radiusSum / n, 1e-6);
  ring.height = heightSum / n;
  Vec3d first = cameras[0].column(3) - ring.target;
  Vec3d flat = first - ring.up * dot(first, ring.up);
  ring.startDirection = length(flat) > 1e-9 * ring.radius ? normalize(flat) : anyPerpendicular(ring.up);
  return ring;
}

std::vector<Mat4> makeCameraPath(CameraPathKind kind, const std::vector<Mat4>& cameras, int frames) {
  GLINT_CHECK(frames >= 1 && !cameras.empty(), "a camera path needs frames and cameras");
  std::vector<Mat4> path;
  path.reserve(size_t(frames));
  if (kind == CameraPathKind::DatasetTest) {
    int count = int(cameras.size());
    if (frames == count || count == 1) {
      for (int i = 0; i < frames; ++i) path.push_back(cameras[size_t(std::min(i, count - 1))]);
      return path;
    }
    auto at = [&](int i) -> const Mat4& { return cameras[size_t(std::clamp(i, 0, count - 1))]; };
    for (int f = 0; f < frames; ++f) {
      double s = frames > 1 ? double(f) * (count - 1) / (frames - 1) : 0.0;
      int i = std::min(int(s), count - 2);
      double t = s - i;
      Vec3d eye = catmullRom(at(i - 1).column(3), at(i).column(3), at(i + 1).column(3), at(i + 2).column(3), t);
      // Blended directions (normalised linear blends: neighbouring test cameras differ by
      // small rotations, where this is as smooth as a slerp and needs no quaternions).
      Vec3d forward = normalize(-at(i).column(2) * (1 - t) + -at(i + 1).column(2) * t);
      Vec3d up = normalize(at(i).column(1) * (1 - t) + at(i + 1).column(1) * t);
      path.push_back(Mat4::lookAt(eye, eye + forward, up));
    }
    return path;
  }
  CameraRing ring = cameraRing(cameras);
  for (int f = 0; f < frames; ++f) {
    double t = double(f) / frames;  // the loop closes: the frame after the last is the first
    if (kind == CameraPathKind::Orbit) {
      path.push_back(lookingAt(ringPoint(ring, 2 * std::numbers::pi * t, ring.radius, ring.height), ring));
    } else {
      double rise = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * t);  // 0 -> 1 -> 0
      double height = ring.lowest + (ring.highest - ring.lowest) * rise;
      double radius = ring.radius * (1.0 - 0.2 * rise);
      path.push_back(lookingAt(ringPoint(ring, 4 * std::numbers::pi * t, radius, height), ring));
    }
  }
  return path;
}

}  // namespace glint
