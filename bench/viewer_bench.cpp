// Benchmark of the viewer as a page drives it: the HTTP server of `glint view` on a loopback
// port, a client that posts cameras and long-polls /api/frame as web/frames.js does, and
// its measures: frames per second while the camera moves (the low-resolution frames of a
// drag) and full-size samples per second while it rests, at 320x240 with 2 bounces. The
// cameras are where users look: on a training run, the viewer's start camera and the
// dataset's training cameras; without one, a generated scene of 100k surface Gaussians (a
// floor and three spheres) seen from the viewer's start camera. Prints a table and writes
// JSON (--json FILE).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include "app/scene_source.h"
#include "app/trace_flags.h"
#include "app/viewer/access_policy.h"
#include "app/viewer/progressive_renderer.h"
#include "app/viewer/viewer_server.h"
#include "app/viewer/viewer_setup.h"
#include "scene/dataset.h"
#include "tracers/compute_device.h"
#include "core/parallel.h"
#include "io/image.h"
#include "math/rng.h"
#include "surface_scene.h"

using namespace glint;

namespace {

using Clock = std::chrono::steady_clock;

// The page's side of the viewer API: JSON posts with the token, long polls for frames.
class PageClient {
 public:
  PageClient(int port, std::string token) : http_("127.0.0.1", port), token_(std::move(token)) {
    http_.set_read_timeout(30, 0);
  }
  void post(const std::string& path, const nlohmann::json& body) {
    httplib::Headers headers{{kTokenHeader, token_}};
    auto res = http_.Post(path.c_str(), headers, body.dump(), "application/json");
    if (!res || res->status != 200) throw std::runtime_error("POST " + path + " failed");
  }
  nlohmann::json get(const std::string& path) {
    auto res = http_.Get(path.c_str());
    if (!res || res->status != 200) throw std::runtime_error("GET " + path + " failed");
    return nlohmann::json::parse(res->body);
  }
  struct FrameInfo {
    uint64_t id = 0;
    int samples = 0;
    int renderMs = 0;
    size_t bytes = 0;
  };
  // The newest frame after `after` (the server waits up to a second for one).
  FrameInfo frame(uint64_t after) {
    auto res = http_.Get(("/api/frame?after=" + std::to_string(after) + "&format=jpeg").c_str());
    if (!res || res->status != 200) throw std::runtime_error("GET /api/frame failed");
    return {std::stoull(res->get_header_value("X-Glint-Frame")), std::stoi(res->get_header_value("X-Glint-Samples")),
            std::stoi(res->get_header_value("X-Glint-Render-Ms")), res->body.size()};
  }

 private:
  httplib::Client http_;
  std::string token_;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Measures the viewer, through its HTTP server, as a page drives it: frames/s while moving and "
               "full-size samples/s while still, from the cameras a user sees."};
  std::string run, jsonPath;
  int width = 320, height = 240, bounces = 2, threads = 2, gaussians = 100000, cameras = 4;
  double seconds = 5;
  app.add_option("run", run, "Training run folder or .ply (default: a generated scene)");
  app.add_option("--gaussians", gaussians, "Size of the generated scene")->capture_default_str();
  app.add_option("--width", width, "Full image width")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--height", height, "Full image height")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--bounces", bounces, "Reflected segments")->check(CLI::Range(0, 8))->capture_default_str();
  app.add_option("--threads", threads, "Worker threads (0 = all)")->check(CLI::Range(0, 256))->capture_default_str();
  app.add_option("--seconds", seconds, "Duration of each still measurement")->check(CLI::Range(0.5, 600.0))->capture_default_str();
  app.add_option("--cameras", cameras, "Still cameras measured: the start camera and training cameras spread over "
                                       "the dataset")->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--json", jsonPath, "Also write the results to this JSON file");
  std::string device = "cpu", datasetPath;
  app.add_option("--device", device, "Where the viewer traces: cpu, cuda or auto (as glint view --device)")
      ->check(CLI::IsMember(deviceRequestNames()))
      ->capture_default_str();
  app.add_option("--dataset", datasetPath, "Dataset whose cameras to offer (default: the run's)");
  CLI11_PARSE(app, argc, argv);
  setViewerTracer(resolveTracerForDevice(device, "fast", /*tracerGiven=*/false, "viewer_bench"));

  ThreadLimit limit(threads);
  SceneSource source;
  std::string sceneName = run;
  if (run.empty()) {
    source.scene = makeSurfaceScene(size_t(gaussians), 1);
    sceneName = "generated " + std::to_string(gaussians / 1000) + "k";
  } else {
    source = loadSceneSource(run);
  }
  // The options `glint view` makes: the dataset's training (then test) cameras, the first
  // of them the start camera, else the overview; the run's path settings. Nothing is
  // saved, so the output folder is never written.
  std::optional<Dataset> dataset;
  if (!datasetPath.empty()) source.settings.dataset = datasetPath;
  if (!source.settings.dataset.empty()) dataset = Dataset::open(source.settings.dataset, /*requireBuffers=*/false);
  ViewerFlags flags;
  flags.resolution = std::to_string(width) + "x" + std::to_string(height);
  flags.maxSamples = 1 << 20;
  ViewerOptions options =
      makeViewerOptions(flags, dataset, source.scene, std::filesystem::temp_directory_path() / "glint_viewer_bench");
  options.path = source.settings.path();
  std::vector<std::pair<std::string, ViewerCamera>> still{{"start camera", options.initialCamera}};
  const size_t trainingCount = options.trainingCameras.size();
  for (int c = 1; c < cameras && trainingCount > 1; ++c) {
    const TrainingCameraEntry& e = options.trainingCameras[size_t(c) * trainingCount / size_t(cameras)];
    still.emplace_back(e.name, e.camera);
  }
  const size_t sceneSize = source.scene.size();
  ViewerServer server(options, std::move(source.scene), source.settings.trace);
  const int port = server.bind();
  server.start();
  PageClient page(port, server.token());
  page.post("/api/settings", {{"bounces", bounces}});

  // Still: per camera, full-size samples accumulated per second, counted from the first one.
  nlohmann::json stillJson = nlohmann::json::array();
  double sampleSum = 0, renderMsSum = 0;
  std::printf("viewer_bench: %s (%zu Gaussians), %dx%d, %d bounces, %d threads, %s tracer, through the HTTP server\n\n",
              sceneName.c_str(), sceneSize, width, height, bounces, maxThreads(), viewerTracer().c_str());
  std::printf("%-28s %14s %16s\n", "still camera", "samples/s", "render ms/sample");
  uint64_t last = 0;
  for (const auto& [name, camera] : still) {
    page.post("/api/camera", toJson(camera));
    PageClient::FrameInfo f = page.frame(last);
    while (f.samples < 1) f = page.frame(f.id);
    const int firstSamples = f.samples;
    int64_t renderMs = 0, frames = 0;
    auto start = Clock::now();
    while (std::chrono::duration<double>(Clock::now() - start).count() < seconds) {
      f = page.frame(f.id);
      renderMs += f.renderMs, ++frames;
    }
    double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    double rate = (f.samples - firstSamples) / elapsed;
    double msPerSample = frames ? double(renderMs) / double(frames) : 0.0;
    std::printf("%-28s %14.2f %16.1f\n", name.c_str(), rate, msPerSample);
    stillJson.push_back({{"camera", name}, {"samples_per_s", rate}, {"render_ms", msPerSample}});
    sampleSum += rate, renderMsSum += msPerSample;
    last = f.id;
  }
  const double meanRate = sampleSum / double(still.size());

  // Moving: a new camera as soon as each frame arrives, as a drag does (small steps about
  // the start camera).
  int frames = 0, movingWidth = 0;
  double angle = 0;
  auto start = Clock::now();
  while (std::chrono::duration<double>(Clock::now() - start).count() < seconds) {
    ViewerCamera c = options.initialCamera;
    angle += 0.01;
    c.forward = normalize(c.forward + Vec3d(0.1 * std::sin(angle * 7), 0.0, 0.1 * std::cos(angle * 7)));
    page.post("/api/camera", toJson(c));
    PageClient::FrameInfo f = page.frame(last);
    last = f.id;
    ++frames;
  }
  const double movingFps = frames / std::chrono::duration<double>(Clock::now() - start).count();
  nlohmann::json state = page.get("/api/state");
  movingWidth = state.value("width", width);
  server.stop();

  std::printf("\n%-34s %10s\n", "measure", "value");
  std::printf("%-34s %10.2f\n", "still: full-size samples/s (mean)", meanRate);
  std::printf("%-34s %10.2f\n", "still: Mpixel-samples/s (mean)", meanRate * width * height / 1e6);
  std::printf("%-34s %10.1f\n", "moving: frames/s", movingFps);
  if (!jsonPath.empty()) {
    nlohmann::json json = {{"scene", sceneName}, {"gaussians", sceneSize}, {"width", width}, {"height", height},
                           {"bounces", bounces}, {"threads", maxThreads()}, {"tracer", viewerTracer()}, {"still", stillJson},
                           {"still_samples_per_s", meanRate}, {"moving_fps", movingFps},
                           {"state_width", movingWidth}};
    std::ofstream(jsonPath) << json.dump(2) << "\n";
    std::printf("\nwrote %s\n", jsonPath.c_str());
  }
  return 0;
}
