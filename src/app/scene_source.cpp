// Loading a Gaussian scene from a .ply file or a training run folder (scene.ply + config.json).
#include "app/scene_source.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "core/activity.h"
#include "core/error.h"
#include "scene/gaussian_ply.h"
#include "train/run_folder.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

bool hasPlyExtension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".ply";
}

}  // namespace

SceneSource loadSceneSource(const fs::path& p) {
  ActivityScope activity("reading the scene " + p.string());
  SceneSource source;
  if (fs::is_directory(p)) {
    const RunFolder run(p);
    if (!fs::is_regular_file(run.sceneFile())) throw Error(p.string(), "is not a training run: no scene.ply");
    // The settings first: a bad config.json is refused before a large scene is read.
    if (run.hasConfig()) source.settings = run.readConfig();
    source.scene = readGaussianPly(run.sceneFile());
    return source;
  }
  if (!fs::exists(p))
    throw Error(p.string(), "does not exist (expected a Gaussian scene .ply or a training run folder)");
  if (!hasPlyExtension(p)) throw Error(p.string(), "is neither a Gaussian scene .ply nor a training run folder");
  source.scene = readGaussianPly(p);
  return source;
}

}  // namespace glint
