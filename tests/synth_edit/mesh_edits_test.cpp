// Edits of ground-truth mesh scenes: each operation gives exactly the expected vertices,
// normals, sphere centres and radii and material factors; shared materials are split; the
// surface the path tracer sees after an F0 or diffuse edit has the requested colours.
#include "synth_edit/mesh_edits.h"

#include <gtest/gtest.h>

#include "edit/hsv.h"
#include "synth_edit/mesh_scene_fixture.h"

namespace glint {
namespace {

using test::boxSelection;
using test::everything;
using test::tinyMeshScene;

constexpr float kTol = 1e-6f;

void expectVec(const Vec3f& a, const Vec3f& b, float tol = kTol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// Selections of the tiny scene: "triangle" (by its bounds centre), "b" (sphere B),
// "axis" (spheres A and B), "all".
EditDocument documentWith(std::vector<Operation> operations) {
  EditDocument doc;
  doc.selections["triangle"] = boxSelection({0.5f, 0.5f, 0}, Vec3f(0.1f));
  doc.selections["b"] = boxSelection({4, 0, 0}, Vec3f(0.5f));
  doc.selections["axis"] = boxSelection({3, 0, 0}, {2, 0.5f, 0.5f});
  doc.selections["all"] = everything();
  doc.operations = std::move(operations);
  return doc;
}

Operation op(Operation::Kind kind, const std::string& selection) {
  Operation o;
  o.kind = kind;
  o.selection = selection;
  return o;
}

TEST(MeshEdits, TranslateMovesVerticesAndSphereCentresOnly) {
  MeshScene scene = tinyMeshScene();
  Operation move = op(Operation::Kind::Translate, "triangle");
  move.offset = {1, 2, 3};
  Operation moveB = op(Operation::Kind::Translate, "b");
  moveB.offset = {0, 0, -1};
  MeshEditReport report = applyMeshEdits(documentWith({move, moveB}), scene);
  expectVec(scene.meshes[0].positions[0], {1, 2, 3});
  expectVec(scene.meshes[0].positions[1], {2, 2, 3});
  expectVec(scene.meshes[0].positions[2], {1, 3, 3});
  expectVec(scene.meshes[0].normals[0], {0, 0, 1});
  expectVec(scene.spheres[1].center, {4, 0, -1});
  EXPECT_EQ(scene.spheres[1].radius, 1.0f);
  expectVec(scene.spheres[0].center, {2, 0, 0});
  ASSERT_EQ(report.operations.size(), 2u);
  EXPECT_EQ(report.operations[0].selected, 1u);
  EXPECT_TRUE(report.warnings.empty());
}

TEST(MeshEdits, RotateTurnsVerticesNormalsAndCentresAboutThePivot) {
  MeshScene scene = tinyMeshScene();
  // 90 degrees about +y through the origin: (x, y, z) -> (z, y, -x).
  Operation turn = op(Operation::Kind::Rotate, "triangle");
  turn.axis = {0, 1, 0};
  turn.angleDegrees = 90.0f;
  turn.hasPivot = true;
  turn.pivot = {0, 0, 0};
  // Sphere B about the default pivot, the centre of its selection's box (4, 0, 0): it stays.
  Operation turnB = op(Operation::Kind::Rotate, "b");
  turnB.axis = {0, 0, 1};
  turnB.angleDegrees = 45.0f;
  // Both axis spheres about (3, 0, 0), 180 degrees about +y: A (2,0,0) -> (4,0,0), B -> (2,0,0).
  Operation swap = op(Operation::Kind::Rotate, "axis");
  swap.axis = {0, 1, 0};
  swap.angleDegrees = 180.0f;
  applyMeshEdits(documentWith({turn, turnB, swap}), scene);
  expectVec(scene.meshes[0].positions[0], {0, 0, 0});
  expectVec(scene.meshes[0].positions[1], {0, 0, -1});
  expectVec(scene.meshes[0].positions[2], {0, 1, 0});
  for (const Vec3f& n : scene.meshes[0].normals) expectVec(n, {1, 0, 0});
  expectVec(scene.spheres[0].center, {4, 0, 0}, 1e-5f);
  expectVec(scene.spheres[1].center, {2, 0, 0}, 1e-5f);
  EXPECT_EQ(scene.spheres[0].radius, 0.5f);
  expectVec(scene.spheres[2].center, {0, 3, 0});
}

TEST(MeshEdits, ScaleScalesPositionsAndRadiiAboutThePivotAndKeepsNormals) {
  MeshScene scene = tinyMeshScene();
  Operation grow = op(Operation::Kind::Scale, "axis");  // pivot (3, 0, 0)
  grow.factor = 2.0f;
  Operation shrink = op(Operation::Kind::Scale, "triangle");
  shrink.factor = 0.5f;
  shrink.hasPivot = true;
  shrink.pivot = {1, 1, 0};
  applyMeshEdits(documentWith({grow, shrink}), scene);
  expectVec(scene.spheres[0].center, {1, 0, 0});
  EXPECT_EQ(scene.spheres[0].radius, 1.0f);
  expectVec(scene.spheres[1].center, {5, 0, 0});
  EXPECT_EQ(scene.spheres[1].radius, 2.0f);
  EXPECT_EQ(scene.spheres[2].radius, 0.25f);
  expectVec(scene.meshes[0].positions[0], {0.5f, 0.5f, 0});
  expectVec(scene.meshes[0].positions[1], {1, 0.5f, 0});
  expectVec(scene.meshes[0].positions[2], {0.5f, 1, 0});
  expectVec(scene.meshes[0].normals[2], {0, 0, 1});
}

TEST(MeshEdits, DuplicateAppendsMovedCopiesAndDeleteRemovesExactlyTheSelection) {
  MeshScene scene = tinyMeshScene();
  Operation copy = op(Operation::Kind::Duplicate, "all");
  copy.offset = {0, 0, 10};
  MeshEditReport report = applyMeshEdits(documentWith({copy}), scene);
  EXPECT_EQ(report.nodesBefore, 4u);
  EXPECT_EQ(report.nodesAfter, 8u);
  ASSERT_EQ(scene.meshes.size(), 2u);
  ASSERT_EQ(scene.spheres.size(), 6u);
  expectVec(scene.meshes[1].positions[1], {1, 0, 10});
  expectVec(scene.meshes[1].normals[1], {0, 0, 1});
  EXPECT_EQ(scene.meshes[1].material, 0);
  expectVec(scene.meshes[0].positions[1], {1, 0, 0});
  for (size_t i = 0; i < 3; ++i) {
    expectVec(scene.spheres[3 + i].center, scene.spheres[i].center + Vec3f(0, 0, 10));
    EXPECT_EQ(scene.spheres[3 + i].radius, scene.spheres[i].radius);
    EXPECT_EQ(scene.spheres[3 + i].material, scene.spheres[i].material);
  }
  EXPECT_EQ(report.materialsAfter, 3u);  // copies share their originals' materials

  // Deleting the copies (everything above z = 5) restores the original scene.
  EditDocument removeCopies = documentWith({op(Operation::Kind::Delete, "copies")});
  removeCopies.selections["copies"] = boxSelection({0, 0, 10}, Vec3f(9));
  applyMeshEdits(removeCopies, scene);
  MeshScene original = tinyMeshScene();
  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_EQ(scene.spheres.size(), 3u);
  EXPECT_EQ(scene.meshes[0].positions, original.meshes[0].positions);
  for (size_t i = 0; i < 3; ++i) EXPECT_EQ(scene.spheres[i].center, original.spheres[i].center);

  // Deleting sphere B keeps the others in order.
  applyMeshEdits(documentWith({op(Operation::Kind::Delete, "b")}), scene);
  ASSERT_EQ(scene.spheres.size(), 2u);
  expectVec(scene.spheres[0].center, {2, 0, 0});
  expectVec(scene.spheres[1].center, {0, 3, 0});
  EXPECT_EQ(scene.meshes.size(), 1u);
}

TEST(MeshEdits, MaterialEditsSplitSharedMaterialsOncePerOperation) {
  MeshScene scene = tinyMeshScene();
  // Sphere B shares "paint" with the triangle: it gets its own copy, the triangle keeps 0.6.
  Operation smooth = op(Operation::Kind::Roughness, "b");
  smooth.roughnessMode = Operation::RoughnessMode::Set;
  smooth.amount = 0.05f;
  MeshEditReport report = applyMeshEdits(documentWith({smooth}), scene);
  EXPECT_EQ(report.materialsBefore, 3u);
  EXPECT_EQ(report.materialsAfter, 4u);
  EXPECT_EQ(scene.spheres[1].material, 3);
  EXPECT_EQ(scene.meshes[0].material, 0);
  EXPECT_FLOAT_EQ(scene.materials[3].roughness, 0.05f);
  EXPECT_FLOAT_EQ(scene.materials[0].roughness, 0.6f);
  EXPECT_EQ(scene.materials[3].baseColor, scene.materials[0].baseColor);

  // Two nodes sharing one material, both selected: no copy, and the change applies once.
  MeshScene shared = tinyMeshScene();
  shared.spheres[0].material = 0;  // A and B and the triangle all use "paint"
  EditDocument doc = documentWith({});
  doc.selections["paint"] = everything({{Attribute::Roughness, 0.5f, 0.7f}});
  Operation halve = op(Operation::Kind::Roughness, "paint");
  halve.roughnessMode = Operation::RoughnessMode::Multiply;
  halve.amount = 0.5f;
  Operation shift = op(Operation::Kind::Roughness, "axis");  // A and B, not the triangle
  shift.roughnessMode = Operation::RoughnessMode::Shift;
  shift.amount = 0.9f;
  doc.operations = {halve, shift};
  MeshEditReport sharedReport = applyMeshEdits(doc, shared);
  EXPECT_EQ(sharedReport.operations[0].selected, 3u);
  EXPECT_EQ(sharedReport.materialsAfter, 4u);  // only the shift split "paint", once for A and B
  EXPECT_FLOAT_EQ(shared.materials[0].roughness, 0.3f);
  EXPECT_EQ(shared.spheres[0].material, 3);
  EXPECT_EQ(shared.spheres[1].material, 3);
  EXPECT_FLOAT_EQ(shared.materials[3].roughness, 1.0f);  // 0.3 + 0.9 clamped
}

TEST(MeshEdits, F0AndDiffuseEditsGiveTheRequestedSurfaceColours) {
  MeshScene scene = tinyMeshScene();
  const Rgb gold(0.95f, 0.64f, 0.54f), red(0.7f, 0.1f, 0.1f);
  Operation f0 = op(Operation::Kind::F0, "all");
  f0.color.value = gold;
  Operation diffuse = op(Operation::Kind::Diffuse, "all");
  diffuse.color.value = red;
  diffuse.color.blend = 0.5f;
  std::vector<SurfaceMaterial> before;
  for (const Material& m : scene.materials) before.push_back(materialFactors(m));
  applyMeshEdits(documentWith({f0, diffuse}), scene);
  for (size_t i = 0; i < nodeCount(scene); ++i) {
    int m = nodeMaterial(scene, i);
    SurfaceMaterial seen = scene.surfaceMaterial(m, {0.5f, 0.5f});  // what the path tracer sees
    expectVec(seen.F0, gold, 1e-5f);
    expectVec(seen.diffuse, lerp(before[m].diffuse, red, 0.5f), 1e-5f);
    EXPECT_FLOAT_EQ(seen.roughness, before[m].roughness);
  }
  // The metals had no diffuse: half of red makes them dielectrics with F0 kept; the
  // dielectric stays one.
  EXPECT_EQ(scene.materials[1].metallic, 0.0f);
  EXPECT_EQ(scene.materials[0].metallic, 0.0f);
}

TEST(MeshEdits, AnF0EditOnAMetalChangesItsBaseColourAndKeepsItMetal) {
  MeshScene scene = tinyMeshScene();
  Operation hue = op(Operation::Kind::F0, "axis");  // chrome A and paint B
  hue.color.mode = ColorChange::Mode::HsvShift;
  hue.color.value = {120, 0, 0};
  SurfaceMaterial chromeBefore = materialFactors(scene.materials[1]);
  SurfaceMaterial paintBefore = materialFactors(scene.materials[0]);
  applyMeshEdits(documentWith({hue}), scene);
  const Material& chrome = scene.materials[scene.spheres[0].material];
  EXPECT_EQ(chrome.metallic, 1.0f);
  expectVec(chrome.baseColor, hsvToRgb(rgbToHsv(chromeBefore.F0) + Vec3f(120, 0, 0)), 1e-5f);
  // The grey dielectric F0 has no hue to shift: B's F0 and diffuse are unchanged.
  SurfaceMaterial paint = materialFactors(scene.materials[scene.spheres[1].material]);
  expectVec(paint.F0, paintBefore.F0, 1e-6f);
  expectVec(paint.diffuse, paintBefore.diffuse, 1e-6f);
}

TEST(MeshEdits, ADiffuseHsvMultiplyOnADielectricKeepsItsF0) {
  MeshScene scene = tinyMeshScene();
  Operation darker = op(Operation::Kind::Diffuse, "triangle");
  darker.color.mode = ColorChange::Mode::HsvMultiply;
  darker.color.value = {1, 0.5f, 1.2f};
  applyMeshEdits(documentWith({darker}), scene);
  SurfaceMaterial triangle = materialFactors(scene.materials[scene.meshes[0].material]);
  expectVec(triangle.diffuse, hsvToRgb(rgbToHsv({0.2f, 0.4f, 0.6f}) * Vec3f(1, 0.5f, 1.2f)), 1e-6f);
  expectVec(triangle.F0, Rgb(0.04f), 1e-6f);
  // Sphere B still has the original paint.
  EXPECT_EQ(scene.materials[scene.spheres[1].material].baseColor, Rgb(0.2f, 0.4f, 0.6f));
}

TEST(MeshEdits, OperationsComposeInOrderAndEmptySelectionsAreWarnings) {
  MeshScene scene = tinyMeshScene();
  Operation copy = op(Operation::Kind::Duplicate, "b");
  copy.offset = {0, 5, 0};
  // The selection is evaluated after the duplicate: the box around (4, 5, 0) holds the copy.
  EditDocument doc = documentWith({copy});
  doc.selections["copy"] = boxSelection({4, 5, 0}, Vec3f(0.5f));
  doc.selections["nothing"] = boxSelection({-50, 0, 0}, Vec3f(1));
  Operation move = op(Operation::Kind::Translate, "copy");
  move.offset = {1, 0, 0};
  doc.operations.push_back(move);
  doc.operations.push_back(op(Operation::Kind::Delete, "nothing"));
  MeshEditReport report = applyMeshEdits(doc, scene);
  ASSERT_EQ(scene.spheres.size(), 4u);
  expectVec(scene.spheres[3].center, {5, 5, 0});
  expectVec(scene.spheres[1].center, {4, 0, 0});
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("operations[2] delete \"nothing\""), std::string::npos) << report.warnings[0];
  std::string text = formatMeshEditReport(report);
  EXPECT_NE(text.find("operations[1] translate \"copy\": 1 node"), std::string::npos) << text;
  EXPECT_NE(text.find("nodes (meshes and spheres): 4 -> 5"), std::string::npos) << text;
}

}  // namespace
}  // namespace glint
