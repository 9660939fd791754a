// The built-in scenes are valid and deterministic; the gallery has what COLMAP and the
// method need (texture everywhere, each kind of reflector, inside-the-room cameras).
#include "synth/builtin_scenes.h"

#include <gtest/gtest.h>

#include "synth/camera_paths.h"

namespace glint {
namespace {

TEST(BuiltinScenes, EveryNamedSceneValidates) {
  for (const std::string& name : builtinSceneNames()) {
    MeshScene scene = makeBuiltinScene(name);
    EXPECT_NO_THROW(scene.validate("builtin:" + name)) << name;
  }
}

TEST(BuiltinScenes, GalleryIsDeterministic) {
  MeshScene a = makeBuiltinScene("gallery"), b = makeBuiltinScene("gallery");
  ASSERT_EQ(a.textures.size(), b.textures.size());
  for (size_t t = 0; t < a.textures.size(); ++t) EXPECT_EQ(a.textures[t].image.pixels, b.textures[t].image.pixels);
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t m = 0; m < a.meshes.size(); ++m) EXPECT_EQ(a.meshes[m].positions.size(), b.meshes[m].positions.size());
}

TEST(BuiltinScenes, GalleryTexturesEverySurfaceDifferentlyAndHasEachReflector) {
  MeshScene scene = makeBuiltinScene("gallery");
  // The six room faces each have a texture of their own: nothing repeats across the room.
  int textured = 0;
  for (const TriangleMesh& mesh : scene.meshes)
    if (mesh.name.rfind("wall", 0) == 0 || mesh.name == "floor" || mesh.name == "ceiling") {
      EXPECT_GE(scene.materials[mesh.material].baseColorTexture, 0) << mesh.name;
      ++textured;
    }
  EXPECT_EQ(textured, 6);
  for (size_t i = 0; i < scene.textures.size(); ++i)
    for (size_t j = i + 1; j < scene.textures.size(); ++j)
      if (scene.textures[i].image.width == scene.textures[j].image.width) {
        EXPECT_NE(scene.textures[i].image.pixels, scene.textures[j].image.pixels);
      }
  bool mirror = false, chrome = false, roughMetal = false, glossyDielectric = false;
  for (const Material& m : scene.materials) {
    mirror |= m.name == "mirror" && m.metallic == 1 && m.roughness == 0;
    chrome |= m.metallic == 1 && m.roughness > 0 && m.roughness < 0.05f;
    roughMetal |= m.metallic == 1 && m.roughness >= 0.2f;
    glossyDielectric |= m.metallic == 0 && m.roughness < 0.15f && m.baseColorTexture < 0;
  }
  EXPECT_TRUE(mirror && chrome && roughMetal && glossyDielectric);
}

TEST(BuiltinScenes, GalleryCamerasStayInsideTheRoom) {
  MeshScene scene = makeBuiltinScene("gallery");
  Vec3f lower, upper;
  scene.bounds(&lower, &upper);
  for (const Mat4& pose : orbitCameras(scene.cameras.train, 120)) {
    Vec3d p = pose.column(3);
    EXPECT_GT(p.x, lower.x + 0.5);
    EXPECT_LT(p.x, upper.x - 0.5);
    EXPECT_GT(p.y, lower.y + 0.5);
    EXPECT_LT(p.y, upper.y - 0.5);
    EXPECT_GT(p.z, lower.z + 0.5);
    EXPECT_LT(p.z, upper.z - 0.5);
  }
}

}  // namespace
}  // namespace glint
