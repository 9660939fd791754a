// Multi-view agreement of depth targets: exact depth agrees, a wrong view's depth or a
// turned camera's does not, and the training views leave the disagreeing pixels out.
#include "train/depth_consistency.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "io/temp_folder.h"
#include "scene/dataset.h"
#include "train/plane_dataset.h"
#include "train/training_views.h"

namespace glint {
namespace {

constexpr int kWidth = 128, kHeight = 96;

// The floor z = 0 with a ball of radius 0.5 resting on it at the origin: depth varies
// smoothly on both and jumps at the ball's silhouette.
double ballDepth(const Ray& ray) {
  const Vec3d oc = ray.origin - Vec3d(0, 0, 0.5);
  const double b = dot(oc, ray.direction), c = dot(oc, oc) - 0.25, disc = b * b - c;
  const double t = disc >= 0.0 ? -b - std::sqrt(disc) : 0.0;
  return t > 0.0 ? t : 0.0;
}

double sceneDepth(const Ray& ray) {
  double nearest = 0.0;
  if (const double t = -ray.origin.z / ray.direction.z; t > 0.0) nearest = t;
  if (const double t = ballDepth(ray); t > 0.0 && (nearest == 0.0 || t < nearest)) nearest = t;
  return nearest;
}

Camera ringCamera(int i, int count, const Vec3d& target = Vec3d(0, 0, 0.3)) {
  const double angle = 2.0 * 3.14159265358979 * i / count;
  const Vec3d eye(1.2 * std::cos(angle), 1.2 * std::sin(angle), 2.5);
  return Camera::fromFieldOfView(Mat4::lookAt(eye, target, Vec3d(0, 0, 1)), 0.9, kWidth, kHeight);
}

// Depth images of the scene as `seenBy` cameras see it (the truth), one vector per view.
std::vector<std::vector<float>> renderDepth(const std::vector<Camera>& seenBy) {
  std::vector<std::vector<float>> depth(seenBy.size());
  for (size_t v = 0; v < seenBy.size(); ++v)
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        depth[v].push_back(float(sceneDepth(seenBy[v].generateRay(x + 0.5, y + 0.5))));
  return depth;
}

DepthLookup lookup(const std::vector<std::vector<float>>& depth) {
  return [&depth](size_t view, size_t pixel) { return depth[view][pixel]; };
}

// The fraction of a view's depth pixels with minAgreeing or more agreeing neighbours; with
// `ballSeenBy`, only those where that camera sees the ball.
double trustedFraction(const DepthConsistency& c, size_t view, int minAgreeing,
                       const std::vector<std::vector<float>>& depth, const Camera* ballSeenBy = nullptr) {
  int64_t with = 0, trusted = 0;
  for (size_t p = 0; p < depth[view].size(); ++p) {
    if (!(depth[view][p] > 0.0f)) continue;
    if (ballSeenBy) {
      const Ray ray = ballSeenBy->generateRay(double(p % kWidth) + 0.5, double(p / kWidth) + 0.5);
      if (ballDepth(ray) == 0.0 || ballDepth(ray) > sceneDepth(ray)) continue;
    }
    ++with, trusted += c.agreeing[view][p] >= minAgreeing ? 1 : 0;
  }
  return double(trusted) / double(with);
}

std::vector<Camera> ring(int count) {
  std::vector<Camera> cameras;
  for (int i = 0; i < count; ++i) cameras.push_back(ringCamera(i, count));
  return cameras;
}

// The slow reference: how many of view v's neighbours see the point at its pixel, by casting
// a ray from each neighbour's centre at it.
int neighboursSeeing(const std::vector<Camera>& cameras, const std::vector<uint32_t>& neighbours, size_t v,
                     size_t pixel, double depth) {
  const Camera& camera = cameras[v];
  const Ray ray = camera.generateRay(double(pixel % kWidth) + 0.5, double(pixel / kWidth) + 0.5);
  const Vec3d x = ray.origin + ray.direction * depth;
  int seeing = 0;
  for (uint32_t u : neighbours) {
    Vec2d p;
    if (!cameras[u].project(cameras[u].cameraToWorld.inverse(), x, &p)) continue;
    const double distance = length(x - cameras[u].position());
    const double hit = sceneDepth(Ray{cameras[u].position(), (x - cameras[u].position()) / distance});
    seeing += std::abs(hit - distance) < 1e-4 * distance ? 1 : 0;
  }
  return seeing;
}

// Exact depth agrees with every neighbour that sees its point, and only with those.
TEST(DepthConsistency, ExactDepthAgreesWithEveryNeighbourThatSeesIt) {
  const std::vector<Camera> cameras = ring(8);
  const std::vector<std::vector<float>> depth = renderDepth(cameras);
  const DepthConsistency c = checkDepthConsistency(cameras, lookup(depth), {});
  int64_t depthPixels = 0, trusted = 0;
  for (size_t v = 0; v < cameras.size(); ++v) {
    EXPECT_EQ(c.neighbours[v].size(), 7u);  // each sees some of what all the others see
    int64_t matching = 0, nearly = 0, pixels = 0;
    for (size_t p = 0; p < depth[v].size(); ++p) {
      if (!(depth[v][p] > 0.0f)) continue;
      ++pixels;
      const int seeing = neighboursSeeing(cameras, c.neighbours[v], v, p, depth[v][p]);
      matching += c.agreeing[v][p] == seeing ? 1 : 0;
      nearly += std::abs(c.agreeing[v][p] - seeing) <= 1 ? 1 : 0;
      trusted += seeing >= 2 ? 1 : 0;
    }
    depthPixels += pixels;
    // Where a neighbour sees the point near the ball's limb its depth changes too fast
    // between pixels to interpolate, and the nearest pixel's may be a few percent off.
    EXPECT_GT(double(matching), 0.9 * double(pixels)) << "view " << v;
    EXPECT_GT(double(nearly), 0.98 * double(pixels)) << "view " << v;
  }
  EXPECT_EQ(c.depthPixels, depthPixels);
  EXPECT_NEAR(double(c.trustedPixels), double(trusted), 0.02 * double(depthPixels));
  EXPECT_GT(double(c.trustedPixels), 0.8 * double(depthPixels));  // the test's cameras overlap well
}

// Depth interpolated between the neighbour's pixel centres, not read at the nearest one: on
// surfaces seen at a slant the nearest pixel's depth is a few percent off.
TEST(DepthConsistency, InterpolationKeepsExactDepthWithinATightTolerance) {
  const std::vector<Camera> cameras = ring(8);
  const std::vector<std::vector<float>> depth = renderDepth(cameras);
  const DepthConsistency usual = checkDepthConsistency(cameras, lookup(depth), {});
  const DepthConsistency tight = checkDepthConsistency(cameras, lookup(depth), {.tolerance = 0.002});
  EXPECT_GT(double(tight.trustedPixels), 0.97 * double(usual.trustedPixels));
}

TEST(DepthConsistency, AViewWhoseDepthIsScaledLosesItsDepthAndOnlyIt) {
  const std::vector<Camera> cameras = ring(8);
  std::vector<std::vector<float>> depth = renderDepth(cameras);
  const DepthConsistency exact = checkDepthConsistency(cameras, lookup(depth), {});
  for (float& z : depth[3]) z *= 1.08f;
  const DepthConsistency c = checkDepthConsistency(cameras, lookup(depth), {});
  EXPECT_LT(trustedFraction(c, 3, 2, depth), 0.05);
  for (size_t v = 0; v < cameras.size(); ++v)
    if (v != 3) {  // the others lose only what view 3 was one of two to confirm
      EXPECT_GT(trustedFraction(c, v, 2, depth), trustedFraction(exact, v, 2, depth) - 0.1) << "view " << v;
    }
  // A tolerance wider than the error keeps it.
  const DepthConsistency wide = checkDepthConsistency(cameras, lookup(depth), {.tolerance = 0.2});
  EXPECT_GT(trustedFraction(wide, 3, 2, depth), trustedFraction(exact, 3, 2, depth) - 0.05);
}

// The view's depth is right for where its camera really points, 4 degrees away from the pose
// it was given: placed with the given pose its points miss the others' surfaces where depth
// varies across the view, on the ball; on the floor a turn slides the points along the
// plane, where the others' depth cannot see it.
TEST(DepthConsistency, ACameraTurnedByDegreesLosesItsDepthWhereDepthVaries) {
  const std::vector<Camera> cameras = ring(8);
  std::vector<Camera> truth = cameras;
  const Vec3d eye = cameras[5].position(), target(0, 0, 0.3);
  const Vec3d side = normalize(cross(target - eye, Vec3d(0, 0, 1)));
  const double turn = std::tan(4.0 * 3.14159265358979 / 180.0) * length(target - eye);
  truth[5] = Camera::fromFieldOfView(Mat4::lookAt(eye, target + side * turn, Vec3d(0, 0, 1)), 0.9, kWidth, kHeight);
  const std::vector<std::vector<float>> exactDepth = renderDepth(cameras);
  const DepthConsistency exact = checkDepthConsistency(cameras, lookup(exactDepth), {});
  const std::vector<std::vector<float>> depth = renderDepth(truth);
  const DepthConsistency c = checkDepthConsistency(cameras, lookup(depth), {});
  const double ballKept = trustedFraction(c, 5, 2, depth, &truth[5]);
  const double ballExact = trustedFraction(exact, 5, 2, exactDepth, &cameras[5]);
  const double kept = trustedFraction(c, 5, 2, depth), keptExact = trustedFraction(exact, 5, 2, exactDepth);
  EXPECT_LT(ballKept, 0.5 * ballExact);
  EXPECT_LT(kept, keptExact);
  EXPECT_GT(trustedFraction(c, 4, 2, depth), trustedFraction(exact, 4, 2, exactDepth) - 0.05);
}

TEST(DepthConsistency, NeighboursAreTheViewsThatSeeTheSameSurfaceMostFirst) {
  std::vector<Camera> cameras = ring(8);
  // A camera beside view 0 sees nearly all of it; one looking up at the sky sees none of it.
  const Vec3d eye0 = cameras[0].position();
  cameras.push_back(Camera::fromFieldOfView(Mat4::lookAt(eye0 + Vec3d(0, 0.05, 0), Vec3d(0, 0, 0.3), Vec3d(0, 0, 1)),
                                            0.9, kWidth, kHeight));
  cameras.push_back(Camera::fromFieldOfView(Mat4::lookAt(eye0, eye0 + Vec3d(0, 0, 1), Vec3d(0, 1, 0)), 0.9, kWidth,
                                            kHeight));
  const std::vector<std::vector<float>> depth = renderDepth(cameras);
  const std::vector<uint32_t> near = overlappingViews(cameras, lookup(depth), 0, 8);
  ASSERT_FALSE(near.empty());
  EXPECT_EQ(near[0], 8u);
  for (size_t v = 0; v < 9; ++v)
    for (uint32_t u : overlappingViews(cameras, lookup(depth), v, 8)) EXPECT_NE(u, 9u) << "view " << v;
  EXPECT_TRUE(overlappingViews(cameras, lookup(depth), 9, 8).empty());  // it has no depth
  EXPECT_EQ(overlappingViews(cameras, lookup(depth), 0, 3).size(), 3u);
}

// A neighbour without depth where a point lands confirms nothing; a pixel without depth is
// neither checked nor counted.
TEST(DepthConsistency, PixelsWithoutDepthAreNeitherCheckedNorConfirming) {
  const std::vector<Camera> cameras = ring(3);
  std::vector<std::vector<float>> depth = renderDepth(cameras);
  for (size_t p = 0; p < depth[0].size(); p += 2) depth[0][p] = 0.0f;
  std::fill(depth[1].begin(), depth[1].end(), 0.0f);
  const DepthConsistency c = checkDepthConsistency(cameras, lookup(depth), {.minAgreeing = 1});
  int64_t with = 0;
  for (size_t p = 0; p < depth[0].size(); ++p) {
    if (depth[0][p] == 0.0f) {
      EXPECT_EQ(c.agreeing[0][p], 0) << p;
    }
    with += depth[0][p] > 0.0f ? 1 : 0;
    EXPECT_LE(c.agreeing[0][p], 1);  // only view 2 can confirm
  }
  for (const auto& d : depth[2]) with += d > 0.0f ? 1 : 0;
  EXPECT_EQ(c.depthPixels, with);
  EXPECT_TRUE(c.neighbours[1].empty());
  for (uint32_t u : c.neighbours[0]) EXPECT_NE(u, 1u);
}

// The training views leave the disagreeing pixels out of the depth term, and only them.
TEST(DepthConsistency, TrainingViewsDropTheDepthTheOthersContradict) {
  test::TempFolder folder;
  const std::vector<Vec3d> eyes = test::ringOfEyes(6, 0.3, 3.0);
  test::PlaneDataset data = test::writePlaneDataset(folder.path(), eyes);
  Image& wrong = data.trainBuffers[2][Buffer::Depth];
  for (float& z : wrong.pixels) z *= 1.1f;
  writeViewBuffers(folder.path(), data.train.views[2], data.trainBuffers[2], ImageFormat::Exr);
  const Dataset dataset = Dataset::open(folder.path());
  TrainingViews views = TrainingViews::load(dataset, dataset.train());
  for (size_t p = 0; p < views.pixelCount(2); ++p) ASSERT_TRUE(views.target(2, p).hasDepth);

  const DepthConsistency c = views.keepConsistentDepth({});
  int64_t untrusted = 0;
  for (size_t v = 0; v < views.viewCount(); ++v) {
    int64_t kept = 0, surfaces = 0;
    for (size_t p = 0; p < views.pixelCount(v); ++p) {
      const PixelTarget t = views.target(v, p);
      if (!t.surface) continue;
      ++surfaces;
      kept += t.hasDepth ? 1 : 0;
      EXPECT_EQ(t.hasDepth, c.agreeing[v][p] >= 2);
    }
    untrusted += surfaces - kept;
    if (v == 2)
      EXPECT_LT(kept, surfaces / 10);
    else  // all but the edge pixels the others' images miss (16x12 views)
      EXPECT_GT(kept, surfaces * 8 / 10) << "view " << v;
  }
  EXPECT_EQ(c.depthPixels - c.trustedPixels, untrusted);
}

}  // namespace
}  // namespace glint
