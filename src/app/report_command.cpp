// `glint report RUN`: gathers a training run's config, log, evaluation metrics and rendered
// test views into one self-contained page, RUN/report.html.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/rendered_buffers.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"
#include "eval/html_report.h"
#include "eval/training_curves.h"
#include "eval/training_log.h"
#include "eval/view_metrics.h"
#include "io/image.h"
#include "io/json_file.h"
#include "scene/dataset.h"
#include "train/run_folder.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

struct ReportOptions {
  std::string run;
  std::string output;
  std::string dataset;
  int views = -1;  // -1: every evaluated view
  bool force = false;
};

// Throws the "not found" error of an input, saying which command makes it.
void requireInput(const fs::path& file, const std::string& makeIt) {
  if (!fs::exists(file)) throw Error(file.string(), "not found; " + makeIt);
}

// The metrics of `glint eval`, per view in the order of the split.
struct EvalMetrics {
  std::string split = "test";
  ViewMetrics mean;
  std::vector<std::pair<std::string, ViewMetrics>> perView;
  nlohmann::json all;  // the whole file, for the header (spp, tracer, seconds)
};

EvalMetrics readEvalMetrics(const fs::path& file) {
  EvalMetrics m;
  m.all = readJsonFile(file);
  const std::string name = file.string();
  if (!m.all.is_object()) throw Error(name, "is not a JSON object");
  if (m.all.contains("split") && m.all["split"].is_string()) m.split = m.all["split"].get<std::string>();
  if (!m.all.contains("mean")) throw Error(name, "key \"mean\" is missing");
  m.mean = viewMetricsFromJson(m.all["mean"], name, "mean");
  if (!m.all.contains("per_view") || !m.all["per_view"].is_array())
    throw Error(name, "key \"per_view\" is missing or not an array");
  for (size_t v = 0; v < m.all["per_view"].size(); ++v) {
    const nlohmann::json& entry = m.all["per_view"][v];
    std::string where = "per_view[" + std::to_string(v) + "]";
    if (!entry.is_object() || !entry.contains("view") || !entry["view"].is_string())
      throw Error(name, "key \"" + where + ".view\" is missing or not a string");
    m.perView.emplace_back(entry["view"].get<std::string>(), viewMetricsFromJson(entry, name, where));
  }
  return m;
}

// Why metrics m were not made on the views of split (of the dataset at datasetPath), or ""
// when they were.
std::string viewsMismatch(const EvalMetrics& m, const DatasetSplit& split, const fs::path& datasetPath) {
  if (m.split != split.name) return "evaluated the " + m.split + " split, not " + split.name;
  if (m.perView.size() != split.views.size())
    return "has " + std::to_string(m.perView.size()) + " views but the " + split.name + " split of " +
           datasetPath.string() + " has " + std::to_string(split.views.size());
  for (size_t v = 0; v < split.views.size(); ++v)
    if (m.perView[v].first != split.views[v].filePath)
      return "key \"per_view[" + std::to_string(v) + "].view\" is " + m.perView[v].first + " but the dataset has " +
             split.views[v].filePath;
  return "";
}

// The dataset: --dataset, else the one the metrics were evaluated on ("dataset" of
// metrics.json: `glint eval --dataset D_EDITED --edits` scores against another dataset than
// the run's), else the "dataset" of RUN/config.json (written by glint train).
fs::path datasetFolder(const ReportOptions& o, const fs::path& configFile, const std::optional<TrainConfig>& config,
                       const EvalMetrics& metrics, const fs::path& metricsFile) {
  if (!o.dataset.empty()) return o.dataset;
  if (metrics.all.contains("dataset") && metrics.all["dataset"].is_string()) {
    const fs::path evaluated = metrics.all["dataset"].get<std::string>();
    if (!evaluated.empty()) {
      if (!fs::exists(evaluated))
        throw Error(metricsFile.string(), "evaluated the dataset " + evaluated.string() +
                                              ", which is not found; pass --dataset");
      return evaluated;
    }
  }
  if (!config || config->dataset.empty())
    throw Error(configFile.string(), "key \"dataset\" is missing; pass --dataset");
  return config->dataset;
}

// The ground truth and our rendering of one view's radiance passes (those the dataset has).
ReportView loadViewImages(const Dataset& dataset, const DatasetSplit& split, size_t v, const fs::path& imagesFolder,
                          const ViewMetrics& metrics, const std::string& run) {
  ReportView view;
  view.name = split.views[v].filePath;
  const std::pair<const char*, Buffer> passes[] = {
      {"diffuse", Buffer::Diffuse}, {"specular", Buffer::Specular}, {"final", Buffer::Render}};
  for (const auto& [name, buffer] : passes) {
    // A dataset of final images only (NeRF-synthetic, a capture) has no truth for the others.
    if (!dataset.findBufferFile(split.views[v], buffer)) continue;
    fs::path oursFile = renderedBufferPath(imagesFolder, split.views[v].filePath, buffer);
    requireInput(oursFile, "run `glint eval " + run + " --save-images` first (it writes the rendered views)");
    ReportPass pass{name, dataset.loadBuffer(split, v, buffer), readImage(oursFile), {}};
    if (pass.ours.width != pass.truth.width || pass.ours.height != pass.truth.height)
      throw Error(oursFile.string(), "is " + std::to_string(pass.ours.width) + "x" + std::to_string(pass.ours.height) +
                                         " but the ground truth is " + std::to_string(pass.truth.width) + "x" +
                                         std::to_string(pass.truth.height) + "; re-run `glint eval` on this dataset");
    pass.metrics = buffer == Buffer::Diffuse ? metrics.diffuse : buffer == Buffer::Specular ? metrics.specular
                                                                                          : metrics.final;
    view.passes.push_back(std::move(pass));
  }
  for (Buffer buffer : {Buffer::Normal, Buffer::Depth, Buffer::Roughness, Buffer::F0}) {
    if (!dataset.findBufferFile(split.views[v], buffer)) continue;  // as above
    fs::path oursFile = renderedBufferPath(imagesFolder, split.views[v].filePath, buffer);
    requireInput(oursFile, "run `glint eval " + run + " --save-images` first (it writes the rendered views)");
    Image truth = dataset.loadBuffer(split, v, buffer), ours = readImage(oursFile);
    if (ours.width != truth.width || ours.height != truth.height || ours.channels != truth.channels)
      throw Error(oursFile.string(), "does not match the ground truth's " + std::string(bufferName(buffer)) +
                                         " buffer in size or channels; re-run `glint eval` on this dataset");
    view.gBuffers.push_back({bufferName(buffer), gBufferPictures(buffer, truth, ours)});
  }
  return view;
}

std::string formatSeconds(double seconds) {
  if (!std::isfinite(seconds)) return "-";
  char text[64];
  if (seconds >= 60)
    std::snprintf(text, sizeof text, "%s (%.0f s)", formatDuration(seconds).c_str(), seconds);
  else
    std::snprintf(text, sizeof text, "%.1f s", seconds);
  return text;
}

// The value of a log column in the last row, NaN for an empty log.
double lastValue(const TrainingLog& log, const char* column) {
  return log.rows() == 0 ? std::nan("") : log.column(column).back();
}

// The edit file an evaluation applied (`glint eval --edits`), or "" for the unedited scene.
std::string evaluationEdits(const nlohmann::json& m) {
  return m.contains("edits") && m["edits"].is_string() ? m["edits"].get<std::string>() : "";
}

// How an evaluation was made, from its metrics file: "64 spp, 4 bounces, denoised specular".
std::string evaluationSettings(const nlohmann::json& m) {
  std::string text;
  auto add = [&](const std::string& part) { text += (text.empty() ? "" : ", ") + part; };
  if (m.contains("spp") && m["spp"].is_number_integer()) add(std::to_string(m["spp"].get<int>()) + " spp");
  if (m.contains("bounces") && m["bounces"].is_number_integer())
    add(std::to_string(m["bounces"].get<int>()) + " bounces");
  if (m.contains("denoise") && m["denoise"].is_string() && m["denoise"] != "none")
    add("denoised " + m["denoise"].get<std::string>());
  if (m.contains("edits") && m["edits"].is_string()) add("edits " + m["edits"].get<std::string>());
  return text;
}

// The run's other metrics files (RUN/eval/*.json but `primary`) made on the same views, by
// name. A file that is not such a metrics file is skipped with a warning: the folder is
// the user's too.
std::vector<OtherEvaluation> otherEvaluations(const fs::path& primary, const DatasetSplit& split,
                                              const fs::path& datasetPath) {
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(primary.parent_path()))
    if (entry.is_regular_file() && entry.path().extension() == ".json" && entry.path() != primary)
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::vector<OtherEvaluation> others;
  for (const fs::path& file : files) {
    try {
      EvalMetrics m = readEvalMetrics(file);
      const std::string mismatch = viewsMismatch(m, split, datasetPath);
      if (!mismatch.empty()) {
        std::fprintf(stderr, "glint report: note: left out of the evaluations: %s: %s\n", file.string().c_str(),
                     mismatch.c_str());
        continue;
      }
      others.push_back({file.filename().string() + ": " + evaluationSettings(m.all), m.mean, evaluationEdits(m.all)});
    } catch (const Error& e) {
      // The error names the file already.
      std::fprintf(stderr, "glint report: note: left out of the evaluations: %s\n", e.what());
    }
  }
  return others;
}

// `p` relative to the run folder: the page names no one's home folder, and stays right when
// the run and its dataset move together.
std::string relativeToRun(const fs::path& run, const fs::path& p) {
  const fs::path relative =
      fs::absolute(p).lexically_normal().lexically_relative(fs::absolute(run).lexically_normal());
  return relative.empty() ? p.string() : relative.string();
}

std::vector<std::pair<std::string, std::string>> headerFacts(const ReportOptions& o, const fs::path& datasetPath,
                                                             const DatasetSplit& split,
                                                             const std::optional<TrainConfig>& config,
                                                             const TrainingLog& log, const EvalMetrics& metrics) {
  std::vector<std::pair<std::string, std::string>> facts;
  const fs::path runFolder = fs::absolute(o.run).lexically_normal();
  facts.emplace_back("run", runFolder.filename().empty() ? runFolder.parent_path().filename().string()
                                                         : runFolder.filename().string());
  facts.emplace_back("dataset", relativeToRun(o.run, datasetPath) + " (" + split.name + " split: " +
                                    std::to_string(split.views.size()) + " views, " + std::to_string(split.width) +
                                    "x" + std::to_string(split.height) + ")");
  std::string steps = log.rows() == 0 ? "none logged" : formatMetric(lastValue(log, "step"), 0);
  if (config) steps += " of " + std::to_string(config->iters) + ", bounces " + std::to_string(config->path().bounces);
  facts.emplace_back("training steps", steps);
  facts.emplace_back("Gaussians at the end", formatMetric(lastValue(log, "gaussians"), 0));
  facts.emplace_back("training wall time", formatSeconds(lastValue(log, "wall_s")));
  const nlohmann::json& m = metrics.all;
  std::string evaluation = evaluationSettings(m);
  if (m.contains("tracer") && m["tracer"].is_string())
    evaluation += (evaluation.empty() ? "" : ", ") + m["tracer"].get<std::string>() + " tracer";
  if (m.contains("seconds") && m["seconds"].is_number())
    evaluation += (evaluation.empty() ? "" : ", ") + formatSeconds(m["seconds"].get<double>());
  if (!evaluation.empty()) facts.emplace_back("evaluation", evaluation);
  return facts;
}

void runReport(const ReportOptions& o) {
  const RunFolder run(o.run);
  if (!fs::is_directory(run.root())) throw Error(o.run, "is not a training run folder");
  const fs::path configFile = run.configFile(), logFile = run.logFile(), metricsFile = run.metricsFile();
  const std::string trainHint = "it is written by `glint train DATASET -o " + o.run + "`";

  // The report is derived from the run, so RUN/report.html is simply rewritten; a file
  // elsewhere may be the user's own.
  const fs::path defaultOutput = run.reportFile();
  const fs::path output = o.output.empty() ? defaultOutput : fs::path(o.output);
  if (!o.output.empty() && fs::exists(output) && !o.force &&
      fs::weakly_canonical(output) != fs::weakly_canonical(defaultOutput))
    throw Error(o.output, "exists; pass --force to overwrite it");

  std::optional<TrainConfig> config;
  if (o.dataset.empty() || run.hasConfig()) {
    requireInput(configFile, trainHint);
    config = run.readConfig();
  }
  requireInput(logFile, trainHint);
  TrainingLog log = readTrainingLog(logFile, {"step", "loss", "gaussians", "wall_s"});
  requireInput(metricsFile, "run `glint eval " + o.run + " --save-images` first");
  EvalMetrics metrics = readEvalMetrics(metricsFile);
  std::error_code noTime;
  if (fs::exists(run.sceneFile()) &&
      fs::last_write_time(run.sceneFile(), noTime) > fs::last_write_time(metricsFile, noTime))
    std::fprintf(stderr, "glint report: warning: %s is older than scene.ply; re-run `glint eval %s --save-images`\n",
                 metricsFile.string().c_str(), o.run.c_str());

  const fs::path datasetPath = datasetFolder(o, configFile, config, metrics, metricsFile);
  // Read as the evaluation read it: the run's settings, and the --downscale and --background
  // that metrics.json records.
  DatasetReading reading = config ? config->datasetReading(/*requireBuffers=*/true) : DatasetReading{};
  if (metrics.all.contains("downscale") && metrics.all["downscale"].is_number_integer())
    reading.downscale = std::clamp(metrics.all["downscale"].get<int>(), 1, kMaxDownscale);
  if (metrics.all.contains("background") && metrics.all["background"].is_string())
    reading.background = choiceFromName<AlphaBackground>(metrics.all["background"].get<std::string>())
                             .value_or(reading.background);
  Dataset dataset = Dataset::open(datasetPath, reading);
  const DatasetSplit& split = dataset.split(metrics.split);
  if (std::string mismatch = viewsMismatch(metrics, split, datasetPath); !mismatch.empty())
    throw Error(metricsFile.string(), mismatch + "; was it evaluated on another dataset?");

  HtmlReportContent content;
  if (metrics.all.contains("display_transfer") && metrics.all["display_transfer"].is_string())
    content.displayTransfer = metrics.all["display_transfer"].get<std::string>();
  content.title = "Glint report: " + run.root().lexically_normal().filename().string();
  if (content.title == "Glint report: ") content.title += o.run;
  content.facts = headerFacts(o, datasetPath, split, config, log, metrics);
  content.mean = metrics.mean;
  content.perView = metrics.perView;
  content.evaluationLabel = metricsFile.filename().string() + ": " + evaluationSettings(metrics.all);
  content.evaluationEdits = evaluationEdits(metrics.all);
  content.otherEvaluations = otherEvaluations(metricsFile, split, datasetPath);
  size_t shown = o.views < 0 ? split.views.size() : std::min(split.views.size(), size_t(o.views));
  {
    ProgressBar progress("report", int64_t(shown), "views");
    for (size_t v = 0; v < shown; ++v) {
      content.views.push_back(
          loadViewImages(dataset, split, v, metricsFile.parent_path() / split.name, metrics.perView[v].second, o.run));
      progress.advance();
    }
  }
  auto named = [&](const fs::path& p) { return relativeToRun(o.run, p); };
  if (config) {  // the file as written, every setting of the run (defaults included)
    content.configSource = named(configFile);
    nlohmann::json settings = readJsonFile(configFile);
    if (settings.contains("dataset") && settings["dataset"].is_string())
      settings["dataset"] = named(settings["dataset"].get<std::string>());
    content.configText = settings.dump(2);
  }
  content.charts = trainingCharts(log);
  content.chartNote = "Lines are running means over " + std::to_string(kSmoothingSteps) +
                      " steps, drawn over the faint per-step values. The test PSNR during training is 8-bit (tonemapped), on "
                      "train's --eval-views views at --eval-spp samples, not scored as by `glint eval`.";
  content.note = "Written by `glint report` from " + named(configFile) + ", " + named(logFile) + ", " +
                 named(metricsFile) + " and the images under " + named(metricsFile.parent_path() / split.name) +
                 " (paths relative to the run). Self-contained: no network access, no other files.";

  std::string html = renderHtmlReport(content);
  writeTextAtomically(output, html);
  double kb = double(html.size()) / 1024;
  char size[32];
  std::snprintf(size, sizeof size, kb < 1024 ? "%.0f KB" : "%.1f MB", kb < 1024 ? kb : kb / 1024);
  std::printf("report: %s (%zu views shown, %s)\n", output.string().c_str(), shown, size);
}

}  // namespace

void addReportCommand(CLI::App& app) {
  auto o = std::make_shared<ReportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Write RUN/report.html, one self-contained page (no network, no other files) of a training run: its "
      "settings, the mean and per-view metrics of `glint eval` (RUN/eval/metrics.json, compared in one table with "
      "every other metrics file of RUN/eval/ on the same views), ground truth against ours for the diffuse, specular "
      "and final passes of each test view with per-pixel error maps, the G-buffers (normal, depth, roughness, F0) "
      "beside the ground truth's, a table of edit consistency when some evaluation applied --edits, the whole "
      "training configuration, and the training curves. LPIPS is left out (it needs a network's trained weights). "
      "Needs RUN/config.json and RUN/log.csv (from `glint train`) and RUN/eval/ (from `glint eval RUN "
      "--save-images`).");
  cmd->add_option("run", o->run, "Training run folder")->required();
  cmd->add_option("-o,--output", o->output, "Page to write (default RUN/report.html, rewritten each time), atomically");
  cmd->add_option("--dataset", o->dataset, "Dataset with the ground truth; default: the dataset RUN/eval/metrics.json was evaluated on (as glint eval --dataset gave it), else the dataset of RUN/config.json");
  cmd->add_option("--views", o->views, "Show the images of the first N views only (default: every evaluated view)")
      ->check(CLI::Range(0, 1 << 20));
  cmd->add_flag("--force", o->force, "Overwrite an existing -o FILE (RUN/report.html is always rewritten)");
  cmd->callback([o]() { runReport(*o); });
}

}  // namespace glint
