// Where the viewer's "save edits" and "export PLY" may write. They write only into the
// viewer's own folder (RUN/viewer/, or viewer/ beside an opened .ply), which no other
// command writes, so no request can replace the run's scene, config, log, checkpoint,
// report or evaluation; names the run uses are refused there too, so that the viewer's
// folder never looks like a run (glint view/render take a folder with scene.ply and
// config.json for one).
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

namespace glint {

// The name of the viewer's folder inside the folder of what it opened.
constexpr const char* kViewerFolderName = "viewer";

// The file a save or export request {"name": ...} names: a plain file name with the given
// extension (defaultName when absent) inside folder, which is created. Throws RequestError
// 400 for a malformed name and 403 for a name a run owns or a path that is not a regular file.
std::filesystem::path viewerOutputFile(const std::filesystem::path& folder, const nlohmann::json& request,
                                       const char* defaultName, const char* extension);

// True for the names `glint train`, `eval`, `report` and datasets give their files.
bool isRunFileName(const std::string& name);

}  // namespace glint
