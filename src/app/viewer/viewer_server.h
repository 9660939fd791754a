// The viewer's HTTP server (cpp-httplib): the page's static files, frames from the
// progressive renderer, and JSON endpoints for the camera, display settings, training
// cameras and edits. Every request is validated; a bad one gets a 4xx JSON error
// ({"error": "..."}) and changes nothing. Requests pass the access policy first
// (access_policy.h: Host, Origin, JSON bodies, the per-launch token), and connections are
// served under connection_limits.h.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/viewer/access_policy.h"
#include "app/viewer/viewer_camera.h"
#include "edit/gaussian_edits.h"
#include "edit/heal_uncovered.h"
#include "raytrace/trace_settings.h"
#include "render/differential_relight.h"
#include "render/gaussian_path.h"
#include "scene/gaussians.h"

namespace httplib {
class Server;
}

namespace glint {

class EditSession;
class ProgressiveRenderer;

struct TrainingCameraEntry {
  std::string name;
  ViewerCamera camera;
};

struct ViewerOptions {
  std::string host = "127.0.0.1";
  int port = 0;  // 0: any free port
  int width = 480, height = 360;
  int maxSamples = 1024;
  std::filesystem::path webRoot;       // the page's files
  std::filesystem::path outputFolder;  // where "save edits" and "export PLY" write (viewer_outputs.h)
  // Locked (core/folder_lock.h) while a save or an export writes: the run folder, so that a
  // save while `glint train` writes the run is refused with the trainer's PID. Empty: outputFolder.
  std::filesystem::path lockFolder;
  bool editable = true;                // false while training: the scene is the trainer's
  std::vector<TrainingCameraEntry> trainingCameras;
  ViewerCamera initialCamera;
  std::string token;  // required on requests that change anything; empty: a random one
  // Gaussians an edit may leave in the scene; an edit beyond is refused (413).
  size_t maxGaussians = kDefaultMaxGaussians;
  // Differential relighting after every edit (glint view --relight), or none.
  std::optional<RelightSettings> relight;
  // Healing of the surface an edit uncovered, before relighting (glint view --heal), or none.
  std::optional<HealSettings> heal;
  // How the scene's paths are traced (a run's TrainConfig::path()); the page starts at its
  // bounces and may change them.
  PathSettings path = [] {
    PathSettings p;
    p.bounces = 2;  // the paper's path length 3
    return p;
  }();
};

// Request bodies above this are refused with 413 (edit operations are a few hundred bytes).
constexpr size_t kMaxRequestBytes = 64 * 1024;

class ViewerServer {
 public:
  ViewerServer(ViewerOptions options, GaussianScene scene, const TraceSettings& trace);
  ~ViewerServer();  // stops serving

  // Binds the socket; returns the port (the chosen one when options.port is 0). Throws Error.
  int bind();
  // Serves on a background thread until stop() (or destruction).
  void start();
  void stop();
  // The page's address, with the token in its query (?token=...): the page sends it back.
  std::string url() const;
  const std::string& token() const { return access_.token; }

  // Replaces the scene shown (a training snapshot); only for servers that are not editable.
  // Returns at once: the render thread builds the tracer.
  void showScene(GaussianScene scene);

 private:
  void addRoutes();
  void addEditRoutes();
  void addStaticRoute();

  ViewerOptions options_;
  TraceSettings trace_;
  AccessPolicy access_;
  int port_ = 0;
  std::unique_ptr<httplib::Server> http_;
  std::unique_ptr<ProgressiveRenderer> renderer_;
  std::unique_ptr<EditSession> edits_;
  std::thread listener_;
};

}  // namespace glint
