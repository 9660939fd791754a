// Reading a JSON file with one error that names the file when it is not valid JSON, and
// writing float settings as people wrote them.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace glint {

// The parsed contents of `path` (parseJsonText of the file). Throws Error naming the file
// when it cannot be read or is not valid JSON.
nlohmann::json readJsonFile(const std::filesystem::path& path);

// `text` parsed, its nesting checked first (checkJsonNesting). Throws Error(fileName, "is not
// valid JSON at byte N: ...") with nlohmann's message (its "[json.exception...]" tag
// dropped, the bytes it quotes made printable), and a hint where Python's NaN or Infinity,
// which JSON does not allow, stand near that byte.
nlohmann::json parseJsonText(std::string_view text, const std::string& fileName);

// nlohmann's parser recurses once per nesting level, so a file of 100,000 brackets would
// overflow the stack: every parse of a file's text checks first that its arrays and objects
// nest no deeper than this (Glint's own files nest 4 levels).
constexpr int kMaxJsonNesting = 256;
// Throws Error(fileName, ...) naming the byte where `text` nests deeper than kMaxJsonNesting.
void checkJsonNesting(std::string_view text, const std::string& fileName);

// A float as the JSON number of its shortest decimal: 0.9f is written 0.9, not the
// 0.8999999761581421 of the double it widens to, and reads back as the same float.
double jsonNumber(float value);

}  // namespace glint
