// What `glint info DATASET` prints: cameras, resolution, buffer statistics, point cloud and
// the problems validateDataset finds, as aligned plain-text tables.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scene/dataset.h"

namespace glint {

// Buffer statistics are taken over at most this many views per split, evenly spaced,
// so that describing a large dataset stays fast (validation still reads every view).
constexpr int kSummaryMaxViews = 20;
// Problems listed in full before "... and N more".
constexpr int kSummaryMaxProblems = 50;

// The human-readable report. Never throws for bad data: whatever cannot be read is left out
// of the tables and shows up in the problem list. *clean (if given) is set to true when
// validateDataset found no problem.
std::string describeDataset(const std::filesystem::path& root, bool* clean = nullptr);

// "file: message" with file shown relative to root when it lies inside it.
std::string formatProblem(const DatasetProblem& problem, const std::filesystem::path& root);

}  // namespace glint
