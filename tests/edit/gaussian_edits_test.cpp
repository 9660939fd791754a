// Edits of Gaussian scenes: each operation on a tiny scene gives exactly the expected means,
// quaternions, normals and attributes; operations compose in order; duplicating a selection
// and deleting the copies restores the original render bit for bit.
#include "edit/gaussian_edits.h"
#include "edit/edit_file.h"

#include <gtest/gtest.h>

#include <cmath>

#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_layers.h"
#include "render/gaussian_renderer.h"

namespace glint {
namespace {

constexpr float kTol = 1e-6f;

void expectVec(const Vec3f& a, const Vec3f& b, float tol = kTol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

void expectQuat(const Quatf& a, const Quatf& b) {
  EXPECT_NEAR(a.w, b.w, kTol);
  EXPECT_NEAR(a.x, b.x, kTol);
  EXPECT_NEAR(a.y, b.y, kTol);
  EXPECT_NEAR(a.z, b.z, kTol);
}

// Three Gaussians: A at (2, 0, 0) rotated 90 degrees about x, B at (1, 0, 0), C far away at
// (0, 5, 0); only A and B lie in the sphere "near" (centre (1, 0, 0), radius 1.5).
GaussianScene tinyScene() {
  GaussianScene s;
  s.resize(3);
  float h = std::sqrt(0.5f);
  s.position = {{2, 0, 0}, {1, 0, 0}, {0, 5, 0}};
  s.rotation = {{h, h, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}};
  s.logScale = {{-2, -3, -4}, {-1, -1, -1}, {0, 0, 0}};
  s.opacityLogit = {0.5f, 1.0f, 2.0f};
  s.normal = {{1, 0, 0}, {0, 0, 0}, {0, 1, 0}};
  s.diffuse = {{1, 0, 0}, {0.2f, 0.4f, 0.6f}, {2, 2, 2}};
  s.roughness = {0.5f, 0.1f, 0.9f};
  s.f0 = {{0.04f, 0.04f, 0.04f}, {0.9f, 0.6f, 0.5f}, {0.5f, 0.5f, 0.5f}};
  return s;
}

Selection sphereSelection(const Vec3f& centre, float radius) {
  Selection s;
  s.kind = Selection::Kind::Shape;
  s.shape.kind = Shape::Kind::Sphere;
  s.shape.center = centre;
  s.shape.radius = radius;
  return s;
}

EditDocument documentWith(std::vector<Operation> operations) {
  EditDocument doc;
  doc.selections["near"] = sphereSelection({1, 0, 0}, 1.5f);
  Selection all;
  all.kind = Selection::Kind::Everything;
  doc.selections["all"] = all;
  doc.operations = std::move(operations);
  return doc;
}

Operation op(Operation::Kind kind, const std::string& selection = "near") {
  Operation o;
  o.kind = kind;
  o.selection = selection;
  return o;
}

// C, outside "near", must be untouched by every operation on "near".
void expectFarGaussianUntouched(const GaussianScene& s) {
  GaussianScene original = tinyScene();
  ASSERT_GE(s.size(), 3u);
  EXPECT_EQ(s.position[2], original.position[2]);
  EXPECT_EQ(s.normal[2], original.normal[2]);
  EXPECT_EQ(s.roughness[2], original.roughness[2]);
  EXPECT_EQ(s.f0[2], original.f0[2]);
  EXPECT_EQ(s.diffuse[2], original.diffuse[2]);
}

TEST(GaussianEdits, TranslateMovesSelectedMeans) {
  Operation translate = op(Operation::Kind::Translate);
  translate.offset = {0.5f, -1, 2};
  GaussianScene s = tinyScene();
  EditReport report = applyEdits(documentWith({translate}), s);
  EXPECT_EQ(s.position[0], Vec3f(2.5f, -1, 2));
  EXPECT_EQ(s.position[1], Vec3f(1.5f, -1, 2));
  expectFarGaussianUntouched(s);
  expectQuat(s.rotation[0], tinyScene().rotation[0]);
  ASSERT_EQ(report.operations.size(), 1u);
  EXPECT_EQ(report.operations[0].selected, 2u);
  EXPECT_FALSE(report.countChanged());
  EXPECT_TRUE(report.warnings.empty());
}

TEST(GaussianEdits, RotateTurnsMeansOrientationsAndNormalsAboutThePivot) {
  // 90 degrees about +z around the sphere's centre (1, 0, 0), the default pivot.
  Operation rotate = op(Operation::Kind::Rotate);
  rotate.axis = {0, 0, 3};  // any length
  rotate.angleDegrees = 90;
  GaussianScene s = tinyScene();
  applyEdits(documentWith({rotate}), s);
  expectVec(s.position[0], {1, 1, 0});
  expectVec(s.position[1], {1, 0, 0});
  // A was 90 degrees about x; then 90 degrees about z: together 120 degrees about (1, 1, 1),
  // the quaternion (1/2, 1/2, 1/2, 1/2) (x -> y -> z -> x).
  expectQuat(s.rotation[0], {0.5f, 0.5f, 0.5f, 0.5f});
  float h = std::sqrt(0.5f);
  expectQuat(s.rotation[1], {h, 0, 0, h});
  expectVec(s.normal[0], {0, 1, 0});
  EXPECT_EQ(s.normal[1], Vec3f(0.0f));  // no normal stays none
  EXPECT_EQ(s.logScale[0], Vec3f(-2, -3, -4));
  expectFarGaussianUntouched(s);

  // An explicit pivot: 180 degrees about y through the origin.
  Operation flip = op(Operation::Kind::Rotate, "all");
  flip.axis = {0, 1, 0};
  flip.angleDegrees = 180;
  flip.hasPivot = true;
  flip.pivot = {0, 0, 0};
  s = tinyScene();
  applyEdits(documentWith({flip}), s);
  expectVec(s.position[0], {-2, 0, 0});
  expectVec(s.position[2], {0, 5, 0});
  expectVec(s.normal[2], {0, 1, 0});
  expectVec(s.normal[0], {-1, 0, 0});
}

TEST(GaussianEdits, ScaleMovesMeansFromThePivotAndGrowsSizes) {
  Operation scale = op(Operation::Kind::Scale);
  scale.factor = 2;
  scale.hasPivot = true;
  scale.pivot = {0, 0, 1};
  GaussianScene s = tinyScene();
  applyEdits(documentWith({scale}), s);
  expectVec(s.position[0], {4, 0, -1});
  expectVec(s.position[1], {2, 0, -1});
  expectVec(s.logScale[0], Vec3f(-2, -3, -4) + Vec3f(std::log(2.0f)));
  expectVec(s.scale(1), Vec3f(2 * std::exp(-1.0f)), 1e-6f);
  expectQuat(s.rotation[0], tinyScene().rotation[0]);
  EXPECT_EQ(s.logScale[2], Vec3f(0.0f));
  expectFarGaussianUntouched(s);
}

TEST(GaussianEdits, DuplicateAppendsMovedCopiesAndDeleteRemovesInOrder) {
  Operation duplicate = op(Operation::Kind::Duplicate);
  duplicate.offset = {0, 0, 10};
  GaussianScene s = tinyScene();
  EditReport report = applyEdits(documentWith({duplicate}), s);
  ASSERT_EQ(s.size(), 5u);
  EXPECT_TRUE(s.consistent());
  EXPECT_TRUE(report.countChanged());
  EXPECT_EQ(report.countAfter, 5u);
  GaussianScene original = tinyScene();
  for (size_t copy = 3, from = 0; copy < 5; ++copy, ++from) {
    EXPECT_EQ(s.position[copy], original.position[from] + Vec3f(0, 0, 10));
    expectQuat(s.rotation[copy], original.rotation[from]);
    EXPECT_EQ(s.logScale[copy], original.logScale[from]);
    EXPECT_EQ(s.opacityLogit[copy], original.opacityLogit[from]);
    EXPECT_EQ(s.normal[copy], original.normal[from]);
    EXPECT_EQ(s.diffuse[copy], original.diffuse[from]);
    EXPECT_EQ(s.roughness[copy], original.roughness[from]);
    EXPECT_EQ(s.f0[copy], original.f0[from]);
  }
  // Then delete "near": it holds A and B (the copies at z = 10 are outside it), so C and
  // both copies remain, in order.
  s = tinyScene();
  report = applyEdits(documentWith({duplicate, op(Operation::Kind::Delete)}), s);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s.position[0], Vec3f(0, 5, 0));
  EXPECT_EQ(s.position[1], Vec3f(2, 0, 10));
  EXPECT_EQ(s.position[2], Vec3f(1, 0, 10));
  EXPECT_EQ(s.opacityLogit[1], 0.5f);
  EXPECT_EQ(report.operations[1].selected, 2u);
  EXPECT_FALSE(report.countChanged());  // 3 -> 5 -> 3
}

TEST(GaussianEdits, RoughnessSetShiftMultiplyClampToTheUnitInterval) {
  auto roughness = [](Operation::RoughnessMode mode, float amount) {
    Operation o = op(Operation::Kind::Roughness);
    o.roughnessMode = mode;
    o.amount = amount;
    return o;
  };
  GaussianScene s = tinyScene();
  applyEdits(documentWith({roughness(Operation::RoughnessMode::Set, 0.05f)}), s);
  EXPECT_EQ(s.roughness, (std::vector<float>{0.05f, 0.05f, 0.9f}));
  s = tinyScene();
  applyEdits(documentWith({roughness(Operation::RoughnessMode::Shift, 0.55f)}), s);
  EXPECT_EQ(s.roughness[0], 1.0f);  // 1.05 clamped
  EXPECT_NEAR(s.roughness[1], 0.65f, kTol);
  s = tinyScene();
  applyEdits(documentWith({roughness(Operation::RoughnessMode::Shift, -0.3f)}), s);
  EXPECT_NEAR(s.roughness[0], 0.2f, kTol);
  EXPECT_EQ(s.roughness[1], 0.0f);  // -0.2 clamped
  s = tinyScene();
  applyEdits(documentWith({roughness(Operation::RoughnessMode::Multiply, 3.0f)}), s);
  EXPECT_EQ(s.roughness[0], 1.0f);
  EXPECT_NEAR(s.roughness[1], 0.3f, kTol);
  expectFarGaussianUntouched(s);
}

Operation colorOp(Operation::Kind kind, ColorChange::Mode mode, Vec3f value, float blend = 1) {
  Operation o = op(kind);
  o.color = {mode, value, blend};
  return o;
}

TEST(GaussianEdits, F0SetBlendsAndHsvChangesClampToTheUnitInterval) {
  GaussianScene s = tinyScene();
  // A quarter of the way from (0.04, 0.04, 0.04) / (0.9, 0.6, 0.5) to gold.
  applyEdits(documentWith({colorOp(Operation::Kind::F0, ColorChange::Mode::Set, {1.0f, 0.8f, 0.3f}, 0.25f)}), s);
  expectVec(s.f0[0], {0.04f * 0.75f + 0.25f, 0.04f * 0.75f + 0.2f, 0.04f * 0.75f + 0.075f});
  expectVec(s.f0[1], {0.9f * 0.75f + 0.25f, 0.6f * 0.75f + 0.2f, 0.5f * 0.75f + 0.075f});
  expectFarGaussianUntouched(s);
  // Value x 2: B's (0.9, 0.6, 0.5) becomes (1.8, 1.2, 1.0), clamped to 1 per channel.
  s = tinyScene();
  applyEdits(documentWith({colorOp(Operation::Kind::F0, ColorChange::Mode::HsvMultiply, {1, 1, 2})}), s);
  expectVec(s.f0[1], {1.0f, 1.0f, 1.0f});
  expectVec(s.f0[0], {0.08f, 0.08f, 0.08f});
}

TEST(GaussianEdits, DiffuseHsvShiftTurnsHueAndMultiplyDesaturates) {
  GaussianScene s = tinyScene();
  applyEdits(documentWith({colorOp(Operation::Kind::Diffuse, ColorChange::Mode::HsvShift, {120, 0, 0})}), s);
  expectVec(s.diffuse[0], {0, 1, 0});  // red -> green
  // (0.2, 0.4, 0.6): hue 210 -> 330 (between magenta and red): (0.6, 0.2, 0.4).
  expectVec(s.diffuse[1], {0.6f, 0.2f, 0.4f});
  expectFarGaussianUntouched(s);

  s = tinyScene();
  applyEdits(documentWith({colorOp(Operation::Kind::Diffuse, ColorChange::Mode::HsvMultiply, {1, 0, 1.5f}, 1),
                           colorOp(Operation::Kind::Diffuse, ColorChange::Mode::Set, {0, 0, 1}, 0.5f)}),
             s);
  // Saturation 0 leaves grey at the value (max channel) x 1.5, then half blue; diffuse is
  // not clamped above 1 (it holds irradiance times albedo).
  expectVec(s.diffuse[0], {0.75f, 0.75f, 1.25f});
  expectVec(s.diffuse[1], {0.45f, 0.45f, 0.95f});
}

TEST(GaussianEdits, OperationsComposeInOrder) {
  // Move A and B away by 10 along z, then select "near" again: it is empty now, so the
  // roughness change touches nothing and is reported as a warning.
  Operation translate = op(Operation::Kind::Translate);
  translate.offset = {0, 0, 10};
  Operation roughness = op(Operation::Kind::Roughness);
  roughness.amount = 0.0f;
  GaussianScene s = tinyScene();
  EditReport report = applyEdits(documentWith({translate, roughness}), s);
  EXPECT_EQ(s.roughness, tinyScene().roughness);
  ASSERT_EQ(report.operations.size(), 2u);
  EXPECT_EQ(report.operations[1].selected, 0u);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("operations[1] roughness \"near\""), std::string::npos);
  EXPECT_NE(formatEditReport(report).find("warning:"), std::string::npos);
  // The other order changes A and B's roughness before moving them.
  s = tinyScene();
  report = applyEdits(documentWith({roughness, translate}), s);
  EXPECT_EQ(s.roughness, (std::vector<float>{0.0f, 0.0f, 0.9f}));
  EXPECT_TRUE(report.warnings.empty());
  // Rotate then translate differs from translate then rotate (about the sphere's centre).
  Operation rotate = op(Operation::Kind::Rotate);
  rotate.axis = {0, 0, 1};
  rotate.angleDegrees = 90;
  rotate.hasPivot = true;
  rotate.pivot = {1, 0, 0};
  translate.offset = {1, 0, 0};
  s = tinyScene();
  applyEdits(documentWith({rotate, translate}), s);
  expectVec(s.position[0], {2, 1, 0});
  s = tinyScene();
  applyEdits(documentWith({translate, rotate}), s);  // A at (3, 0, 0) is outside "near" now
  expectVec(s.position[0], {3, 0, 0});
  expectVec(s.position[1], {1, 1, 0});
}

// A small reflective scene: a mirror floor of flat Gaussians and a red blob above it.
GaussianScene reflectiveScene() {
  GaussianScene s;
  test::addLayer(&s, 0.0f, 0.0f, 0.0f, 10, 10, 0.2f, {Rgb(0.0f), Vec3f(0, 0, 1), 0.05f, Rgb(0.9f)});
  for (int k = 0; k < 20; ++k) {
    size_t n = s.size();
    s.resize(n + 1);
    s.position[n] = {0.05f * float(k % 5) - 0.1f, 0.05f * float(k / 5) - 0.1f, 0.4f + 0.02f * float(k % 3)};
    s.logScale[n] = Vec3f(std::log(0.06f));
    s.opacityLogit[n] = logit(0.9f);
    s.diffuse[n] = {0.9f, 0.1f, 0.1f};
    s.normal[n] = normalize(Vec3f(0.1f * float(k % 4), 0.2f, 1.0f));
    s.roughness[n] = 0.3f;
    s.f0[n] = Rgb(0.04f);
  }
  return s;
}

ViewBuffers renderScene(const GaussianScene& scene) {
  auto tracer = makeGaussianTracer("fast");
  tracer->build(scene, TraceSettings{});
  Camera camera;
  camera.cameraToWorld = Mat4::lookAt(Vec3d(0, -2.0, 1.5), Vec3d(0, 0, 0.2), Vec3d(0, 0, 1));
  camera.width = 48;
  camera.height = 36;
  camera = Camera::fromFieldOfView(camera.cameraToWorld, 0.9, camera.width, camera.height);
  RenderSettings settings;
  settings.spp = 4;
  settings.seed = 5;
  settings.path.bounces = 1;
  return renderGaussianView(*tracer, camera, settings, 0);
}

TEST(GaussianEdits, DuplicateThenDeleteTheCopiesRestoresTheRenderBitForBit) {
  GaussianScene original = reflectiveScene();
  EditDocument doc;
  Selection blob;
  blob.kind = Selection::Kind::Shape;
  blob.shape.kind = Shape::Kind::Box;
  blob.shape.center = {0, 0, 0.45f};
  blob.shape.halfExtent = {0.3f, 0.3f, 0.2f};
  doc.selections["blob"] = blob;
  Selection copies = blob;
  copies.shape.center = {0.5f, 0.3f, 0.45f};
  doc.selections["copies"] = copies;
  Operation duplicate = op(Operation::Kind::Duplicate, "blob");
  duplicate.offset = {0.5f, 0.3f, 0};
  doc.operations = {duplicate};

  GaussianScene duplicated = original;
  EditReport report = applyEdits(doc, duplicated);
  ASSERT_EQ(report.operations[0].selected, 20u);
  ASSERT_EQ(duplicated.size(), original.size() + 20);

  GaussianScene restored = duplicated;
  doc.operations = {op(Operation::Kind::Delete, "copies")};
  report = applyEdits(doc, restored);
  ASSERT_EQ(report.operations[0].selected, 20u);  // exactly the copies, not the floor
  ASSERT_EQ(restored.size(), original.size());

  ViewBuffers before = renderScene(original);
  ViewBuffers withCopy = renderScene(duplicated);
  ViewBuffers after = renderScene(restored);
  // The copy shows (directly and in the mirror), so the comparison below is not vacuous...
  EXPECT_NE(withCopy[Buffer::Render].pixels, before[Buffer::Render].pixels);
  EXPECT_NE(withCopy[Buffer::Specular].pixels, before[Buffer::Specular].pixels);
  // ...and deleting it gives back every buffer exactly.
  for (Buffer b : kAllBuffers) EXPECT_EQ(after[b].pixels, before[b].pixels) << bufferName(b);
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// Provenance: which Gaussians an edit moved, added or removed, through a sequence of
// operations on the tiny scene (A and B in "near", C far away).
TEST(EditProvenance, RecordsMovedAddedAndRemovedGaussians) {
  // Material edits move nothing.
  GaussianScene scene = tinyScene();
  EditProvenance p = EditProvenance::identity(scene.size());
  applyEdits(documentWith({op(Operation::Kind::Roughness)}), scene, kDefaultMaxGaussians, &p);
  EXPECT_EQ(p.unmoved(), (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_TRUE(p.movedOrAdded().empty());
  EXPECT_TRUE(p.movedOrRemoved().empty());

  // Translate "near" (A, B) by 5 m, duplicate everything 10 m up (A', B', C'), then delete
  // the original C (sphere "far" around it; its copy is out of reach).
  scene = tinyScene();
  p = EditProvenance::identity(scene.size());
  Operation move = op(Operation::Kind::Translate);
  move.offset = {5, 0, 0};
  Operation copy = op(Operation::Kind::Duplicate, "all");
  copy.offset = {0, 0, 10};
  EditDocument doc = documentWith({move, copy, op(Operation::Kind::Delete, "far")});
  doc.selections["far"] = sphereSelection({0, 5, 0}, 0.5f);
  applyEdits(doc, scene, kDefaultMaxGaussians, &p);
  // After: A, B (moved), A', B', C' (copies); C deleted.
  ASSERT_EQ(scene.size(), 5u);
  EXPECT_EQ(p.source, (std::vector<uint32_t>{0, 1, 0, 1, 2}));
  EXPECT_TRUE(p.unmoved().empty());
  EXPECT_EQ(p.movedOrAdded(), (std::vector<uint32_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(p.movedOrRemoved(), (std::vector<uint32_t>{0, 1, 2}));  // A, B moved; C removed

  // Duplicating alone keeps the originals in place: only the copies changed the scene.
  scene = tinyScene();
  p = EditProvenance::identity(scene.size());
  applyEdits(documentWith({op(Operation::Kind::Duplicate)}), scene, kDefaultMaxGaussians, &p);
  EXPECT_EQ(p.unmoved(), (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(p.movedOrAdded(), (std::vector<uint32_t>{3, 4}));
  EXPECT_TRUE(p.movedOrRemoved().empty());
}

// A translation by zero, a rotation by no angle and a scaling by one leave the scene bit for
// bit as it was and move nothing, so relighting has nothing to trace; a translation by a
// hair still moves.
TEST(EditProvenance, AnOperationThatMovesNothingMovesNothing) {
  Operation still = op(Operation::Kind::Translate);
  Operation unturned = op(Operation::Kind::Rotate);
  unturned.axis = {0, 0, 1};
  unturned.angleDegrees = 0;
  unturned.hasPivot = true;
  unturned.pivot = {0.3f, -0.7f, 0.1f};  // (p - pivot) + pivot would round
  Operation unscaled = op(Operation::Kind::Scale);
  unscaled.factor = 1;
  unscaled.hasPivot = true;
  unscaled.pivot = {0.3f, -0.7f, 0.1f};
  for (const Operation& o : {still, unturned, unscaled}) {
    GaussianScene scene = tinyScene();
    const GaussianScene unedited = scene;
    EditProvenance p = EditProvenance::identity(scene.size());
    applyEdits(documentWith({o}), scene, kDefaultMaxGaussians, &p);
    EXPECT_TRUE(p.movedOrAdded().empty()) << operationName(o.kind);
    EXPECT_TRUE(p.movedOrRemoved().empty()) << operationName(o.kind);
    for (size_t i = 0; i < scene.size(); ++i) {
      EXPECT_EQ(scene.position[i], unedited.position[i]) << i;
      EXPECT_EQ(scene.logScale[i], unedited.logScale[i]) << i;
      EXPECT_EQ(scene.normal[i], unedited.normal[i]) << i;
    }
  }
  GaussianScene scene = tinyScene();
  EditProvenance p = EditProvenance::identity(scene.size());
  Operation hair = op(Operation::Kind::Translate);
  hair.offset = {0, 1e-6f, 0};
  applyEdits(documentWith({hair}), scene, kDefaultMaxGaussians, &p);
  EXPECT_FALSE(p.movedOrAdded().empty());
}

}  // namespace
}  // namespace glint
