// Reading RUN/log.csv: header, rows of numbers, empty fields as NaN.
#include "eval/training_log.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"

namespace glint {

namespace {

std::vector<std::string> splitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();  // getline drops a trailing empty field
  return fields;
}

}  // namespace

bool TrainingLog::has(const std::string& name) const {
  return std::find(names.begin(), names.end(), name) != names.end();
}

const std::vector<double>& TrainingLog::column(const std::string& name) const {
  auto it = std::find(names.begin(), names.end(), name);
  GLINT_CHECK(it != names.end(), "the training log has no column " + name);
  return columns[size_t(it - names.begin())];
}

TrainingLog readTrainingLog(const std::filesystem::path& path, std::initializer_list<const char*> required) {
  return parseTrainingLog(readInputFile(path, kMaxTextModelFileBytes), path.string(), required);
}

TrainingLog parseTrainingLog(const std::string& text, const std::string& file,
                             std::initializer_list<const char*> required) {
  std::istringstream in(text);
  TrainingLog log;
  std::string line;
  int lineNumber = 0;
  while (std::getline(in, line)) {
    ++lineNumber;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::vector<std::string> fields = splitFields(line);
    if (lineNumber == 1) {
      log.names = fields;
      for (const char* name : required)
        if (!log.has(name)) throw Error(file, "line 1: the header has no '" + std::string(name) + "' column");
      log.columns.resize(log.names.size());
      continue;
    }
    if (line.empty()) continue;
    if (fields.size() != log.names.size())
      throw Error(file, "line " + std::to_string(lineNumber) + ": " + std::to_string(fields.size()) +
                            " fields, but the header has " + std::to_string(log.names.size()));
    for (size_t c = 0; c < fields.size(); ++c) {
      const std::string& f = fields[c];
      double value = std::nan("");
      if (!f.empty()) {
        auto [end, error] = std::from_chars(f.data(), f.data() + f.size(), value);
        if (error != std::errc() || end != f.data() + f.size())
          throw Error(file, "line " + std::to_string(lineNumber) + ", column '" + log.names[c] + "': '" + f +
                                "' is not a number");
      }
      log.columns[c].push_back(value);
    }
  }
  if (lineNumber == 0) throw Error(file, "is empty: expected a header line of column names");
  return log;
}

}  // namespace glint
