// Reading a JSON file with one error that names the file.
#include "io/json_file.h"

#include <string>

#include "core/input_file.h"
#include "core/error.h"
#include "core/printable_text.h"

namespace glint {

nlohmann::json readJsonFile(const std::filesystem::path& path) {
  std::string text = readInputFile(path, kMaxJsonFileBytes);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    // nlohmann quotes the bytes it stopped at, which need not be printable.
    throw Error(path.string(), "is not valid JSON: " + printableText(e.what(), std::string::npos));
  }
}

}  // namespace glint
