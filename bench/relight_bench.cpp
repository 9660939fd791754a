// Benchmark of an edit's latency in the viewer (app/viewer/edit_session.h, the code `glint
// view` runs): the time from an edit request to the edited scene being shown, and to its
// deferred relighting being shown, with relighting and healing off, healing alone, and both
// (the default) at several relighting ray counts. Prints a table and writes JSON (--json FILE).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/heal_flags.h"
#include "app/relight_flags.h"
#include "app/scene_source.h"
#include "app/viewer/edit_session.h"
#include "app/viewer/viewer_setup.h"
#include "bench_timing.h"
#include "core/error.h"
#include "core/parallel.h"
#include "edit/gaussian_edits.h"
#include "edit/heal_uncovered.h"
#include "io/json_file.h"
#include "math/rng.h"
#include "render/differential_relight.h"
#include "scene/dataset.h"
#include "scene/gaussian_ply.h"

using namespace glint;

namespace {

// The viewer's requests of an edit file: one {"selection", "operation"} per operation, as
// the page sends them (the operation without its selection's name).
std::vector<nlohmann::json> requestsOf(const nlohmann::json& document) {
  std::vector<nlohmann::json> requests;
  for (nlohmann::json op : document.at("operations")) {
    const std::string name = op.at("selection");
    op.erase("selection");
    requests.push_back({{"selection", document.at("selections").at(name)}, {"operation", op}});
  }
  return requests;
}

// A seeded random subset of `keep` Gaussians (all of them when keep is 0 or not smaller).
GaussianScene subset(const GaussianScene& scene, size_t keep, uint64_t seed) {
  if (keep == 0 || keep >= scene.size()) return scene;
  std::vector<uint32_t> order(scene.size());
  std::iota(order.begin(), order.end(), 0u);
  Rng rng(seed);
  for (size_t i = 0; i < keep; ++i) std::swap(order[i], order[i + size_t(rng.uniform() * double(scene.size() - i))]);
  order.resize(keep);
  std::sort(order.begin(), order.end());
  std::vector<bool> kept(scene.size(), false);
  for (uint32_t i : order) kept[i] = true;
  GaussianScene out = scene;
  out.filter(kept);
  return out;
}

struct Row {
  std::string mode;
  int rays = 0;
  double firstShown = 0;  // the first edit shown (relighting deferred, as the viewer does)
  double firstRelit = 0;  // ... and relit, which also builds the unedited scene's tracer
  double againShown = 0;    // the last operation again (undo, then redo): shown
  double againPreview = 0;  // ... its relighting previewed (EditSession::relightPreview)
  double againRelit = 0;    // ... and relit in full after the preview
  double editDuring = 0;    // an undo sent 0.5 s into a full relighting: shown after (it cancels it)
  std::string relight;    // the session's own line about the relighting
  size_t healed = 0;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Measures how long the viewer takes to show an edit (glint view's edit session: the edit, healing, the "
      "tracer's refit or rebuild) and then its relighting, which the viewer defers, with relighting and healing "
      "off, healing alone, and both at each --rays. Each mode applies the edit file's operations as the page sends "
      "them, then undoes and redoes the last one: the redo is the latency of an edit once the session has built "
      "the unedited scene's tracer."};
  std::string scenePath, editsPath, jsonPath;
  size_t keep = 0;
  uint64_t seed = 1;
  int threads = 2;
  std::vector<int> rayCounts = {64, 16};
  app.add_option("scene", scenePath,
                 "Gaussian scene (.ply) or training run folder, read as glint view reads it (the run's trace and "
                 "path settings, its dataset's first camera and image size)")
      ->required()
      ->check(CLI::ExistingPath);
  app.add_option("edits", editsPath, "Edit file (docs/edit-files.md) whose operations are applied")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--keep", keep, "Use a seeded random subset of this many Gaussians (0 = all)")->capture_default_str();
  app.add_option("--seed", seed, "Seed of --keep's subset")->capture_default_str();
  app.add_option("--rays", rayCounts, "Relighting ray counts to measure (--relight-rays of glint view)")
      ->check(CLI::Range(1, 65536))
      ->capture_default_str();
  app.add_option("--threads", threads, "Worker threads (0 = all)")->check(CLI::Range(0, 256))->capture_default_str();
  app.add_option("--json", jsonPath, "Also write the results to this JSON file");
  CLI11_PARSE(app, argc, argv);

  try {
    ThreadLimit limit(threads);
    // As glint view sets itself up (app/view_command.cpp) with its default flags.
    SceneSource source = loadSceneSource(scenePath, PlyLayout::Auto);
    const GaussianScene scene = subset(source.scene, keep, seed);
    std::optional<Dataset> dataset;
    if (!source.settings.dataset.empty() && std::filesystem::exists(source.settings.dataset))
      dataset = Dataset::open(source.settings.dataset, source.settings.datasetReading(/*requireBuffers=*/false));
    const ViewerOptions viewer = makeViewerOptions(ViewerFlags{}, dataset, scene, "unused");
    const std::vector<nlohmann::json> requests = requestsOf(readJsonFile(editsPath));
    if (requests.empty()) throw Error(editsPath + ": the edit file holds no operation");

    // The context the viewer's edit routes give (app/viewer/edit_routes.cpp): the camera
    // shown, and its sample budget at full size, 1 + bounces segments a path.
    TracerUpdateContext context;
    context.probeCamera = viewer.initialCamera.camera(viewer.width, viewer.height);
    context.workRays = double(viewer.width) * viewer.height * viewer.maxSamples * (1 + source.settings.renderPath().bounces);
    const RelightSettings relightDefaults = RelightFlags{}.settings(source.settings.path());
    const HealSettings healDefaults = HealFlags{}.settings();

    struct Mode {
      std::string name;
      bool relight, heal;
      int rays;
    };
    std::vector<Mode> modes = {{"edit only", false, false, 0}, {"heal", false, true, 0}};
    for (int rays : rayCounts) modes.push_back({"heal + relight", true, true, rays});
    std::vector<Row> rows;
    for (const Mode& mode : modes) {
      std::optional<RelightSettings> relight;
      if (mode.relight) {
        relight = relightDefaults;
        relight->setRays(mode.rays);  // as --relight-rays sets them
      }
      std::optional<HealSettings> heal;
      if (mode.heal) heal = healDefaults;
      EditSession session(scene, source.settings.trace, kDefaultMaxGaussians, relight, heal, /*deferRelighting=*/true);
      Row row;
      row.mode = mode.name;
      row.rays = mode.rays;
      row.firstShown = secondsOf([&] {
        for (const nlohmann::json& request : requests) session.apply(request, context);
      });
      row.firstRelit = row.firstShown + secondsOf([&] { session.relight(context); });
      session.undo(context);
      session.relight(context);
      row.againShown = secondsOf([&] { session.redo(context); });
      row.againPreview = row.againShown + secondsOf([&] { session.relightPreview(); });
      const std::string preview = session.status().value("relight", "");
      row.againRelit = row.againPreview + secondsOf([&] { session.relight(context); });
      const nlohmann::json status = session.status();
      if (mode.relight) {
        // The viewer's case of a user who edits again while the shadows are computed.
        session.undo(context);
        session.redo(context);
        std::thread relighting([&] { session.relight(context); });
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
        row.editDuring = secondsOf([&] { session.undo(context); });
        relighting.join();
      }
      if (status.contains("relight")) row.relight = preview + "; then " + status["relight"].get<std::string>();
      if (status.contains("healed")) row.healed = status["healed"];
      rows.push_back(row);
      std::fprintf(stderr, "relight_bench: %s (%d rays) done\n", mode.name.c_str(), mode.rays);
    }

    std::printf("relight_bench: %zu Gaussians (%s%s), %zu operations of %s, %d threads; the viewer at %dx%d\n\n",
                scene.size(), scenePath.c_str(), keep ? (", a seeded subset") : "", requests.size(), editsPath.c_str(),
                maxThreads(), viewer.width, viewer.height);
    std::printf("shown: the edit applied and its tracer updated (what the viewer shows first); relit: and its\n"
                "shadows (the viewer relights after showing the edit); preview: a first look at them, from %zu\n"
                "Gaussians within reach at up to %d rays, which the viewer shows before the full relighting (whose time\n"
                "includes the preview's). first: the first edit of the session, which also builds the unedited\n"
                "scene's tracer; again: the last operation undone and redone; edit during: an undo sent 0.5 s\n"
                "into the full relighting of the redo, shown after (it cancels the relighting)\n\n",
                EditSession::kPreviewTraced, EditSession::kPreviewRays);
    std::printf("%-16s %6s %9s %9s %9s %9s %9s %9s %7s  %s\n", "mode", "rays", "first", "", "again", "", "",
                "edit", "healed", "relighting (of the redo)");
    std::printf("%-16s %6s %9s %9s %9s %9s %9s %9s\n", "", "", "shown s", "relit s", "shown s", "preview s", "relit s",
                "during s");
    nlohmann::json json = {{"scene", scenePath}, {"gaussians", scene.size()}, {"edits", editsPath},
                           {"threads", maxThreads()}, {"rows", nlohmann::json::array()}};
    for (const Row& r : rows) {
      std::printf("%-16s %6s %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %7zu  %s\n", r.mode.c_str(),
                  r.rays ? std::to_string(r.rays).c_str() : "-", r.firstShown, r.firstRelit, r.againShown,
                  r.againPreview, r.againRelit, r.editDuring, r.healed, r.relight.c_str());
      json["rows"].push_back({{"mode", r.mode}, {"rays", r.rays}, {"first_shown_seconds", r.firstShown},
                              {"first_relit_seconds", r.firstRelit}, {"again_shown_seconds", r.againShown},
                              {"again_preview_seconds", r.againPreview}, {"again_relit_seconds", r.againRelit},
                              {"edit_during_relighting_seconds", r.editDuring},
                              {"healed", r.healed}, {"relight", r.relight}});
    }
    if (!jsonPath.empty()) {
      std::ofstream(jsonPath) << json.dump(2) << "\n";
      std::printf("\nwrote %s\n", jsonPath.c_str());
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "relight_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
