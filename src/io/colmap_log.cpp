// Parsing COLMAP's progress lines and model_analyzer's statistics.
#include "io/colmap_log.h"

#include <cstdlib>

namespace glint {

namespace {

// The non-negative integer at text[*at...], advancing *at past it; nullopt without a digit.
std::optional<long> readCount(std::string_view text, size_t* at) {
  size_t start = *at;
  long value = 0;
  while (*at < text.size() && text[*at] >= '0' && text[*at] <= '9' && *at - start < 12)
    value = value * 10 + (text[(*at)++] - '0');
  if (*at == start) return std::nullopt;
  return value;
}

bool expect(std::string_view text, size_t* at, std::string_view what) {
  if (text.substr(*at, what.size()) != what) return false;
  *at += what.size();
  return true;
}

// "[i/N" after `prefix` at the start of the line (leading spaces allowed): i and N.
std::optional<ColmapProgress> bracketedCount(std::string_view line, std::string_view prefix) {
  size_t at = line.find_first_not_of(' ');
  if (at == std::string_view::npos || !expect(line, &at, prefix) || !expect(line, &at, " [")) return std::nullopt;
  std::optional<long> done = readCount(line, &at);
  if (!done || !expect(line, &at, "/")) return std::nullopt;
  std::optional<long> total = readCount(line, &at);
  if (!total || *total <= 0) return std::nullopt;
  return ColmapProgress{*done, *total};
}

}  // namespace

std::optional<ColmapProgress> parseColmapProgress(std::string_view line) {
  for (std::string_view prefix : {"Processed file", "Matching image", "Undistorting image"})
    if (auto progress = bracketedCount(line, prefix)) return progress;
  if (auto block = bracketedCount(line, "Matching block")) {
    size_t at = line.find(", ");
    if (at == std::string_view::npos) return std::nullopt;
    at += 2;
    std::optional<long> column = readCount(line, &at);
    if (!column || !expect(line, &at, "/")) return std::nullopt;
    std::optional<long> columns = readCount(line, &at);
    if (!columns || *columns != block->total) return std::nullopt;
    return ColmapProgress{(block->done - 1) * block->total + *column, block->total * block->total};
  }
  size_t at = line.find_first_not_of(' ');
  if (at != std::string_view::npos && expect(line, &at, "Registering image #")) {
    if (!readCount(line, &at) || !expect(line, &at, " (")) return std::nullopt;
    std::optional<long> registered = readCount(line, &at);
    if (!registered || !expect(line, &at, ")")) return std::nullopt;
    return ColmapProgress{*registered, 0};
  }
  return std::nullopt;
}

std::optional<ColmapModelStats> parseColmapModelStats(std::string_view output) {
  ColmapModelStats stats;
  bool haveRegistered = false, haveError = false;
  size_t lineStart = 0;
  while (lineStart < output.size()) {
    size_t lineEnd = output.find('\n', lineStart);
    if (lineEnd == std::string_view::npos) lineEnd = output.size();
    std::string_view line = output.substr(lineStart, lineEnd - lineStart);
    lineStart = lineEnd + 1;
    // Glog prefixes the lines ("I20261128 01:02:03.4 12345 model.cc:10] "): the figure
    // follows the last "] ", or starts the line when there is no prefix.
    size_t bracket = line.rfind("] ");
    if (bracket != std::string_view::npos) line = line.substr(bracket + 2);
    size_t colon = line.find(':');
    if (colon == std::string_view::npos) continue;
    std::string_view name = line.substr(0, colon);
    std::string value(line.substr(colon + 1));
    char* end = nullptr;
    double number = std::strtod(value.c_str(), &end);
    if (end == value.c_str()) continue;
    if (name == "Cameras") stats.cameras = long(number);
    else if (name == "Images") stats.images = long(number);
    else if (name == "Registered images") stats.registeredImages = long(number), haveRegistered = true;
    else if (name == "Points") stats.points = long(number);
    else if (name == "Observations") stats.observations = long(number);
    else if (name == "Mean track length") stats.meanTrackLength = number;
    else if (name == "Mean reprojection error") stats.meanReprojectionError = number, haveError = true;
  }
  if (!haveRegistered || !haveError) return std::nullopt;
  return stats;
}

}  // namespace glint
