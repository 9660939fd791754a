// Scenes defined in code, needing no files: `builtin:spheres`, `builtin:room` and `builtin:gallery`.
#pragma once

#include <string>
#include <vector>

#include "synth/mesh_scene.h"

namespace glint {

// Names accepted after "builtin:".
std::vector<std::string> builtinSceneNames();
// Throws Error listing the valid names for an unknown one.
MeshScene makeBuiltinScene(const std::string& name);

}  // namespace glint
