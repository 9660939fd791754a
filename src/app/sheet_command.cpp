// `glint sheet DATASET -o FILE.png`: a labelled contact sheet of a dataset's buffers.
#include <cstdio>

#include "app/cli_parsing.h"
#include "app/commands.h"
#include "app/thread_flag.h"
#include "core/error.h"
#include "core/parallel.h"
#include "eval/contact_sheet.h"
#include "io/image.h"

namespace glint {

namespace {

struct SheetOptions {
  std::string dataset;
  std::string output;
  std::string split = "train";
  std::string views;
  int rows = 3;
  int threads = 0;
};

void runSheet(const SheetOptions& o) {
  ThreadLimit threads(o.threads);
  Dataset dataset = Dataset::open(o.dataset);
  const DatasetSplit& split = dataset.split(o.split);
  std::vector<size_t> views;
  if (!o.views.empty()) {
    views = parseIndexList(o.views, "--views");
    for (size_t v : views)
      if (v >= split.views.size())
        throw Error("--views: view " + std::to_string(v) + " does not exist (the " + o.split + " split has " +
                    std::to_string(split.views.size()) + " views)");
  } else {
    // Evenly spread rows over the split.
    size_t n = std::min<size_t>(size_t(o.rows), split.views.size());
    for (size_t i = 0; i < n; ++i) views.push_back(i * split.views.size() / n);
  }
  Image sheet = makeContactSheet(dataset, split, views);
  writeImage(o.output, sheet);
  std::fprintf(stderr, "glint sheet: wrote %s (%dx%d)\n", o.output.c_str(), sheet.width, sheet.height);
}

}  // namespace

void addSheetCommand(CLI::App& app) {
  auto options = std::make_shared<SheetOptions>();
  CLI::App* cmd = app.add_subcommand(
      "sheet", "Write a contact sheet PNG of a dataset: one row per view, one column per buffer (radiance "
               "tonemapped, depth as a colour ramp, normals as n/2+0.5).");
  cmd->add_option("dataset", options->dataset, "Dataset folder")->required();
  cmd->add_option("-o,--output", options->output, "Output image (.png)")->required();
  cmd->add_option("--split", options->split, "Which split to show")->check(CLI::IsMember({"train", "test"}))->capture_default_str();
  cmd->add_option("--views", options->views, "Comma-separated view indices (default: evenly spread rows)");
  cmd->add_option("--rows", options->rows, "Number of evenly spread views when --views is not given")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  addThreadsFlag(cmd, &options->threads);
  cmd->callback([options]() { runSheet(*options); });
}

}  // namespace glint
