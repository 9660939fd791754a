// Camera spheres from depth buffers, and culling exactly the Gaussians inside them.
#include "train/camera_culling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/parallel.h"
#include "io/temp_folder.h"
#include "math/rng.h"
#include "scene/capture_dataset.h"
#include "train/plane_dataset.h"
#include "train/room_capture.h"

namespace glint {
namespace {

TEST(CameraSphere, RadiusIsTheFactorTimesTheNearestSurfaceDepth) {
  Camera camera = Camera::fromFieldOfView(Mat4::translation(Vec3d(1, 2, 3)), 0.8, 4, 3);
  Image depth(4, 3, 1, 5.0f);
  depth.at(0, 0) = 0.0f;      // no surface: ignored although smallest
  depth.at(1, 0) = 1.0e10f;   // no surface
  depth.at(2, 1) = 2.5f;      // the nearest surface
  depth.at(3, 2) = 2.75f;
  std::optional<CameraSphere> sphere = cameraSphere(depth, camera);
  ASSERT_TRUE(sphere);
  EXPECT_EQ(sphere->centre(), Vec3d(1, 2, 3));
  EXPECT_NEAR(sphere->radius, 0.8 * 2.5, 1e-6);  // the factor is a float
  EXPECT_EQ(cameraSphere(depth, camera, 0.5f)->radius, 1.25);

  Image empty(4, 3, 1, 0.0f);
  EXPECT_FALSE(cameraSphere(empty, camera));
}

TEST(CameraSpheres, OnePerViewWithASurface) {
  test::TempFolder folder;
  std::vector<Vec3d> eyes = test::ringOfEyes(4);
  test::PlaneDataset data = test::writePlaneDataset(folder.path(), eyes, 2);
  Dataset dataset = Dataset::open(folder.path());
  std::vector<CameraSphere> spheres = cameraSpheres(dataset, dataset.train());
  ASSERT_EQ(spheres.size(), 3u);  // view 2 sees no surface
  const size_t views[] = {0, 1, 3};
  for (size_t s = 0; s < spheres.size(); ++s) {
    const Image& depth = data.trainBuffers[views[s]][Buffer::Depth];
    float nearest = *std::min_element(depth.pixels.begin(), depth.pixels.end());  // every pixel hits
    EXPECT_NEAR(length(spheres[s].centre() - eyes[views[s]]), 0.0, 1e-12);
    EXPECT_NEAR(spheres[s].radius, 0.8 * nearest, 1e-6);
    // The plane z = 0 lies outside the sphere, as all real geometry must.
    EXPECT_LT(spheres[s].radius, eyes[views[s]].z);
  }
}

TEST(NearestPointInView, CountsOnlyPointsTheImageShows) {
  const Camera camera = Camera::fromFieldOfView(Mat4::identity(), 1.2, 40, 30);  // looks down -z
  EXPECT_EQ(nearestPointInView(camera, {}), std::numeric_limits<double>::infinity());
  const std::vector<Vec3d> points = {Vec3d(0, 0, -3), Vec3d(0, 0, 1),  // behind the camera
                                     Vec3d(100, 0, -1),                 // outside the image
                                     Vec3d(0.5, 0, -2)};
  EXPECT_NEAR(nearestPointInView(camera, points), std::sqrt(4.25), 1e-12);
}

// A capture's spheres never reach past its sparse points: with exact priors the depth
// buffer's nearest surface decides (no point in view is nearer), with a monocular
// predictor's relative depth, aligned up to several times too far, the points bound it.
TEST(CameraSpheres, ACapturesSparsePointsBoundTheRadius) {
  test::TempFolder folder;
  test::writeRoomCapture(folder / "exact", PriorErrors::None);
  test::writeRoomCapture(folder / "monocular", PriorErrors::Monocular);
  for (const char* name : {"exact", "monocular"}) {
    const Dataset dataset = Dataset::open(folder / name, true, 8);
    const std::vector<CameraSphere> spheres = cameraSpheres(dataset, dataset.train());
    ASSERT_EQ(spheres.size(), dataset.train().views.size()) << name;
    for (size_t v = 0; v < spheres.size(); ++v) {
      const double fromDepth =
          cameraSphere(dataset.loadBuffer(dataset.train(), v, Buffer::Depth), dataset.train().camera(v))->radius;
      const double fromPoints = 0.8 * nearestPointInView(dataset.train().camera(v), dataset.capture()->points);
      EXPECT_NEAR(spheres[v].radius, std::min(fromDepth, fromPoints), 1e-6) << name << " view " << v;
      // Up to the pixel grid: a point near the image's edge may lie nearer than the surface
      // seen at the centre of its pixel (1.5% in one view of this 64x48 capture).
      if (std::string(name) == "exact") {
        EXPECT_LE(fromDepth, fromPoints * 1.03) << "view " << v;
      }
    }
  }
}

TEST(CullRegion, InViewLimitsTheSphereToWhatTheCameraSees) {
  // A 40x30 camera at the origin looking down -z (identity pose), sphere radius 2.
  CameraSphere sphere{Camera::fromFieldOfView(Mat4::identity(), 1.2, 40, 30), 2.0};
  const Vec3d ahead(0.1, -0.2, -1.0), behind(0, 0, 1.0), aside(1.5, 0, -0.2), farAhead(0, 0, -3.0);
  for (CullRegion region : {CullRegion::SphereInView, CullRegion::WholeSphere}) {
    EXPECT_TRUE(insideCullRegion(sphere, ahead, region));
    EXPECT_FALSE(insideCullRegion(sphere, farAhead, region));
  }
  EXPECT_FALSE(insideCullRegion(sphere, behind, CullRegion::SphereInView));
  EXPECT_FALSE(insideCullRegion(sphere, aside, CullRegion::SphereInView));  // outside the field of view
  EXPECT_TRUE(insideCullRegion(sphere, behind, CullRegion::WholeSphere));
  EXPECT_TRUE(insideCullRegion(sphere, aside, CullRegion::WholeSphere));
}

TEST(CullRegion, InViewMatchesTheRaysOfTheCamerasPixels) {
  // Points along the rays through pixel positions just inside and just outside the image
  // are in view exactly when the position is inside.
  Camera camera = Camera::fromFieldOfView(Mat4::lookAt(Vec3d(1, 2, 3), Vec3d(0, 0.5, 0), Vec3d(0, 1, 0)), 0.9, 16, 12);
  CameraSphere sphere{camera, 10.0};
  const double e = 1e-3;
  const double positions[][2] = {{e, e}, {16 - e, 12 - e}, {8, 6}, {-e, 6}, {16 + e, 6}, {8, -e}, {8, 12 + e}};
  for (const auto& pos : positions) {
    Ray ray = camera.generateRay(pos[0], pos[1]);
    bool inside = pos[0] >= 0 && pos[0] < 16 && pos[1] >= 0 && pos[1] < 12;
    EXPECT_EQ(insideCullRegion(sphere, ray.origin + ray.direction * 2.0, CullRegion::SphereInView), inside)
        << pos[0] << ", " << pos[1];
  }
}

struct CullingCase {
  GaussianScene scene;
  std::vector<CameraSphere> spheres;
};

CullingCase randomCase(int gaussians, int sphereCount) {
  Rng rng = Rng::forKeys({11});
  CullingCase c;
  c.scene.resize(size_t(gaussians));
  for (int i = 0; i < gaussians; ++i) {
    c.scene.position[size_t(i)] = Vec3f(8.0f * rng.uniform() - 4.0f, 8.0f * rng.uniform() - 4.0f, 4.0f * rng.uniform());
    c.scene.diffuse[size_t(i)] = Rgb(float(i));  // identifies the Gaussian after filtering
  }
  for (int s = 0; s < sphereCount; ++s) {
    Vec3d eye(6.0 * rng.uniformDouble() - 3.0, 6.0 * rng.uniformDouble() - 3.0, 4.0 * rng.uniformDouble());
    Vec3d target(rng.uniformDouble(), rng.uniformDouble(), rng.uniformDouble());
    Camera camera =
        Camera::fromFieldOfView(Mat4::lookAt(eye, target, Vec3d(0, 0, 1)), 0.6 + rng.uniformDouble(), 32, 24);
    c.spheres.push_back({camera, 0.2 + 0.8 * rng.uniformDouble()});
  }
  return c;
}

// The expectation written out: distance to the camera centre, then the pinhole projection
// through the inverse of the camera pose.
std::vector<bool> expectedKeep(const CullingCase& c, CullRegion region) {
  std::vector<bool> keep(c.scene.size(), true);
  for (size_t i = 0; i < c.scene.size(); ++i)
    for (const CameraSphere& s : c.spheres) {
      Vec3d p(c.scene.position[i]);
      Vec3d d = p - s.camera.position();
      if (!(dot(d, d) < s.radius * s.radius)) continue;
      Vec3d local = s.camera.cameraToWorld.inverse().transformPoint(p);
      double px = s.camera.cx + s.camera.fx * local.x / -local.z, py = s.camera.cy - s.camera.fy * local.y / -local.z;
      bool inView = local.z < 0 && px >= 0 && px < 32 && py >= 0 && py < 24;
      if (region == CullRegion::WholeSphere || inView) keep[i] = false;
    }
  return keep;
}

TEST(CameraCulling, RemovesExactlyTheGaussiansInsideAnyCullRegion) {
  CullingCase c = randomCase(20000, 30);
  for (CullRegion region : {CullRegion::SphereInView, CullRegion::WholeSphere}) {
    std::vector<bool> expected = expectedKeep(c, region);
    size_t inside = size_t(std::count(expected.begin(), expected.end(), false));
    ASSERT_GT(inside, 100u);  // the case tests something
    ASSERT_LT(inside, c.scene.size() - 100);
    EXPECT_EQ(outsideCameraSpheres(c.scene, c.spheres, region), expected);

    GaussianScene culled = c.scene;
    EXPECT_EQ(cullInsideCameraSpheres(culled, c.spheres, region), inside);
    ASSERT_EQ(culled.size(), c.scene.size() - inside);
    EXPECT_TRUE(culled.consistent());
    size_t next = 0;  // survivors keep their order
    for (size_t i = 0; i < c.scene.size(); ++i)
      if (expected[i]) {
        EXPECT_EQ(culled.position[next], c.scene.position[i]);
        EXPECT_EQ(culled.diffuse[next], c.scene.diffuse[i]);
        ++next;
      }
  }
  // The in-view region is part of the sphere, so it removes fewer.
  std::vector<bool> inView = expectedKeep(c, CullRegion::SphereInView);
  std::vector<bool> whole = expectedKeep(c, CullRegion::WholeSphere);
  EXPECT_LT(std::count(inView.begin(), inView.end(), false), std::count(whole.begin(), whole.end(), false));
}

TEST(CameraCulling, NoSpheresKeepEverything) {
  CullingCase c = randomCase(100, 0);
  EXPECT_EQ(cullInsideCameraSpheres(c.scene, {}), 0u);
  EXPECT_EQ(c.scene.size(), 100u);
}

TEST(CameraCulling, IndependentOfTheThreadCount) {
  CullingCase c = randomCase(50000, 20);
  std::vector<bool> one, two;
  {
    ThreadLimit limit(1);
    one = outsideCameraSpheres(c.scene, c.spheres);
  }
  {
    ThreadLimit limit(2);
    two = outsideCameraSpheres(c.scene, c.spheres);
  }
  EXPECT_EQ(one, two);
}

}  // namespace
}  // namespace glint
