// Reading a JSON file with one error that names the file; floats written as their shortest decimal.
#include "io/json_file.h"

#include <charconv>
#include <cmath>
#include <string>

#include "core/input_file.h"
#include "core/error.h"
#include "core/printable_text.h"

namespace glint {

void checkJsonNesting(std::string_view text, const std::string& fileName) {
  int depth = 0;
  bool inString = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\') ++i;  // the escaped character, a quote included
      else if (c == '"') inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonNesting)
        throw Error(fileName, "is not valid JSON for Glint: arrays and objects nest deeper than " +
                                  std::to_string(kMaxJsonNesting) + " levels at byte " + std::to_string(i));
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

nlohmann::json readJsonFile(const std::filesystem::path& path) {
  std::string text = readInputFile(path, kMaxJsonFileBytes);
  checkJsonNesting(text, path.string());
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    // nlohmann quotes the bytes it stopped at, which need not be printable.
    throw Error(path.string(), "is not valid JSON: " + printableText(e.what(), std::string::npos));
  }
}

double jsonNumber(float value) {
  if (!std::isfinite(value)) return double(value);
  char text[32];
  const auto written = std::to_chars(text, text + sizeof(text), value);  // shortest round trip
  double shortest = 0;
  std::from_chars(text, written.ptr, shortest);
  return shortest;
}

}  // namespace glint
