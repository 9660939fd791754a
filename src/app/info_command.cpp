// `glint info DATASET`: views, resolution, value ranges per buffer, and problems found.
#include <cstdio>

#include "app/commands.h"
#include "app/thread_flag.h"
#include "core/parallel.h"
#include "scene/capture_summary.h"
#include "scene/dataset_summary.h"

namespace glint {

void addInfoCommand(CLI::App& app) {
  auto root = std::make_shared<std::string>();
  auto holdout = std::make_shared<int>(Dataset::kDefaultHoldout);
  auto threads = std::make_shared<int>(0);
  CLI::App* cmd = app.add_subcommand(
      "info", "Describe a dataset: views, resolution, field of view, value ranges per buffer, and every problem found "
              "by validation (for a capture: cameras, the buffers each view has, the depth fits and the normal "
              "space the data shows). Exits with status 2 when problems were found.");
  cmd->add_option("dataset", *root, "Dataset folder: transforms_train.json and its buffers, or a capture (COLMAP "
                                     "sparse/ or nerfstudio transforms.json, images/, priors/)")
      ->required();
  cmd->add_option("--holdout", *holdout, "A capture's every N-th image is a test view (as glint train --holdout)")
      ->check(CLI::Range(2, 1000))
      ->default_val(Dataset::kDefaultHoldout);
  addThreadsFlag(cmd, threads.get(), "the files are read and checked in parallel");
  cmd->callback([root, holdout, threads]() {
    ThreadLimit limit(*threads);
    bool clean = false;
    std::string report = isCaptureFolder(*root) || isPriorTransformsFolder(*root) || isNerfSyntheticFolder(*root)
                             ? describeCapture(*root, *holdout, &clean)
                             : describeDataset(*root, &clean);
    std::fputs(report.c_str(), stdout);
    if (!clean) std::exit(2);
  });
}

}  // namespace glint
