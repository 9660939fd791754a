// `glint info DATASET`: views, resolution, value ranges per buffer, and problems found.
#include <cstdio>

#include "app/commands.h"
#include "scene/dataset_summary.h"

namespace glint {

void addInfoCommand(CLI::App& app) {
  auto root = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "info", "Describe a dataset: views, resolution, field of view, value ranges per buffer, and every problem found "
              "by validation. Exits with status 2 when problems were found.");
  cmd->add_option("dataset", *root, "Dataset folder (with transforms_train.json)")->required();
  cmd->callback([root]() {
    bool clean = false;
    std::string report = describeDataset(*root, &clean);
    std::fputs(report.c_str(), stdout);
    if (!clean) std::exit(2);
  });
}

}  // namespace glint
