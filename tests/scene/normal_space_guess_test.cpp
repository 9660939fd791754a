// guessNormalSpace on synthetic normal maps of a sphere, a floor and a room seen from
// several cameras, written in world space and in each camera axes.
#include "scene/normal_space_guess.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

namespace glint {
namespace {

// Camera-to-world rotation of a camera at `eye` looking at `target` (OpenGL axes: the
// columns are right, up and back).
Mat3d lookAt(const Vec3d& eye, const Vec3d& target, const Vec3d& worldUp = {0, 1, 0}) {
  Vec3d back = normalize(eye - target);
  Vec3d right = normalize(cross(worldUp, back));
  Vec3d up = cross(back, right);
  Mat3d r;
  for (int row = 0; row < 3; ++row) r.m[row] = {right[row], up[row], back[row]};
  return r;
}

// What a ray hits: its distance along the unit direction and the world normal.
struct SurfaceHit {
  double t;
  Vec3d normal;
};

// A unit sphere at the origin.
std::optional<SurfaceHit> hitSphere(const Vec3d& o, const Vec3d& d) {
  double b = dot(o, d), c = dot(o, o) - 1.0, disc = b * b - c;
  if (disc < 0) return std::nullopt;
  double t = -b - std::sqrt(disc);
  if (t <= 0) return std::nullopt;
  return SurfaceHit{t, normalize(o + d * t)};
}

// The floor y = -1, seen from above.
std::optional<SurfaceHit> hitFloor(const Vec3d& o, const Vec3d& d) {
  if (d.y >= -1e-9) return std::nullopt;
  double t = (-1.0 - o.y) / d.y;
  if (t <= 0) return std::nullopt;
  return SurfaceHit{t, {0, 1, 0}};
}

// The inside of the box [-4, 4]^3: walls face inwards.
std::optional<SurfaceHit> hitRoom(const Vec3d& o, const Vec3d& d) {
  SurfaceHit best{1e30, {}};
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-4.0, 4.0}) {
      if (std::abs(d[axis]) < 1e-12) continue;
      double t = (side - o[axis]) / d[axis];
      if (t <= 0 || t >= best.t) continue;
      Vec3d n;
      n[axis] = -side / 4.0;
      best = {t, n};
    }
  return best.t < 1e30 ? std::optional(best) : std::nullopt;
}

enum class Written { World, OpenGl, OpenCv, PaperPrior };

struct RenderedView {
  Image normals;
  Image zDepth;
  Mat3d cameraToWorld;
  RayIntrinsics k;
};

// Ray-casts one view: normals in the requested space, and z-depth (0 where nothing is hit).
template <typename Scene>
RenderedView render(Scene scene, const Vec3d& eye, const Mat3d& cameraToWorld, Written written) {
  const int w = 48, h = 36;
  RenderedView view{Image(w, h, 3), Image(w, h, 1), cameraToWorld, RayIntrinsics{40, 40, w / 2.0, h / 2.0}};
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      Vec3d ray = cameraRay(view.k, i + 0.5, j + 0.5);  // z = -1
      std::optional<SurfaceHit> hit = scene(eye, normalize(cameraToWorld * ray));
      if (!hit) continue;
      view.zDepth.at(i, j) = float(hit->t / length(ray));
      Vec3d n = hit->normal;
      if (written != Written::World) {
        CameraAxes axes = written == Written::OpenGl   ? CameraAxes::OpenGl
                          : written == Written::OpenCv ? CameraAxes::OpenCv
                                                       : CameraAxes::PaperPrior;
        n = fromOpenGlAxes(cameraToWorld.transposeTimes(n), axes);
      }
      view.normals.setRgb(i, j, Rgb(n));
    }
  return view;
}

// Cameras around the origin looking at it, from several sides and heights.
std::vector<Vec3d> orbit() {
  return {{0, 0.5, 4}, {4, 1, 0}, {-3, 2, -2}, {0.5, 3.5, -2}, {-4, -0.5, 1}, {2.5, 2, 2.5}};
}

template <typename Scene>
NormalSpaceGuess guessOrbit(Scene scene, Written written, bool withDepth, double eyeScale = 1.0) {
  std::vector<RenderedView> views;
  for (const Vec3d& eye : orbit())
    views.push_back(render(scene, eye * eyeScale, lookAt(eye * eyeScale, {0, 0, 0}), written));
  std::vector<NormalSpaceView> inputs;
  for (const RenderedView& v : views)
    inputs.push_back({&v.normals, v.cameraToWorld, v.k, withDepth ? &v.zDepth : nullptr});
  return guessNormalSpace(inputs);
}

TEST(NormalSpaceGuess, WorldSpaceSphereIsRecognised) {
  NormalSpaceGuess guess = guessOrbit(hitSphere, Written::World, false);
  EXPECT_EQ(guess.space, NormalSpace::World) << guess.summary();
  EXPECT_GT(guess.confidence, 0.8) << guess.summary();
  EXPECT_GT(guess.worldFacing, 0.99);
  EXPECT_GT(guess.pixels, 1000);
}

TEST(NormalSpaceGuess, CameraSpaceSphereIsRecognisedWithItsAxes) {
  NormalSpaceGuess gl = guessOrbit(hitSphere, Written::OpenGl, false);
  EXPECT_EQ(gl.space, NormalSpace::Camera) << gl.summary();
  EXPECT_GT(gl.confidence, 0.8) << gl.summary();
  EXPECT_NE(gl.axes, CameraAxes::OpenCv);
  NormalSpaceGuess cv = guessOrbit(hitSphere, Written::OpenCv, false);
  EXPECT_EQ(cv.space, NormalSpace::Camera) << cv.summary();
  EXPECT_EQ(cv.axes, CameraAxes::OpenCv) << cv.summary();
  EXPECT_GT(cv.axesConfidence, 0.8);
}

TEST(NormalSpaceGuess, MirroredXNeedsDepthToBeTold) {
  // OpenGL and the paper's axes differ only in the sign of x: facing cannot tell them apart.
  NormalSpaceGuess without = guessOrbit(hitSphere, Written::PaperPrior, false);
  EXPECT_EQ(without.space, NormalSpace::Camera);
  EXPECT_LT(without.axesConfidence, 0.3) << without.summary();
  for (Written written : {Written::PaperPrior, Written::OpenGl}) {
    NormalSpaceGuess with = guessOrbit(hitSphere, written, true);
    EXPECT_EQ(with.axes, written == Written::PaperPrior ? CameraAxes::PaperPrior : CameraAxes::OpenGl)
        << with.summary();
    EXPECT_GT(with.axesConfidence, 0.5);
    EXPECT_GT(with.depthAgreement[int(with.axes)], 0.95);
  }
}

TEST(NormalSpaceGuess, WorksInsideARoomAndOnAFloor) {
  NormalSpaceGuess world = guessOrbit(hitRoom, Written::World, false, 0.5);
  EXPECT_EQ(world.space, NormalSpace::World) << world.summary();
  EXPECT_GT(world.confidence, 0.5) << world.summary();
  NormalSpaceGuess camera = guessOrbit(hitRoom, Written::OpenCv, false, 0.5);
  EXPECT_EQ(camera.space, NormalSpace::Camera) << camera.summary();
  EXPECT_EQ(camera.axes, CameraAxes::OpenCv);
  EXPECT_GT(camera.confidence, 0.5) << camera.summary();
  NormalSpaceGuess floor = guessOrbit(hitFloor, Written::OpenGl, false);
  EXPECT_EQ(floor.space, NormalSpace::Camera) << floor.summary();
}

TEST(NormalSpaceGuess, AnIdentityRotationCannotBeDecided) {
  // A camera at +z looking down -z has the identity rotation: both readings agree.
  Vec3d eye(0, 0, 4);
  Mat3d identity;
  RenderedView view = render(hitSphere, eye, identity, Written::World);
  NormalSpaceGuess guess = guessNormalSpace(view.normals, identity, view.k);
  EXPECT_LT(guess.confidence, 0.1) << guess.summary();
  EXPECT_NEAR(guess.worldFacing, guess.cameraFacing[int(CameraAxes::OpenGl)], 1e-12);
}

TEST(NormalSpaceGuess, EmptyMapsGiveNoVerdict) {
  Image empty(8, 8, 3);
  NormalSpaceGuess guess = guessNormalSpace(empty, Mat3d(), RayIntrinsics{8, 8, 4, 4});
  EXPECT_EQ(guess.pixels, 0);
  EXPECT_EQ(guess.confidence, 0.0);
}

}  // namespace
}  // namespace glint
