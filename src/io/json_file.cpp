// Reading a JSON file with one error that names the file; floats written as their shortest decimal.
#include "io/json_file.h"

#include <algorithm>
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

namespace {

// nlohmann's messages start with "[json.exception.parse_error.101] "; drop that tag.
std::string withoutExceptionTag(const std::string& what) {
  if (!what.empty() && what.front() == '[') {
    size_t close = what.find("] ");
    if (close != std::string::npos) return what.substr(close + 2);
  }
  return what;
}

}  // namespace

nlohmann::json parseJsonText(std::string_view text, const std::string& fileName) {
  checkJsonNesting(text, fileName);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    std::string message =
        "is not valid JSON at byte " + std::to_string(e.byte) + ": " + withoutExceptionTag(e.what());
    // Python's json module writes NaN and Infinity, which JSON does not allow.
    size_t from = e.byte > 16 ? e.byte - 16 : 0;
    std::string_view near = text.substr(std::min(from, text.size()), 32);
    if (near.find("NaN") != std::string_view::npos || near.find("Infinity") != std::string_view::npos)
      message += " (JSON has no NaN or Infinity: every number must be finite)";
    throw Error(fileName, printableText(message, std::string::npos));  // quotes the bytes it stopped at
  } catch (const nlohmann::json::exception& e) {
    // For example out_of_range 406 for a number too large for a double (1e999).
    throw Error(fileName, "is not valid JSON: " + withoutExceptionTag(e.what()) + " (every number must be finite)");
  }
}

nlohmann::json readJsonFile(const std::filesystem::path& path) {
  return parseJsonText(readInputFile(path, kMaxJsonFileBytes), path.string());
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
