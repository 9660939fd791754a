// Static file resolution for the viewer page, confined to the web folder.
#include "app/viewer/static_files.h"

#include <algorithm>
#include <cctype>
#include <system_error>
#include <unistd.h>

namespace glint {

namespace fs = std::filesystem;

namespace {

// Only plain names of letters, digits, '-', '_' and '.', not starting with '.': this
// excludes "..", hidden files, backslashes, NULs and percent-escapes in one rule.
bool isPlainName(const std::string& part) {
  if (part.empty() || part[0] == '.' || part.size() > 128) return false;
  for (char c : part)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.')) return false;
  return true;
}

}  // namespace

std::optional<fs::path> resolveStaticFile(const fs::path& webRoot, const std::string& urlPath) {
  if (urlPath.empty() || urlPath[0] != '/' || urlPath.size() > 512) return std::nullopt;
  std::string relative = urlPath == "/" ? "index.html" : urlPath.substr(1);
  fs::path candidate = webRoot;
  size_t start = 0;
  while (start <= relative.size()) {
    size_t end = relative.find('/', start);
    if (end == std::string::npos) end = relative.size();
    std::string part = relative.substr(start, end - start);
    if (!isPlainName(part)) return std::nullopt;
    candidate /= part;
    start = end + 1;
  }
  // Resolve links and compare with the resolved root, so a symbolic link inside the web
  // folder cannot point the server at the rest of the disk.
  std::error_code error;
  fs::path root = fs::canonical(webRoot, error);
  if (error) return std::nullopt;
  fs::path resolved = fs::canonical(candidate, error);
  if (error || !fs::is_regular_file(resolved, error)) return std::nullopt;
  auto [rootEnd, unused] = std::mismatch(root.begin(), root.end(), resolved.begin(), resolved.end());
  if (rootEnd != root.end()) return std::nullopt;
  return resolved;
}

const char* contentTypeFor(const fs::path& file) {
  std::string ext = file.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".png") return "image/png";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".json") return "application/json";
  return "application/octet-stream";
}

fs::path findWebFolder() {
  std::error_code error;
  fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (error) return {};
  for (fs::path dir : {exe.parent_path() / "web", exe.parent_path().parent_path() / "web"})
    if (fs::is_regular_file(dir / "index.html", error)) return dir;
  return {};
}

}  // namespace glint
