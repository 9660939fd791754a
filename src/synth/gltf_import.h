// Imports glTF 2.0 scenes (.gltf with external or embedded buffers, and .glb) into the
// generator's MeshScene.
#pragma once

#include <filesystem>

#include "synth/mesh_scene.h"

namespace glint {

// Loads the default scene of a glTF 2.0 file (scene 0 when none is marked default, or every
// root node when the file has no scenes) with all node transforms baked into world space:
// one TriangleMesh per triangle-list primitive, metallic-roughness materials (plus
// KHR_materials_specular, KHR_materials_ior and KHR_materials_emissive_strength), their
// textures decoded to linear floats, and KHR_lights_punctual lights. Cameras in the file
// are ignored (the generator makes its own camera paths). Features Glint cannot render
// (transparency, normal maps, texture transforms, non-triangle primitives, ...) are
// skipped with one warning each on stderr. Throws Error naming the file for a missing or
// malformed file, an extension it requires that Glint does not support, or data that
// points outside its buffers.
MeshScene loadGltfScene(const std::filesystem::path& path);

}  // namespace glint
