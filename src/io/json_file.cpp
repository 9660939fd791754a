// Reading a JSON file with one error that names the file.
#include "io/json_file.h"

#include <string>

#include "core/atomic_file.h"
#include "core/error.h"

namespace glint {

nlohmann::json readJsonFile(const std::filesystem::path& path) {
  std::string text = readTextFile(path);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(path.string(), std::string("is not valid JSON: ") + e.what());
  }
}

}  // namespace glint
