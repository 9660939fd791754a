// Camera convention conversions: exact round trips, COLMAP's own projection equations
// against our rays, and nerfstudio's ns-process-data conversion against ours.
#include "scene/camera_conventions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/error.h"
#include "math/quat.h"

namespace glint {
namespace {

// Unit quaternions covering every branch of the matrix-to-quaternion conversion: small
// and large angles, 180-degree turns about each axis, and negative w (the same rotation
// as -q).
std::vector<Quatd> testRotations() {
  std::vector<Quatd> rotations = {{1, 0, 0, 0},  {0, 1, 0, 0},       {0, 0, 1, 0},   {0, 0, 0, 1},
                                  {-0.5, 0.5, -0.5, 0.5}, {0.1, 0.9, -0.3, 0.2}, {0.05, 0.2, 0.95, -0.1},
                                  {0.02, -0.1, 0.2, -0.97}};
  std::mt19937 rng(21);
  std::normal_distribution<double> normal;
  for (int i = 0; i < 40; ++i) rotations.push_back({normal(rng), normal(rng), normal(rng), normal(rng)});
  for (Quatd& q : rotations) q = q.normalized();
  return rotations;
}

ColmapCamera pinhole(uint32_t id) { return ColmapCamera{id, "PINHOLE", 640, 480, {500.5, 480.25, 321.5, 243.75}}; }

ColmapImage image(const Quatd& q, const Vec3d& t, uint32_t cameraId, const std::string& name = "img.png") {
  ColmapImage im;
  im.id = 5;
  im.qvec = q;
  im.tvec = t;
  im.cameraId = cameraId;
  im.name = name;
  return im;
}

void expectNear(const Mat4& a, const Mat4& b, double tolerance) {
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(a.m[r][c], b.m[r][c], tolerance) << r << "," << c;
}

TEST(CameraConventions, ColmapToOursToColmapIsTheIdentity) {
  ColmapCamera camera = pinhole(3);
  for (const Quatd& q : testRotations()) {
    ColmapImage in = image(q, {0.5, -1.25, 3.0}, 3);
    CaptureCamera ours = fromColmap(camera, in);
    ColmapView back = toColmap(ours, 3, 5);
    double sign = (back.image.qvec.w * q.w + back.image.qvec.x * q.x + back.image.qvec.y * q.y +
                   back.image.qvec.z * q.z) < 0 ? -1.0 : 1.0;
    EXPECT_GE(back.image.qvec.w, 0.0);
    EXPECT_NEAR(sign * back.image.qvec.w, q.w, 1e-12);
    EXPECT_NEAR(sign * back.image.qvec.x, q.x, 1e-12);
    EXPECT_NEAR(sign * back.image.qvec.y, q.y, 1e-12);
    EXPECT_NEAR(sign * back.image.qvec.z, q.z, 1e-12);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(back.image.tvec[i], in.tvec[i], 1e-12);
    EXPECT_EQ(back.image.name, in.name);
    EXPECT_EQ(back.image.cameraId, 3u);
    EXPECT_EQ(back.camera.model, "PINHOLE");
    EXPECT_EQ(back.camera.params, camera.params);
    EXPECT_EQ(back.camera.width, 640);
    EXPECT_EQ(back.camera.height, 480);
  }
  // SIMPLE_PINHOLE comes back as PINHOLE with fx = fy.
  ColmapCamera simple{1, "SIMPLE_PINHOLE", 100, 50, {70, 50.5, 25.5}};
  ColmapView back = toColmap(fromColmap(simple, image({1, 0, 0, 0}, {}, 1)), 1, 1);
  EXPECT_EQ(back.camera.params, (std::vector<double>{70, 70, 50.5, 25.5}));
}

TEST(CameraConventions, OursToColmapToOursIsTheIdentity) {
  CaptureCamera ours;
  ours.imageName = "a/b.jpg";
  ours.width = 100, ours.height = 80;
  ours.fx = 90, ours.fy = 91, ours.cx = 50.5, ours.cy = 39.5;
  for (const Vec3d& eye : {Vec3d(3, 1, 2), Vec3d(0, 0, 5), Vec3d(-1, -4, 0.5), Vec3d(0, 2, 0)}) {
    ours.cameraToWorld = Mat4::lookAt(eye, {0.1, 0.2, 0.3}, {0, 0, 1});
    CaptureCamera again = fromColmap(toColmap(ours, 1, 1).camera, toColmap(ours, 1, 1).image);
    expectNear(again.cameraToWorld, ours.cameraToWorld, 1e-12);
    EXPECT_EQ(again.imageName, ours.imageName);
    EXPECT_EQ(again.fx, ours.fx);
    EXPECT_EQ(again.fy, ours.fy);
    EXPECT_EQ(again.cx, ours.cx);
    EXPECT_EQ(again.cy, ours.cy);
  }
}

TEST(CameraConventions, NerfstudioToOursToNerfstudioIsTheIdentity) {
  NerfstudioFrame frame;
  frame.filePath = "images/frame_00001.png";
  frame.width = 960, frame.height = 540;
  frame.fx = 800.5, frame.fy = 801.25, frame.cx = 480.125, frame.cy = 269.5;
  frame.transformMatrix = Mat4::lookAt({1, 2, 3}, {0, 0, 0}, {0, 0, 1});
  NerfstudioFrame back = toNerfstudio(fromNerfstudio(frame));
  EXPECT_EQ(back.filePath, frame.filePath);
  EXPECT_EQ(back.width, frame.width);
  EXPECT_EQ(back.height, frame.height);
  EXPECT_EQ(back.fx, frame.fx);
  EXPECT_EQ(back.fy, frame.fy);
  EXPECT_EQ(back.cx, frame.cx);
  EXPECT_EQ(back.cy, frame.cy);
  EXPECT_EQ(back.transformMatrix.m, frame.transformMatrix.m);
}

// COLMAP's pinhole projection, written from its documentation: x = R X + t, then
// u = fx x/z + cx, v = fy y/z + cy, with pixel centres at +0.5.
Vec2d colmapProject(const ColmapCamera& camera, const ColmapImage& im, const Vec3d& world) {
  Vec3d x = quatToRotation(im.qvec) * world + im.tvec;
  const std::vector<double>& p = camera.params;
  return {p[0] * x.x / x.z + p[2], p[1] * x.y / x.z + p[3]};
}

// Distance from a point to the ray through pixel (u, v), and the ray parameter there.
double distanceToRay(const CaptureCamera& camera, Vec2d pixel, const Vec3d& point, double* along) {
  Vec3d origin = camera.cameraToWorld.column(3);
  Vec3d direction = normalize(camera.cameraToWorld.transformVector(cameraRayDirection(camera, pixel.x, pixel.y)));
  *along = dot(point - origin, direction);
  return length(point - origin - direction * *along);
}

TEST(CameraConventions, OurRayThroughCOLMAPsProjectionHitsThePoint) {
  ColmapCamera camera = pinhole(1);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1, 1);
  for (const Quatd& q : testRotations()) {
    ColmapImage im = image(q, {0.3, -0.2, 4.0}, 1);
    CaptureCamera ours = fromColmap(camera, im);
    // Points in front of the camera: built in COLMAP's camera space, then to the world.
    Mat3d r = quatToRotation(q);
    for (int i = 0; i < 5; ++i) {
      Vec3d local(uniform(rng), uniform(rng), 2 + uniform(rng));
      Vec3d world = r.transposeTimes(local - im.tvec);
      Vec2d pixel = colmapProject(camera, im, world);
      double along = 0;
      EXPECT_LT(distanceToRay(ours, pixel, world, &along), 1e-9 * length(world - ours.cameraToWorld.column(3)));
      EXPECT_GT(along, 0.0);  // in front of the camera, not behind it
    }
  }
  // The principal point looks straight down -z, and the centre of pixel (0, 0) up and left.
  CaptureCamera ours = fromColmap(camera, image({1, 0, 0, 0}, {}, 1));
  EXPECT_EQ(cameraRayDirection(ours, 321.5, 243.75), Vec3d(0, 0, -1));
  Vec3d corner = cameraRayDirection(ours, 0.5, 0.5);
  EXPECT_LT(corner.x, 0);
  EXPECT_GT(corner.y, 0);
}

// nerfstudio's ns-process-data conversion of a COLMAP image (process_data/colmap_utils.py,
// colmap_to_json), written out: invert world-to-camera, negate the y and z columns
// (OpenCV to OpenGL axes), then swap world rows y and z and negate the new z row; the same
// row operation on the identity is the applied_transform it records.
Mat4 nsProcessDataPose(const ColmapImage& im) {
  Mat3d r = quatToRotation(im.qvec);
  Mat4 w2c = Mat4::identity();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) w2c.m[i][j] = r.m[i][j];
    w2c.m[i][3] = im.tvec[i];
  }
  Mat4 c2w = w2c.inverse();
  for (int i = 0; i < 3; ++i) c2w.m[i][1] *= -1, c2w.m[i][2] *= -1;
  Mat4 out = c2w;
  out.m[1] = c2w.m[2];
  out.m[2] = c2w.m[1];
  for (double& v : out.m[2]) v = -v;
  return out;
}

Mat4 nsAppliedTransform() {
  Mat4 a = Mat4::identity();
  a.m[1] = {0, 0, 1, 0};
  a.m[2] = {0, -1, 0, 0};
  return a;
}

TEST(CameraConventions, NsProcessDataPosesAreOursInTheAppliedTransformsWorld) {
  ColmapCamera camera = pinhole(1);
  Mat4 applied = nsAppliedTransform();
  for (const Quatd& q : testRotations()) {
    ColmapImage im = image(q, {-0.7, 0.4, 2.5}, 1);
    CaptureCamera ours = fromColmap(camera, im);
    expectNear(nsProcessDataPose(im), applied * ours.cameraToWorld, 1e-12);

    // A COLMAP point, mapped by applied_transform, lies on the nerfstudio camera's ray
    // through the pixel COLMAP projects it to.
    NerfstudioFrame frame;
    frame.filePath = im.name;
    frame.width = camera.width, frame.height = camera.height;
    frame.fx = camera.params[0], frame.fy = camera.params[1], frame.cx = camera.params[2], frame.cy = camera.params[3];
    frame.transformMatrix = nsProcessDataPose(im);
    Vec3d world = quatToRotation(q).transposeTimes(Vec3d(0.2, -0.3, 3.0) - im.tvec);
    Vec2d pixel = colmapProject(camera, im, world);
    PointCloud cloud = colmapPointCloud({ColmapPoint{1, world, {0, 0, 0}, 0, {}}}, applied);
    double along = 0;
    EXPECT_LT(distanceToRay(fromNerfstudio(frame), pixel, applied.transformPoint(world), &along), 1e-9);
    EXPECT_GT(along, 0.0);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(cloud.positions[0][i], applied.transformPoint(world)[i], 1e-5);
  }
}

TEST(CameraConventions, CaptureFromColmapSortsByNameAndKeepsPoints) {
  ColmapModel model;
  model.cameras = {pinhole(2), ColmapCamera{9, "SIMPLE_PINHOLE", 10, 10, {8, 5, 5}}};
  model.images = {image({1, 0, 0, 0}, {1, 2, 3}, 9, "z.png"), image({0, 1, 0, 0}, {0, 0, 1}, 2, "a.png"),
                  image({0, 0, 1, 0}, {0, 0, 2}, 2, "m/b.png")};
  model.points = {ColmapPoint{4, {1, 2, 3}, {255, 0, 51}, 0.5, {}}};
  CaptureScene scene = captureFromColmap(model);
  ASSERT_EQ(scene.cameras.size(), 3u);
  EXPECT_EQ(scene.cameras[0].imageName, "a.png");
  EXPECT_EQ(scene.cameras[1].imageName, "m/b.png");
  EXPECT_EQ(scene.cameras[2].imageName, "z.png");
  EXPECT_EQ(scene.cameras[2].fx, 8);
  EXPECT_EQ(scene.cameras[2].width, 10);
  // Camera 9 is identity-rotated and sits at -t.
  EXPECT_EQ(scene.cameras[2].cameraToWorld.column(3), Vec3d(-1, -2, -3));
  ASSERT_EQ(scene.points.positions.size(), 1u);
  EXPECT_EQ(scene.points.positions[0], Vec3f(1, 2, 3));
  EXPECT_EQ(scene.points.colors[0], Rgb(1.0f, 0.0f, 0.2f));

  model.cameras[0] = ColmapCamera{2, "SIMPLE_RADIAL", 640, 480, {500, 320, 240, 0.01}};
  try {
    captureFromColmap(model);
    FAIL() << "distorted camera accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("colmap image_undistorter"), std::string::npos) << e.what();
  }
  model.images[0].cameraId = 77;
  EXPECT_THROW(captureFromColmap(model), Error);
}

TEST(CameraConventions, CaptureFromNerfstudioSortsByPath) {
  NerfstudioTransforms transforms;
  transforms.frames.resize(2);
  transforms.frames[0].filePath = "images/2.png";
  transforms.frames[1].filePath = "images/1.png";
  std::vector<CaptureCamera> cameras = captureFromNerfstudio(transforms);
  ASSERT_EQ(cameras.size(), 2u);
  EXPECT_EQ(cameras[0].imageName, "images/1.png");
  EXPECT_EQ(cameras[1].imageName, "images/2.png");
}

}  // namespace
}  // namespace glint
