// Serving the viewer page: maps a URL path to a file inside the web folder, and never to
// one outside it (no "..", no absolute paths, no symbolic links leading out).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace glint {

// The file under webRoot that urlPath (already percent-decoded, starting with '/') names,
// or nullopt when the path is malformed, escapes the folder or names no regular file.
// "/" maps to index.html.
std::optional<std::filesystem::path> resolveStaticFile(const std::filesystem::path& webRoot,
                                                       const std::string& urlPath);

// Content-Type for a file name by extension (html, js, css, png, svg, json; else octet-stream).
const char* contentTypeFor(const std::filesystem::path& file);

// The web folder installed beside the running executable: <dir of exe>/web, or
// <dir of exe>/../web (the build tree keeps test binaries one level down). Empty if none.
std::filesystem::path findWebFolder();

}  // namespace glint
