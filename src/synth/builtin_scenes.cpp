// The built-in scenes. All are closed rooms lit by a ceiling area light, Y up, metres.
#include "synth/builtin_scenes.h"

#include <cmath>

#include "core/error.h"
#include "math/sampling.h"
#include "synth/mesh_builder.h"
#include "synth/procedural_textures.h"

namespace glint {

namespace {

int addMaterial(MeshScene& scene, const std::string& name, Rgb baseColor, float metallic, float roughness) {
  Material m;
  m.name = name;
  m.baseColor = baseColor;
  m.metallic = metallic;
  m.roughness = roughness;
  scene.materials.push_back(m);
  return int(scene.materials.size()) - 1;
}

int addEmitter(MeshScene& scene, const std::string& name, Rgb radiance) {
  int id = addMaterial(scene, name, Rgb(0.0f), 0.0f, 1.0f);
  scene.materials[id].emission = radiance;
  scene.materials[id].specularLevel = 0.0f;
  return id;
}

// Six inward-facing quads of an axis-aligned room [lo, hi]; materials per face.
struct RoomMaterials {
  int floor, ceiling, left, right, back, front;
};

void addRoom(MeshScene& scene, const Vec3f& lo, const Vec3f& hi, const RoomMaterials& m, float floorUvScale) {
  Vec3f d = hi - lo;
  scene.meshes.push_back(makeQuad("floor", {lo.x, lo.y, hi.z}, {d.x, 0, 0}, {0, 0, -d.z}, m.floor, floorUvScale));
  scene.meshes.push_back(makeQuad("ceiling", {lo.x, hi.y, lo.z}, {d.x, 0, 0}, {0, 0, d.z}, m.ceiling));
  scene.meshes.push_back(makeQuad("wall_left", {lo.x, lo.y, hi.z}, {0, 0, -d.z}, {0, d.y, 0}, m.left));
  scene.meshes.push_back(makeQuad("wall_right", {hi.x, lo.y, lo.z}, {0, 0, d.z}, {0, d.y, 0}, m.right));
  scene.meshes.push_back(makeQuad("wall_back", {lo.x, lo.y, lo.z}, {d.x, 0, 0}, {0, d.y, 0}, m.back));
  scene.meshes.push_back(makeQuad("wall_front", {hi.x, lo.y, hi.z}, {-d.x, 0, 0}, {0, d.y, 0}, m.front));
}

// A downward-facing square area light centred at (x, y, z).
void addCeilingLight(MeshScene& scene, const Vec3f& centre, float size, Rgb radiance) {
  int light = addEmitter(scene, "area_light", radiance);
  float h = 0.5f * size;
  scene.meshes.push_back(makeQuad("area_light", centre + Vec3f(-h, 0, -h), {size, 0, 0}, {0, 0, size}, light));
}

// Three tinted chrome spheres and a rough gold one on a checker floor, in a room with
// coloured walls (the paper's "tinted chrome spheres" setting, appendix C.1).
MeshScene makeSpheres() {
  MeshScene scene;
  scene.textures.push_back(makeCheckerTexture("checker", Rgb(0.8f, 0.8f, 0.75f), Rgb(0.12f, 0.12f, 0.14f), 2, 16));
  int floor = addMaterial(scene, "checker_floor", Rgb(1.0f), 0.0f, 0.5f);
  scene.materials[floor].baseColorTexture = 0;
  RoomMaterials room;
  room.floor = floor;
  room.ceiling = addMaterial(scene, "ceiling", Rgb(0.8f), 0.0f, 0.9f);
  room.left = addMaterial(scene, "wall_red", Rgb(0.65f, 0.12f, 0.1f), 0.0f, 0.9f);
  room.right = addMaterial(scene, "wall_green", Rgb(0.15f, 0.5f, 0.18f), 0.0f, 0.9f);
  room.back = addMaterial(scene, "wall_blue", Rgb(0.2f, 0.3f, 0.65f), 0.0f, 0.9f);
  room.front = addMaterial(scene, "wall_cream", Rgb(0.7f, 0.62f, 0.45f), 0.0f, 0.9f);
  addRoom(scene, {-4, 0, -4}, {4, 4, 4}, room, 8.0f);  // 2 squares per uv unit: 0.5 m tiles
  // A large, moderately bright light keeps the caustics of the chrome spheres soft enough
  // for a few hundred samples per pixel.
  addCeilingLight(scene, {0, 3.99f, 0}, 2.4f, Rgb(11.0f, 10.0f, 8.7f));

  int chromeRed = addMaterial(scene, "chrome_red", Rgb(0.95f, 0.55f, 0.5f), 1.0f, 0.03f);
  int chromeGreen = addMaterial(scene, "chrome_green", Rgb(0.55f, 0.92f, 0.6f), 1.0f, 0.03f);
  int chromeBlue = addMaterial(scene, "chrome_blue", Rgb(0.55f, 0.65f, 0.95f), 1.0f, 0.03f);
  int gold = addMaterial(scene, "rough_gold", Rgb(1.0f, 0.77f, 0.34f), 1.0f, 0.35f);
  scene.spheres.push_back({{-1.3f, 0.6f, 0.3f}, 0.6f, chromeRed});
  scene.spheres.push_back({{0.0f, 0.6f, -0.9f}, 0.6f, chromeGreen});
  scene.spheres.push_back({{1.3f, 0.6f, 0.3f}, 0.6f, chromeBlue});
  scene.spheres.push_back({{0.0f, 0.45f, 1.0f}, 0.45f, gold});

  scene.hasCameraRig = true;
  scene.cameras.fovX = 60.0f * kPi / 180.0f;
  scene.cameras.train = {{0, 0, 0}, {0, 0.5f, 0}, 3.0f, 1.0f, 2.4f, 0.0f, 1.0f, 3.0f};
  scene.cameras.test = {{0, 0, 0}, {0, 0.5f, 0}, 2.6f, 1.5f, 1.9f, 0.41f, 1.0f, 1.0f};
  return scene;
}

// A room with a mirror on the back wall, a glossy table carrying a metallic pot, coloured
// diffuse objects, and a chequered box behind the training cameras: they see it only in
// the mirror, while test cameras circle the room and see it directly.
MeshScene makeRoom() {
  MeshScene scene;
  scene.textures.push_back(makeCheckerTexture("hidden_checker", Rgb(0.9f, 0.75f, 0.1f), Rgb(0.6f, 0.05f, 0.3f), 4, 8));
  scene.textures.push_back(makeCheckerTexture("floor_tiles", Rgb(0.55f, 0.42f, 0.3f), Rgb(0.45f, 0.33f, 0.22f), 2, 8));
  int floor = addMaterial(scene, "floor", Rgb(1.0f), 0.0f, 0.45f);
  scene.materials[floor].baseColorTexture = 1;
  RoomMaterials room;
  room.floor = floor;
  room.ceiling = addMaterial(scene, "ceiling", Rgb(0.85f), 0.0f, 0.9f);
  room.left = addMaterial(scene, "wall_sage", Rgb(0.35f, 0.5f, 0.35f), 0.0f, 0.9f);
  room.right = addMaterial(scene, "wall_sand", Rgb(0.7f, 0.6f, 0.4f), 0.0f, 0.9f);
  room.back = addMaterial(scene, "wall_grey", Rgb(0.55f), 0.0f, 0.9f);
  room.front = addMaterial(scene, "wall_blue", Rgb(0.25f, 0.35f, 0.6f), 0.0f, 0.9f);
  addRoom(scene, {-3, 0, -3}, {3, 3, 3}, room, 6.0f);
  addCeilingLight(scene, {0, 2.99f, 0.3f}, 2.0f, Rgb(9.5f, 8.8f, 7.7f));

  int mirror = addMaterial(scene, "mirror", Rgb(0.95f), 1.0f, 0.0f);
  scene.meshes.push_back(makeQuad("mirror", {-1.5f, 0.5f, -2.98f}, {3.0f, 0, 0}, {0, 2.0f, 0}, mirror));
  int frame = addMaterial(scene, "mirror_frame", Rgb(0.1f, 0.08f, 0.06f), 0.0f, 0.6f);
  scene.meshes.push_back(makeBox("mirror_frame", {-1.6f, 0.4f, -3.0f}, {1.6f, 2.6f, -2.99f}, frame));

  int wood = addMaterial(scene, "glossy_table", Rgb(0.35f, 0.18f, 0.08f), 0.0f, 0.15f);
  TriangleMesh table = makeBox("table", {-0.8f, 0.7f, -0.5f}, {0.8f, 0.76f, 0.5f}, wood);
  for (float x : {-0.72f, 0.66f})
    for (float z : {-0.42f, 0.36f}) appendMesh(table, makeBox("", {x, 0, z}, {x + 0.06f, 0.7f, z + 0.06f}, wood));
  scene.meshes.push_back(table);

  int copper = addMaterial(scene, "copper_pot", Rgb(0.95f, 0.64f, 0.54f), 1.0f, 0.2f);
  scene.meshes.push_back(makeCylinder("pot", {0.35f, 0.76f, 0.0f}, 0.18f, 0.24f, 48, copper));
  scene.spheres.push_back({{0.35f, 1.0f, 0.0f}, 0.12f, copper});  // the pot's lid

  int orange = addMaterial(scene, "orange_box", Rgb(0.85f, 0.35f, 0.05f), 0.0f, 0.7f);
  scene.meshes.push_back(makeBox("orange_box", {-0.55f, 0.76f, -0.15f}, {-0.25f, 1.0f, 0.15f}, orange));
  int purple = addMaterial(scene, "purple_ball", Rgb(0.4f, 0.12f, 0.55f), 0.0f, 0.6f);
  scene.spheres.push_back({{1.6f, 0.35f, -1.6f}, 0.35f, purple});
  int teal = addMaterial(scene, "teal_column", Rgb(0.05f, 0.45f, 0.45f), 0.0f, 0.8f);
  scene.meshes.push_back(makeCylinder("teal_column", {-1.9f, 0.0f, -1.4f}, 0.25f, 1.2f, 48, teal));

  int hidden = addMaterial(scene, "hidden_box", Rgb(1.0f), 0.0f, 0.8f);
  scene.materials[hidden].baseColorTexture = 0;
  scene.meshes.push_back(makeBox("hidden_box", {-0.45f, 0.9f, 2.45f}, {0.45f, 1.7f, 2.75f}, hidden));

  scene.hasCameraRig = true;
  scene.cameras.fovX = 60.0f * kPi / 180.0f;
  // Training cameras: a quarter arc on the +z side, all looking at the mirror, so the
  // hidden box (behind them) appears only in its reflection.
  scene.cameras.train = {{0, 0, 0}, {0, 1.2f, -3.0f}, 1.8f, 1.0f, 1.6f, 0.25f * kPi, 0.25f, 2.0f};
  // Test cameras: a full circle looking at the room's centre; those on the -z side see the
  // hidden box directly. Heights keep them above the column and the ball they pass over.
  scene.cameras.test = {{0, 0, 0}, {0, 0.9f, 0}, 2.0f, 1.35f, 1.75f, 0.1f, 1.0f, 1.0f};
  return scene;
}


// Adds a material whose base colour is a dead-leaves texture of its own (seeded by the
// texture's index, so every surface differs and nothing repeats across the room).
int addTexturedMaterial(MeshScene& scene, const std::string& name, int textureSize, float roughness) {
  scene.textures.push_back(makeDeadLeavesTexture(name, textureSize, uint64_t(scene.textures.size()) + 1, 0.08f,
                                                 0.75f, 16.0f));
  int id = addMaterial(scene, name, Rgb(1.0f), 0.0f, roughness);
  scene.materials[id].baseColorTexture = int(scene.textures.size()) - 1;
  return id;
}

// A room for structure from motion: walls, floor and pedestals carry dead-leaves textures
// (detail at every scale, never repeating, so SIFT finds thousands of distinct features
// and matches them unambiguously), around the reflective objects the method is about: a
// chrome sphere, a rough metal cylinder, a glossy dielectric sphere and a flat mirror.
MeshScene makeGallery() {
  MeshScene scene;
  RoomMaterials room;
  // 1024 texels over 8 m: 8 mm texels, disc radii from 12.5 cm (about 10 pixels at 320x240
  // from 3 m; finer detail only aliases into noise that SIFT takes for features) to 1 m.
  room.floor = addTexturedMaterial(scene, "floor_leaves", 1024, 0.6f);
  room.ceiling = addTexturedMaterial(scene, "ceiling_leaves", 512, 0.9f);
  room.left = addTexturedMaterial(scene, "wall_left_leaves", 1024, 0.85f);
  room.right = addTexturedMaterial(scene, "wall_right_leaves", 1024, 0.85f);
  room.back = addTexturedMaterial(scene, "wall_back_leaves", 1024, 0.85f);
  room.front = addTexturedMaterial(scene, "wall_front_leaves", 1024, 0.85f);
  addRoom(scene, {-4, 0, -4}, {4, 3.5f, 4}, room, 1.0f);
  addCeilingLight(scene, {-1.4f, 3.49f, 0.0f}, 1.6f, Rgb(12.0f, 11.2f, 9.8f));
  addCeilingLight(scene, {1.4f, 3.49f, 0.0f}, 1.6f, Rgb(12.0f, 11.2f, 9.8f));

  // The flat mirror hangs on the back wall in a dark frame.
  int mirror = addMaterial(scene, "mirror", Rgb(0.95f), 1.0f, 0.0f);
  scene.meshes.push_back(makeQuad("mirror", {-1.0f, 0.7f, -3.98f}, {2.0f, 0, 0}, {0, 1.6f, 0}, mirror));
  int frame = addMaterial(scene, "mirror_frame", Rgb(0.08f, 0.06f, 0.05f), 0.0f, 0.5f);
  scene.meshes.push_back(makeBox("mirror_frame", {-1.1f, 0.6f, -4.0f}, {1.1f, 2.4f, -3.99f}, frame));

  int chrome = addMaterial(scene, "chrome", Rgb(0.95f, 0.95f, 0.95f), 1.0f, 0.02f);
  scene.spheres.push_back({{-1.1f, 0.55f, -0.5f}, 0.55f, chrome});
  int roughMetal = addMaterial(scene, "brushed_aluminium", Rgb(0.91f, 0.92f, 0.92f), 1.0f, 0.3f);
  scene.meshes.push_back(makeCylinder("rough_metal_cylinder", {1.1f, 0.0f, -0.6f}, 0.35f, 1.0f, 64, roughMetal));
  int glossy = addMaterial(scene, "glossy_red_plastic", Rgb(0.7f, 0.08f, 0.06f), 0.0f, 0.08f);
  scene.spheres.push_back({{0.2f, 0.85f, 0.9f}, 0.4f, glossy});
  // The glossy sphere sits on a textured pedestal, which also gives the matcher features
  // in the middle of the room.
  int pedestal = addTexturedMaterial(scene, "pedestal_leaves", 256, 0.7f);
  scene.meshes.push_back(makeBox("pedestal", {-0.15f, 0.0f, 0.55f}, {0.55f, 0.45f, 1.25f}, pedestal));

  scene.hasCameraRig = true;
  scene.cameras.fovX = 60.0f * kPi / 180.0f;
  // Training cameras circle inside the room looking at its middle, rising and falling three
  // times: neighbouring views overlap strongly even at 12 views (30 degrees apart).
  scene.cameras.train = {{0, 0, 0}, {0, 0.8f, 0}, 2.7f, 1.1f, 2.0f, 0.0f, 1.0f, 3.0f};
  scene.cameras.test = {{0, 0, 0}, {0, 0.8f, 0}, 2.3f, 1.4f, 1.7f, 0.3f, 1.0f, 1.0f};
  return scene;
}

}  // namespace

std::vector<std::string> builtinSceneNames() { return {"spheres", "room", "gallery"}; }

MeshScene makeBuiltinScene(const std::string& name) {
  if (name == "spheres") return makeSpheres();
  if (name == "room") return makeRoom();
  if (name == "gallery") return makeGallery();
  std::string list;
  for (const std::string& n : builtinSceneNames()) list += (list.empty() ? "builtin:" : ", builtin:") + n;
  throw Error("builtin:" + name, "unknown built-in scene (available: " + list + ")");
}

}  // namespace glint
