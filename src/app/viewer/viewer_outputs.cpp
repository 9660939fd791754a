// Checks of the file names the viewer writes.
#include "app/viewer/viewer_outputs.h"

#include <algorithm>
#include <cctype>

#include "app/viewer/request_json.h"

namespace glint {

namespace {

// What train (scene, config, log, checkpoint/), eval (eval/metrics.json), report
// (report.html) and dataset folders (point cloud, cameras) write: see src/app/*_command.cpp.
constexpr const char* kRunFileNames[] = {"scene.ply", "config.json",  "log.csv",     "checkpoint",
                                         "state.bin", "eval",         "metrics.json", "report.html",
                                         "point_cloud_dense.ply"};

}  // namespace

bool isRunFileName(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (const char* runName : kRunFileNames)
    if (lower == runName) return true;
  return lower.rfind("transforms", 0) == 0;  // transforms.json, transforms_train.json, ...
}

std::filesystem::path viewerOutputFile(const std::filesystem::path& folder, const nlohmann::json& request,
                                       const char* defaultName, const char* extension) {
  requireOnlyFields(request, {"name"});
  std::string name = request.contains("name") ? readString(request, "name", 100) : defaultName;
  bool plain = !name.empty() && name[0] != '.' &&
               name.find_first_not_of("abcdefghijklmnopqrstuvwxyz"
                                      "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.") == std::string::npos;
  std::string ext = extension;
  if (!plain || name.size() <= ext.size() || name.compare(name.size() - ext.size(), ext.size(), ext) != 0)
    throw RequestError(400, "\"name\" must be a plain file name ending in " + ext);
  if (isRunFileName(name))
    throw RequestError(403, "\"" + name + "\" is the name of a run's file; choose another name");
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error || !std::filesystem::is_directory(folder))
    throw RequestError(403, "cannot create the viewer's folder " + folder.string());
  // A symbolic link or folder of that name is not one of the viewer's files.
  std::filesystem::path file = folder / name;
  std::filesystem::file_status status = std::filesystem::symlink_status(file, error);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw RequestError(403, file.string() + " exists and is not a regular file; choose another name");
  return file;
}

}  // namespace glint
