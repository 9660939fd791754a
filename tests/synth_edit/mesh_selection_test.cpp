// Mesh selections: shapes pick whole nodes by the centre of their bounds, filters test the
// material factors, and combinations are set operations on nodes.
#include "synth_edit/mesh_selection.h"

#include <gtest/gtest.h>

#include "synth_edit/mesh_scene_fixture.h"

namespace glint {
namespace {

using test::boxSelection;
using test::combination;
using test::everything;
using test::tinyMeshScene;

NodeMask select(const Selection& selection, const MeshScene& scene) {
  EditDocument doc;
  doc.selections["s"] = selection;
  return selectNodes(doc, "s", scene);
}

TEST(MeshSelection, NodesAreMeshesThenSpheresWithTheirBoundsCentres) {
  MeshScene scene = tinyMeshScene();
  ASSERT_EQ(nodeCount(scene), 4u);
  EXPECT_FALSE(isSphereNode(scene, 0));
  EXPECT_TRUE(isSphereNode(scene, 1));
  EXPECT_EQ(nodeCenter(scene, 0), Vec3f(0.5f, 0.5f, 0.0f));
  EXPECT_EQ(nodeCenter(scene, 2), Vec3f(4, 0, 0));
  EXPECT_EQ(nodeMaterial(scene, 0), 0);
  EXPECT_EQ(nodeMaterial(scene, 3), 2);
}

TEST(MeshSelection, ABoxPicksWholeNodesByTheCentreOfTheirBounds) {
  MeshScene scene = tinyMeshScene();
  // Around the triangle's bounds centre only: none of its vertices is inside, yet it is picked.
  EXPECT_EQ(select(boxSelection({0.5f, 0.5f, 0}, Vec3f(0.1f)), scene), (NodeMask{1, 0, 0, 0}));
  // Around a vertex but not the centre: not picked.
  EXPECT_EQ(select(boxSelection({0, 0, 0}, Vec3f(0.2f)), scene), (NodeMask{0, 0, 0, 0}));
  // Most of sphere B (r 1 at x = 4) but not its centre: not picked; a box reaching the centre picks it.
  EXPECT_EQ(select(boxSelection({4.6f, 0, 0}, Vec3f(0.5f)), scene), (NodeMask{0, 0, 0, 0}));
  EXPECT_EQ(select(boxSelection({4.5f, 0, 0}, Vec3f(0.5f)), scene), (NodeMask{0, 0, 1, 0}));
  // A box over the x axis from 1 to 5 holds spheres A and B.
  EXPECT_EQ(select(boxSelection({3, 0, 0}, {2, 0.5f, 0.5f}), scene), (NodeMask{0, 1, 1, 0}));
}

TEST(MeshSelection, FiltersTestTheMaterialFactors) {
  MeshScene scene = tinyMeshScene();
  // roughness: chrome 0.05 only.
  EXPECT_EQ(select(everything({{Attribute::Roughness, 0.0f, 0.1f}}), scene), (NodeMask{0, 1, 0, 0}));
  // metalness: both metals (no diffuse) are 1, the paint (F0 0.04) is 0.
  EXPECT_EQ(select(everything({{Attribute::Metalness, 0.9f, 1.0f}}), scene), (NodeMask{0, 1, 0, 1}));
  EXPECT_EQ(select(everything({{Attribute::Metalness, 0.0f, 0.1f}}), scene), (NodeMask{1, 0, 1, 0}));
  // mean diffuse: paint 0.4, metals 0.
  EXPECT_EQ(select(everything({{Attribute::Diffuse, 0.3f, 0.5f}}), scene), (NodeMask{1, 0, 1, 0}));
  // mean F0: chrome 2/3, gold 0.703, paint 0.04.
  EXPECT_EQ(select(everything({{Attribute::F0, 0.68f, 1.0f}}), scene), (NodeMask{0, 0, 0, 1}));
  EXPECT_EQ(select(everything({{Attribute::F0, 0.03f, 0.05f}}), scene), (NodeMask{1, 0, 1, 0}));
  // Every filter must hold: metals with roughness above 0.1 = gold.
  EXPECT_EQ(select(everything({{Attribute::Metalness, 0.9f, 1.0f}, {Attribute::Roughness, 0.1f, 1.0f}}), scene),
            (NodeMask{0, 0, 0, 1}));
  // Filters on a shape: the x-axis box minus the non-metals.
  EXPECT_EQ(select(boxSelection({3, 0, 0}, {2, 0.5f, 0.5f}, {{Attribute::Metalness, 0.5f, 1.0f}}), scene),
            (NodeMask{0, 1, 0, 0}));
}

TEST(MeshSelection, TexturesAreIgnoredByFilters) {
  MeshScene scene = tinyMeshScene();
  // A black base-colour texture would make the paint's diffuse 0 where sampled; filters see factors.
  Texture black;
  black.image = Image(1, 1, 3);
  scene.textures.push_back(black);
  scene.materials[0].baseColorTexture = 0;
  EXPECT_EQ(select(everything({{Attribute::Diffuse, 0.3f, 0.5f}}), scene), (NodeMask{1, 0, 1, 0}));
}

TEST(MeshSelection, CombinationsAreSetOperationsOnNodes) {
  MeshScene scene = tinyMeshScene();
  EditDocument doc;
  doc.selections["axis"] = boxSelection({3, 0, 0}, {2, 0.5f, 0.5f});            // A, B
  doc.selections["metal"] = everything({{Attribute::Metalness, 0.9f, 1.0f}});  // A, C
  doc.selections["all"] = everything();
  doc.selections["union"] = combination(Selection::Kind::Union, {"axis", "metal"});
  doc.selections["both"] = combination(Selection::Kind::Intersection, {"axis", "metal"});
  doc.selections["rest"] = combination(Selection::Kind::Difference, {"all", "axis", "metal"});
  EXPECT_EQ(selectNodes(doc, "union", scene), (NodeMask{0, 1, 1, 1}));
  EXPECT_EQ(selectNodes(doc, "both", scene), (NodeMask{0, 1, 0, 0}));
  EXPECT_EQ(selectNodes(doc, "rest", scene), (NodeMask{1, 0, 0, 0}));
}

}  // namespace
}  // namespace glint
