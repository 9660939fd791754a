// Selections on Gaussian scenes: attribute filters pick exactly the Gaussians whose means lie
// in range; union / intersection / difference combine as sets; oriented boxes, spheres and
// elliptic cylinders include points just inside their boundary and exclude those just outside.
#include "edit/gaussian_selection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "math/rng.h"

namespace glint {
namespace {

GaussianScene sceneAt(const std::vector<Vec3f>& positions) {
  GaussianScene scene;
  scene.resize(positions.size());
  scene.position = positions;
  return scene;
}

Selection shapeSelection(const Shape& shape) {
  Selection s;
  s.kind = Selection::Kind::Shape;
  s.shape = shape;
  return s;
}

GaussianMask select(const Selection& selection, const GaussianScene& scene) {
  EditDocument doc;
  doc.selections["s"] = selection;
  return selectGaussians(doc, "s", scene);
}

TEST(GaussianSelection, AttributeFiltersSelectExactlyTheGaussiansInRange) {
  // Five materials: (diffuse, F0, roughness); metalness = (F - 0.04) / (F - 0.04 + d).
  GaussianScene scene;
  scene.resize(5);
  scene.diffuse = {Rgb(0.5f), Rgb(0.0f), Rgb(0.1f, 0.2f, 0.3f), Rgb(0.8f, 0.0f, 0.1f), Rgb(0.05f)};
  scene.f0 = {Rgb(0.04f), Rgb(0.95f, 0.64f, 0.54f), Rgb(0.04f), Rgb(0.5f), Rgb(0.9f)};
  scene.roughness = {0.5f, 0.05f, 0.9f, 0.2f, 0.01f};
  // Mean F0: 0.04, 0.71, 0.04, 0.5, 0.9; mean diffuse: 0.5, 0, 0.2, 0.3, 0.05;
  // metalness: 0, 1, 0, 0.46/0.76 = 0.605, 0.86/0.91 = 0.945.
  struct Case {
    Attribute attribute;
    float lo, hi;
    GaussianMask expected;
  };
  std::vector<Case> cases = {
      {Attribute::F0, 0.6f, 1.0f, {0, 1, 0, 0, 1}},
      {Attribute::F0, 0.0f, 0.05f, {1, 0, 1, 0, 0}},
      {Attribute::Roughness, 0.0f, 0.1f, {0, 1, 0, 0, 1}},
      {Attribute::Roughness, 0.2f, 0.5f, {1, 0, 0, 1, 0}},  // both ends inclusive
      {Attribute::Diffuse, 0.15f, 0.35f, {0, 0, 1, 1, 0}},
      {Attribute::Metalness, 0.9f, 1.0f, {0, 1, 0, 0, 1}},
      {Attribute::Metalness, 0.5f, 0.7f, {0, 0, 0, 1, 0}},
      {Attribute::Metalness, 0.0f, 0.0f, {1, 0, 1, 0, 0}},
  };
  for (const Case& c : cases) {
    Selection s;
    s.kind = Selection::Kind::Everything;
    s.filters = {{c.attribute, c.lo, c.hi}};
    EXPECT_EQ(select(s, scene), c.expected) << int(c.attribute) << " [" << c.lo << ", " << c.hi << "]";
  }
  // Filters combine with "and".
  Selection both;
  both.filters = {{Attribute::F0, 0.6f, 1.0f}, {Attribute::Roughness, 0.0f, 0.02f}};
  EXPECT_EQ(select(both, scene), (GaussianMask{0, 0, 0, 0, 1}));
}

TEST(GaussianSelection, CombinationsAreSetOperations) {
  // Points on a line x = 0..9; A = [1, 5], B = [4, 8], C = [0, 2] as boxes.
  std::vector<Vec3f> points;
  for (int i = 0; i < 10; ++i) points.push_back({float(i), 0.0f, 0.0f});
  GaussianScene scene = sceneAt(points);
  auto interval = [](float lo, float hi) {
    Shape box;
    box.center = {(lo + hi) / 2, 0, 0};
    box.halfExtent = {(hi - lo) / 2, 1, 1};
    return shapeSelection(box);
  };
  EditDocument doc;
  doc.selections["A"] = interval(1, 5);
  doc.selections["B"] = interval(4, 8);
  doc.selections["C"] = interval(0, 2);
  auto combine = [&](Selection::Kind kind, std::vector<std::string> operands) {
    Selection s;
    s.kind = kind;
    s.operands = std::move(operands);
    return s;
  };
  doc.selections["union"] = combine(Selection::Kind::Union, {"A", "B", "C"});
  doc.selections["intersection"] = combine(Selection::Kind::Intersection, {"A", "B"});
  doc.selections["difference"] = combine(Selection::Kind::Difference, {"A", "B", "C"});
  doc.selections["nested"] = combine(Selection::Kind::Difference, {"union", "intersection"});
  doc.selections["nested"].filters = {{Attribute::Roughness, 0.5f, 1.0f}};
  for (int i = 0; i < 10; i += 2) scene.roughness[i] = 0.7f;  // even x pass the filter

  EXPECT_EQ(selectGaussians(doc, "union", scene), (GaussianMask{1, 1, 1, 1, 1, 1, 1, 1, 1, 0}));
  EXPECT_EQ(selectGaussians(doc, "intersection", scene), (GaussianMask{0, 0, 0, 0, 1, 1, 0, 0, 0, 0}));
  EXPECT_EQ(selectGaussians(doc, "difference", scene), (GaussianMask{0, 0, 0, 1, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(selectGaussians(doc, "nested", scene), (GaussianMask{1, 0, 1, 0, 0, 0, 1, 0, 1, 0}));
}

// Points a small step inside and outside the boundary along several local directions.
void expectBoundary(const Shape& shape, const Mat3f& localToWorld, const std::vector<Vec3f>& boundaryLocal) {
  std::vector<Vec3f> points;
  for (const Vec3f& b : boundaryLocal) {
    points.push_back(shape.center + localToWorld * (b * 0.99f));
    points.push_back(shape.center + localToWorld * (b * 1.01f));
  }
  GaussianMask mask = select(shapeSelection(shape), sceneAt(points));
  for (size_t k = 0; k < boundaryLocal.size(); ++k) {
    EXPECT_EQ(mask[2 * k], 1) << "just inside along local " << boundaryLocal[k].x << " " << boundaryLocal[k].y
                              << " " << boundaryLocal[k].z;
    EXPECT_EQ(mask[2 * k + 1], 0) << "just outside along local " << boundaryLocal[k].x << " "
                                  << boundaryLocal[k].y << " " << boundaryLocal[k].z;
  }
}

// A rotation of 40 degrees about (1, 2, 3), built from its matrix so the test does not rely
// on the code under test to turn the quaternion into axes.
constexpr float kAngle = 40.0f * std::numbers::pi_v<float> / 180.0f;
const Vec3f kAxis = normalize(Vec3f(1, 2, 3));

Mat3f rodrigues(const Vec3f& u, float angle) {
  float c = std::cos(angle), s = std::sin(angle);
  Mat3f r;
  r.m[0] = {c + u.x * u.x * (1 - c), u.x * u.y * (1 - c) - u.z * s, u.x * u.z * (1 - c) + u.y * s};
  r.m[1] = {u.y * u.x * (1 - c) + u.z * s, c + u.y * u.y * (1 - c), u.y * u.z * (1 - c) - u.x * s};
  r.m[2] = {u.z * u.x * (1 - c) - u.y * s, u.z * u.y * (1 - c) + u.x * s, c + u.z * u.z * (1 - c)};
  return r;
}

Quatf quatOf(const Vec3f& u, float angle) {
  return {std::cos(angle / 2), u.x * std::sin(angle / 2), u.y * std::sin(angle / 2), u.z * std::sin(angle / 2)};
}

TEST(GaussianSelection, OrientedBoxBoundary) {
  Shape box;
  box.kind = Shape::Kind::Box;
  box.center = {0.5f, -1.0f, 2.0f};
  box.halfExtent = {1.0f, 0.3f, 0.6f};
  box.rotation = quatOf(kAxis, kAngle);
  Mat3f r = rodrigues(kAxis, kAngle);
  expectBoundary(box, r,
                 {{1.0f, 0, 0}, {-1.0f, 0, 0}, {0, 0.3f, 0}, {0, -0.3f, 0}, {0, 0, 0.6f}, {0, 0, -0.6f},
                  {1.0f, 0.3f, 0.6f}, {-1.0f, 0.3f, -0.6f}});
  // Along the world x axis the box reaches further than 1.0 only because it is rotated: a point
  // inside the axis-aligned box but outside the rotated one is not selected.
  Vec3f corner = box.center + Vec3f(0.99f, 0.29f, 0.59f);
  Vec3f local = r.transposeTimes(corner - box.center);
  bool insideRotated = std::abs(local.x) <= 1.0f && std::abs(local.y) <= 0.3f && std::abs(local.z) <= 0.6f;
  EXPECT_FALSE(insideRotated);
  EXPECT_EQ(select(shapeSelection(box), sceneAt({corner}))[0], 0);
}

TEST(GaussianSelection, SphereBoundary) {
  Shape sphere;
  sphere.kind = Shape::Kind::Sphere;
  sphere.center = {1.0f, 2.0f, 3.0f};
  sphere.radius = 0.75f;
  Mat3f identity;
  std::vector<Vec3f> directions = {{0.75f, 0, 0}, {0, -0.75f, 0}, {0, 0, 0.75f}};
  Rng rng(7);
  for (int k = 0; k < 20; ++k) {
    Vec3f d = normalize(Vec3f(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f));
    directions.push_back(d * 0.75f);
  }
  expectBoundary(sphere, identity, directions);
}

TEST(GaussianSelection, EllipticCylinderBoundary) {
  Shape cylinder;
  cylinder.kind = Shape::Kind::Cylinder;
  cylinder.center = {-0.5f, 0.25f, 1.0f};
  cylinder.radii = {0.4f, 0.9f};
  cylinder.halfHeight = 0.5f;
  cylinder.rotation = quatOf(kAxis, kAngle);
  Mat3f r = rodrigues(kAxis, kAngle);
  std::vector<Vec3f> boundary = {{0, 0.5f, 0}, {0, -0.5f, 0}};  // caps
  for (int k = 0; k < 12; ++k) {  // the elliptic side at several heights
    float phi = 2 * std::numbers::pi_v<float> * k / 12;
    boundary.push_back({0.4f * std::cos(phi), 0.0f, 0.9f * std::sin(phi)});
  }
  expectBoundary(cylinder, r, boundary);
  // Inside the side but above the cap: outside.
  EXPECT_EQ(select(shapeSelection(cylinder), sceneAt({cylinder.center + r * Vec3f(0.1f, 0.55f, 0.1f)}))[0], 0);
}

TEST(GaussianSelection, LargeScenesMatchTheDefinitionInParallel) {
  // 200,000 random means: every chunk of the parallel loop must agree with |p - c| <= r.
  Rng rng(3);
  std::vector<Vec3f> points(200000);
  for (Vec3f& p : points) p = {rng.uniform() * 2 - 1, rng.uniform() * 2 - 1, rng.uniform() * 2 - 1};
  Shape sphere;
  sphere.kind = Shape::Kind::Sphere;
  sphere.radius = 0.5f;
  GaussianMask mask = select(shapeSelection(sphere), sceneAt(points));
  size_t expected = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    bool inside = dot(points[i], points[i]) <= 0.25f;
    expected += inside;
    ASSERT_EQ(mask[i], inside) << i;
  }
  EXPECT_EQ(countSelected(mask), expected);
  EXPECT_NEAR(double(expected) / points.size(), 4.0 / 3.0 * std::numbers::pi * 0.125 / 8.0, 0.01);  // sphere / cube volume
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// A chrome ball of radius 0.3 resting on a rough floor: a box that stops 1 cm above the
// floor leaves the ball's contact cap behind; growing along similar material takes the cap
// and never the floor, even where the two touch.
TEST(GaussianSelection, GrowthTakesTheContactCapAndStopsAtTheFloor) {
  GaussianScene scene;
  const Vec3f centre(0, 0, 0.3f);
  // The ball's surface (Fibonacci sphere, about 4 cm between neighbours).
  const int ballCount = 700;
  for (int k = 0; k < ballCount; ++k) {
    float z = 1.0f - 2.0f * (float(k) + 0.5f) / float(ballCount), r = std::sqrt(1.0f - z * z);
    float phi = float(k) * 2.399963f;
    size_t i = scene.size();
    scene.resize(i + 1);
    scene.position[i] = centre + Vec3f(r * std::cos(phi), r * std::sin(phi), z) * 0.3f;
    scene.f0[i] = Rgb(0.9f);
    scene.roughness[i] = 0.05f;
  }
  // The floor, every 2 cm, touching the ball's lowest point.
  for (int x = -30; x <= 30; ++x)
    for (int y = -30; y <= 30; ++y) {
      size_t i = scene.size();
      scene.resize(i + 1);
      scene.position[i] = Vec3f(0.02f * float(x), 0.02f * float(y), 0.0f);
      scene.diffuse[i] = Rgb(0.5f);
      scene.roughness[i] = 0.9f;
    }
  Shape box;
  box.center = Vec3f(0, 0, 0.36f);
  box.halfExtent = Vec3f(0.4f, 0.4f, 0.35f);  // from z = 0.01 up
  Selection selection = shapeSelection(box);
  GaussianMask plain = select(selection, scene);
  int capLeft = 0;
  for (int i = 0; i < ballCount; ++i) capLeft += !plain[i];
  ASSERT_GT(capLeft, 0) << "the box should leave a cap behind";

  selection.grow = {0.06f, 0.1f};
  GaussianMask grown = select(selection, scene);
  for (size_t i = 0; i < scene.size(); ++i) {
    if (int(i) < ballCount) EXPECT_TRUE(grown[i]) << "ball Gaussian " << i << " at z " << scene.position[i].z;
    else EXPECT_FALSE(grown[i]) << "floor Gaussian " << i;
  }
  // A distance shorter than the spacing of the ball's Gaussians grows nothing.
  selection.grow = {0.005f, 0.1f};
  EXPECT_EQ(select(selection, scene), plain);
}

}  // namespace
}  // namespace glint
