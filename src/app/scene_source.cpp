// Loading a Gaussian scene from a .ply file or a training run folder (scene.ply + config.json).
#include "app/scene_source.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string>

#include "core/activity.h"
#include "core/error.h"
#include "train/run_folder.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

bool hasPlyExtension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".ply";
}

// Reads the scene file and tells the user what a 3DGS import assumed.
void readScene(const fs::path& file, PlyLayout layout, SceneSource& source) {
  source.sceneFile = file;
  source.scene = readGaussianPly(file, layout, &source.import);
  std::string description = describeImport(source.import);
  if (!description.empty()) std::fprintf(stderr, "glint: %s: %s\n", file.string().c_str(), description.c_str());
  std::string warning = droppedShWarning(source.import, file.string());
  if (!warning.empty()) std::fprintf(stderr, "glint: %s\n", warning.c_str());
}

}  // namespace

SceneSource loadSceneSource(const fs::path& p, PlyLayout layout) {
  ActivityScope activity("reading the scene " + p.string());
  SceneSource source;
  if (fs::is_directory(p)) {
    const RunFolder run(p);
    if (!fs::is_regular_file(run.sceneFile())) throw Error(p.string(), "is not a training run: no scene.ply");
    // The settings first: a bad config.json is refused before a large scene is read.
    if (run.hasConfig()) source.settings = run.readConfig();
    readScene(run.sceneFile(), layout, source);
    return source;
  }
  if (!fs::exists(p))
    throw Error(p.string(), "does not exist (expected a Gaussian scene .ply or a training run folder)");
  if (!hasPlyExtension(p)) throw Error(p.string(), "is neither a Gaussian scene .ply nor a training run folder");
  readScene(p, layout, source);
  return source;
}

void addInputLayoutFlag(CLI::App& command, std::string& layout) {
  command
      .add_option("--input-layout", layout,
                  "How to read the scene .ply: auto (Glint's header or material properties mean glint, "
                  "anything else 3dgs; a Glint header over 3DGS properties is refused), glint (f_dc is linear "
                  "diffuse colour) or 3dgs (f_dc is the SH DC of a display-referred colour; missing materials "
                  "become a rough dielectric)")
      ->check(CLI::IsMember({"auto", "glint", "3dgs"}))
      ->capture_default_str();
}

PlyLayout parseInputLayout(const std::string& name) {
  if (name == "glint") return PlyLayout::Glint;
  if (name == "3dgs") return PlyLayout::ThreeDgs;
  GLINT_CHECK(name == "auto", "unchecked --input-layout '" + name + "'");
  return PlyLayout::Auto;
}

}  // namespace glint
