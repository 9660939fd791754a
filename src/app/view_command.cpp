// `glint view RUN|SCENE.ply`: the interactive viewer and editor. Serves a page on
// 127.0.0.1 that shows the scene rendered progressively (on the GPU or the CPU), with camera, display
// and edit controls (see README "Viewer"); Ctrl-C stops it.
#include <cstdio>
#include <filesystem>
#include <optional>

#include "app/commands.h"
#include "app/heal_flags.h"
#include "app/relight_flags.h"
#include "app/scene_source.h"
#include "app/thread_flag.h"
#include "app/trace_flags.h"
#include "app/viewer/progressive_renderer.h"
#include "app/viewer/viewer_outputs.h"
#include "app/viewer/viewer_setup.h"
#include "core/error.h"
#include "core/parallel.h"

namespace glint {

namespace {

namespace fs = std::filesystem;

struct ViewOptions {
  std::string scene;
  std::string inputLayout = "auto";
  std::string dataset;
  ViewerFlags viewer;
  size_t maxGaussians = kDefaultMaxGaussians;
  int threads = 0;
  RelightFlags relight;
  HealFlags heal;
  std::string device = "auto";
};

void runView(const ViewOptions& o) {
  ThreadLimit threads(o.threads);
  SceneSource source = loadSceneSource(o.scene, parseInputLayout(o.inputLayout));
  setViewerTracer(resolveTracerForDevice(o.device, "fast", /*tracerGiven=*/false, "glint view"));
  fs::path datasetPath = o.dataset.empty() ? fs::path(source.settings.dataset) : fs::path(o.dataset);
  std::optional<Dataset> dataset;
  if (!datasetPath.empty())
    dataset = Dataset::open(datasetPath, source.settings.datasetReading(/*requireBuffers=*/false));
  // Saved edits and exports go into a viewer/ folder beside what was opened (the run folder, or
  // the .ply's folder): never over a file of the run (viewer_outputs.h).
  fs::path opened = fs::is_directory(o.scene) ? fs::path(o.scene) : fs::absolute(o.scene).parent_path();
  fs::path output = opened / kViewerFolderName;
  ViewerOptions options = makeViewerOptions(o.viewer, dataset, source.scene, output);
  options.lockFolder = fs::is_directory(o.scene) ? opened : output;
  options.maxGaussians = o.maxGaussians;
  options.path = source.settings.renderPath();  // the page starts at the run's render bounces
  if (o.relight.on()) options.relight = o.relight.settings(source.settings.path());
  if (o.heal.on()) options.heal = o.heal.settings();
  std::fprintf(stderr, "glint view: %zu Gaussians at %dx%d; saving edits into %s\n", source.scene.size(),
               options.width, options.height, output.string().c_str());
  ViewerServer server(std::move(options), std::move(source.scene), source.settings.trace);
  server.bind();
  server.start();
  std::printf("glint view: open %s (Ctrl-C stops)\n", server.url().c_str());
  std::fflush(stdout);
  waitForInterrupt();
  std::fprintf(stderr, "glint view: stopping\n");
  server.stop();
}

}  // namespace

void addViewCommand(CLI::App& app) {
  auto o = std::make_shared<ViewOptions>();
  CLI::App* cmd = app.add_subcommand(
      "view", "Interactive viewer and editor in the browser: serves a page (default http://127.0.0.1:PORT/) that "
              "renders the scene progressively, with camera, render mode, bounce, exposure and edit controls. "
              "Edits are saved as an edit file and the edited scene exported as PLY into the viewer/ folder of the run "
              "(or beside the .ply). The printed URL carries a per-launch token that requests changing the viewer "
              "must send; requests naming another host or coming from another site's page are refused.");
  cmd->add_option("scene", o->scene, "Gaussian scene (.ply) or training run folder")->required();
  addInputLayoutFlag(*cmd, o->inputLayout);
  cmd->add_option("--dataset", o->dataset, "Dataset whose cameras to offer (default: the run's dataset)");
  cmd->add_option("--port", o->viewer.port, "Port to listen on (0 = any free port, printed)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  cmd->add_option("--host", o->viewer.host, "Address to listen on; anything but loopback shows the scene to the "
                                            "network and its edits to whoever sees the printed URL with its token (a "
                                            "warning is printed)")
      ->capture_default_str();
  cmd->add_option("--res", o->viewer.resolution, "Full image size WIDTHxHEIGHT (default: the dataset's, at most 640 "
                                                 "wide, else 480x360)");
  cmd->add_option("--max-samples", o->viewer.maxSamples, "Samples per pixel after which accumulation stops")
      ->check(CLI::Range(1, 65536))
      ->capture_default_str();
  cmd->add_option("--max-gaussians", o->maxGaussians,
                  "Most Gaussians an edit may leave in the scene; an edit that would make more is refused and the "
                  "scene kept (the viewer holds about 230 bytes a Gaussian shown, 390 while an edit rebuilds)")
      ->check(CLI::Range(size_t(1), size_t(1) << 40))
      ->capture_default_str();
  addThreadsFlag(cmd, &o->threads, "the viewer renders with them");
  addDeviceFlag(cmd, &o->device);
  o->relight.add(cmd);
  o->heal.add(cmd);
  cmd->callback([o]() { runView(*o); });
}

}  // namespace glint
