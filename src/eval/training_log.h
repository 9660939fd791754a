// The training log RUN/log.csv that `glint train` writes (one row per step), read back as
// numeric columns for reports.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <string>
#include <vector>

namespace glint {

struct TrainingLog {
  std::vector<std::string> names;            // the header's column names, in order
  std::vector<std::vector<double>> columns;  // one per name; NaN where a field is empty

  size_t rows() const { return columns.empty() ? 0 : columns.front().size(); }
  bool has(const std::string& name) const;
  // The column of that name; a programming error (GLINT_CHECK) unless has(name).
  const std::vector<double>& column(const std::string& name) const;
};

// Reads a CSV log: a header of column names, then rows of numbers or empty fields, all
// with as many fields as the header. The header must hold every required name. Throws
// Error naming the file and the line (and column) that is wrong.
TrainingLog readTrainingLog(const std::filesystem::path& path, std::initializer_list<const char*> required = {});
// The same for the text of such a file; `file` names it in errors.
TrainingLog parseTrainingLog(const std::string& text, const std::string& file,
                             std::initializer_list<const char*> required = {});

}  // namespace glint
