// Flag value parsing with messages that name the flag.
#include "app/cli_parsing.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/error.h"
#include "core/printable_text.h"

namespace glint {

CLI::Validator positiveNumber() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0;
        const char* end = text.data() + text.size();
        auto [stop, error] = std::from_chars(text.data(), end, value);
        if (error == std::errc() && stop == end && std::isfinite(value) && value > 0) return "";
        return "must be a finite number > 0, found " + printableText(text);
      },
      "NUMBER > 0");
}

namespace {

bool parseFloat(const std::string& s, float* value) {
  if (s.empty()) return false;
  char* end = nullptr;
  *value = std::strtof(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(*value);
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, separator)) parts.push_back(part);
  return parts;
}

}  // namespace

Vec2i parseResolution(const std::string& text, const std::string& flag) {
  size_t x = text.find('x');
  auto fail = [&]() -> Error {
    return Error(flag + " expects WIDTHxHEIGHT with each side in [1, 16384] (for example 256x192), got '" + text + "'");
  };
  if (x == std::string::npos) throw fail();
  std::string w = text.substr(0, x), h = text.substr(x + 1);
  if (w.empty() || h.empty() || w.find_first_not_of("0123456789") != std::string::npos ||
      h.find_first_not_of("0123456789") != std::string::npos || w.size() > 5 || h.size() > 5)
    throw fail();
  Vec2i r(std::atoi(w.c_str()), std::atoi(h.c_str()));
  if (r.x < 1 || r.y < 1 || r.x > 16384 || r.y > 16384) throw fail();
  return r;
}

Rgb parseColor(const std::string& text, const std::string& flag) {
  std::vector<std::string> parts = split(text, ',');
  float v[3];
  bool ok = parts.size() == 1 || parts.size() == 3;
  for (size_t i = 0; ok && i < parts.size(); ++i) ok = parseFloat(parts[i], &v[i]) && v[i] >= 0;
  if (!ok) throw Error(flag + " expects one non-negative number or three separated by commas (R,G,B), got '" + text + "'");
  return parts.size() == 1 ? Rgb(v[0]) : Rgb(v[0], v[1], v[2]);
}

std::vector<size_t> parseIndexList(const std::string& text, const std::string& flag) {
  std::vector<size_t> indices;
  for (const std::string& part : split(text, ',')) {
    if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos || part.size() > 9)
      throw Error(flag + " expects view indices separated by commas (for example 0,10,20), got '" + text + "'");
    indices.push_back(size_t(std::atol(part.c_str())));
  }
  if (indices.empty()) throw Error(flag + " needs at least one view index");
  return indices;
}

Vec2i parsePixel(const std::string& text, const std::string& flag) {
  std::vector<size_t> xy = parseIndexList(text, flag);
  if (xy.size() != 2 || xy[0] > 1u << 20 || xy[1] > 1u << 20)
    throw Error(flag, "expects a pixel position X,Y (e.g. 80,60), got '" + text + "'");
  return {int(xy[0]), int(xy[1])};
}

WorldBox parseBox(const std::string& text, const std::string& flag) {
  std::vector<std::string> parts = split(text, ',');
  float v[6];
  bool ok = parts.size() == 6;
  for (size_t i = 0; ok && i < 6; ++i) ok = parseFloat(parts[i], &v[i]) && std::isfinite(v[i]);
  if (!ok) throw Error(flag + " expects six numbers X0,Y0,Z0,X1,Y1,Z1 (two opposite corners), got '" + text + "'");
  WorldBox box;
  box.lo = {std::min(v[0], v[3]), std::min(v[1], v[4]), std::min(v[2], v[5])};
  box.hi = {std::max(v[0], v[3]), std::max(v[1], v[4]), std::max(v[2], v[5])};
  return box;
}

}  // namespace glint
