// Reading a JSON file with one error that names the file when it is not valid JSON.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

namespace glint {

// The parsed contents of `path`. Throws Error(path, "not found" / "is not valid JSON: ...").
nlohmann::json readJsonFile(const std::filesystem::path& path);

}  // namespace glint
