// COLMAP's reconstruction of a synthesized capture (tests/data/colmap_gallery) agrees with
// the true cameras of that capture, up to the similarity that structure from motion
// cannot know (world origin, orientation and scale).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "io/colmap_model.h"
#include "math/mat3.h"
#include "scene/camera_conventions.h"

namespace glint {
namespace {

const std::filesystem::path kFixture = std::filesystem::path(GLINT_TEST_DATA) / "colmap_gallery";

// The model to check, and the truth: the committed fixture's, or, where the environment
// names them, a fresh reconstruction's (the colmap_capture test checks `glint capture`'s
// model of the same photographs this way).
std::filesystem::path modelFolder(const char* variable, const char* fixtureFolder) {
  const char* given = std::getenv(variable);
  return given && *given ? std::filesystem::path(given) : kFixture / fixtureFolder;
}

// The bounds a model is held to. COLMAP's result varies from run to run, threads and seeds
// alike: in six runs of `glint capture` on these 24 photographs, two missed the committed
// model's bounds (a mean position error of 8.6 cm, one camera 59 cm and 4.3 degrees off; a
// focal length 3.9% off). Two later runs (SIMPLE_PINHOLE, 2026-11-28, beside other tests) did
// not close the ring of views: its ends, views 0 and 23, were up to 83 and 81 cm off, the
// other cameras 3-24 cm, the mean up to 16.8 cm. A fresh reconstruction (GLINT_COLMAP_MODEL)
// is held to bounds that take that in, and colmap_capture runs COLMAP once more when a run
// misses them. What those bounds still catch: a wrong convention or a view given another's
// pose, which moves cameras by metres or turns them by 15 degrees or more. The committed
// model, a good run, is held to the strict ones.
struct Bounds {
  double focal, meanPosition, maxPosition, maxDegrees;  // relative; fractions of the room; degrees
  size_t leastRegistered;                               // of the 24 images
};
Bounds boundsFor() {
  const char* fresh = std::getenv("GLINT_COLMAP_MODEL");
  if (fresh && *fresh) return {0.06, 0.03, 0.15, 6.0, 20};
  return {0.02, 0.01, 0.03, 2.0, 24};
}

Mat3d rotationOf(const Mat4& m) {
  Mat3d r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = m.m[i][j];
  return r;
}

// The nearest rotation to a near-rotation matrix, by Gram-Schmidt on its rows (enough
// for an average of rotations that differ by a fraction of a degree).
Mat3d orthonormalised(Mat3d r) {
  r.m[0] = normalize(r.m[0]);
  r.m[1] = normalize(r.m[1] - r.m[0] * dot(r.m[0], r.m[1]));
  r.m[2] = cross(r.m[0], r.m[1]);
  return r;
}

double rotationAngleDegrees(const Mat3d& r) {
  double c = std::clamp((r.m[0].x + r.m[1].y + r.m[2].z - 1) / 2, -1.0, 1.0);
  return std::acos(c) * 180 / 3.14159265358979;
}

// x_true = s R x_colmap + t, estimated from the cameras: R as the mean of the per-camera
// rotations R_true R_colmap^T, s as the ratio of the centres' spreads, t from their means.
struct Similarity {
  Mat3d rotation;
  double scale = 1;
  Vec3d translation;
  Vec3d apply(const Vec3d& x) const { return rotation * x * scale + translation; }
};

Similarity alignCameras(const std::vector<CaptureCamera>& truth, const std::vector<CaptureCamera>& colmap) {
  Mat3d sum;
  for (int i = 0; i < 3; ++i) sum.m[i] = Vec3d(0.0);
  Vec3d meanTrue(0.0), meanColmap(0.0);
  for (size_t k = 0; k < truth.size(); ++k) {
    Mat3d r = rotationOf(truth[k].cameraToWorld) * rotationOf(colmap[k].cameraToWorld).transposed();
    for (int i = 0; i < 3; ++i) sum.m[i] = sum.m[i] + r.m[i];
    meanTrue = meanTrue + truth[k].cameraToWorld.column(3);
    meanColmap = meanColmap + colmap[k].cameraToWorld.column(3);
  }
  meanTrue = meanTrue / double(truth.size());
  meanColmap = meanColmap / double(truth.size());
  Similarity s;
  s.rotation = orthonormalised(sum);
  double spreadTrue = 0, spreadColmap = 0;
  for (size_t k = 0; k < truth.size(); ++k) {
    spreadTrue += dot(truth[k].cameraToWorld.column(3) - meanTrue, truth[k].cameraToWorld.column(3) - meanTrue);
    Vec3d c = colmap[k].cameraToWorld.column(3) - meanColmap;
    spreadColmap += dot(c, c);
  }
  s.scale = std::sqrt(spreadTrue / spreadColmap);
  s.translation = meanTrue - s.rotation * meanColmap * s.scale;
  return s;
}

TEST(ColmapGalleryFixture, EveryImageRegisteredWithCamerasCloseToTheTruth) {
  CaptureScene truth = captureFromColmap(readColmapModel(modelFolder("GLINT_COLMAP_TRUTH", "true")));
  CaptureScene colmap = captureFromColmap(readColmapModel(modelFolder("GLINT_COLMAP_MODEL", "colmap")));
  ASSERT_GE(truth.cameras.size(), 24u);
  // The committed model registered every image; a fresh run may leave a few out (the
  // colmap_capture test asks for 20 of 24), so the truth is taken for the images it kept.
  const Bounds bounds = boundsFor();
  std::map<std::string, CaptureCamera> trueByName;
  for (const CaptureCamera& c : truth.cameras) trueByName[c.imageName] = c;
  std::vector<CaptureCamera> matched;
  for (const CaptureCamera& c : colmap.cameras) {
    auto found = trueByName.find(c.imageName);
    ASSERT_NE(found, trueByName.end()) << "COLMAP's model names an image the truth has not: " << c.imageName;
    matched.push_back(found->second);
  }
  ASSERT_GE(colmap.cameras.size(), bounds.leastRegistered) << "COLMAP left images out";
  truth.cameras = std::move(matched);

  // Intrinsics: one shared camera whose focal length COLMAP refined from the true one.
  for (const CaptureCamera& c : colmap.cameras) {
    EXPECT_NEAR(c.fx / truth.cameras[0].fx, 1.0, bounds.focal);
    EXPECT_NEAR(c.fy / truth.cameras[0].fy, 1.0, bounds.focal);
  }

  Similarity s = alignCameras(truth.cameras, colmap.cameras);
  const double roomSize = 8.0;  // builtin:gallery is 8 m wide
  double sumError = 0, maxError = 0, maxAngle = 0;
  for (size_t k = 0; k < truth.cameras.size(); ++k) {
    Vec3d aligned = s.apply(colmap.cameras[k].cameraToWorld.column(3));
    double error = length(aligned - truth.cameras[k].cameraToWorld.column(3));
    sumError += error, maxError = std::max(maxError, error);
    Mat3d difference = rotationOf(truth.cameras[k].cameraToWorld).transposed() * s.rotation *
                       rotationOf(colmap.cameras[k].cameraToWorld);
    maxAngle = std::max(maxAngle, rotationAngleDegrees(difference));
  }
  std::printf("cameras against the truth: mean position error %.3f m, largest %.3f m, largest angle %.2f degrees\n",
              sumError / truth.cameras.size(), maxError, maxAngle);
  EXPECT_LT(sumError / truth.cameras.size(), bounds.meanPosition * roomSize);
  EXPECT_LT(maxError, bounds.maxPosition * roomSize);
  EXPECT_LT(maxAngle, bounds.maxDegrees);
  // The sparse points land in the room after the same alignment (a few stray ones may not).
  int inside = 0;
  for (const Vec3f& p : colmap.points.positions) {
    Vec3d q = s.apply(Vec3d(p));
    inside += std::abs(q.x) < 4.3 && std::abs(q.z) < 4.3 && q.y > -0.3 && q.y < 3.8;
  }
  EXPECT_GT(inside, int(0.9 * colmap.points.positions.size()));
}

}  // namespace
}  // namespace glint
