// The viewer's render thread (paper appendix B.1): while the camera moves it renders
// low-resolution frames (a quarter of the size, then half), and once the camera rests it
// accumulates jittered full-resolution samples, one per frame, until a sample budget.
// Any change of camera, scene or bounces starts over. Nobody asking for frames for a few
// seconds (the page closed) pauses rendering, so a forgotten viewer does not hold the cores.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "app/viewer/display_settings.h"
#include "app/viewer/frame_accumulator.h"
#include "app/viewer/viewer_camera.h"
#include "io/image.h"
#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_path.h"
#include "scene/gaussians.h"

namespace glint {

// A scene with the tracer built over it, shared between the render thread and whoever
// replaces it (edits, training); immutable once published.
struct TracedScene {
  std::shared_ptr<const GaussianScene> scene;
  std::unique_ptr<GaussianTracer> tracer;
};

// The tracer the viewer renders with: "fast" (the CPU) unless `glint view --device` chose
// the GPU at start-up.
const std::string& viewerTracer();
void setViewerTracer(const std::string& kind);

// Builds a TracedScene with the viewer's tracer.
std::shared_ptr<TracedScene> traceScene(std::shared_ptr<const GaussianScene> scene, const TraceSettings& trace);

// One published frame: the display image (RGB in [0, 1]) and what it holds.
struct ViewerFrame {
  uint64_t id = 0;  // increases with every published frame
  Image image;
  int samples = 0;  // full-resolution samples accumulated; 0 for a low-resolution frame
  double renderSeconds = 0;  // time spent on the last pass
};

class ProgressiveRenderer {
 public:
  // width x height: the full resolution. maxSamples: accumulation stops there. Paths are
  // traced with `path`, but for their bounces, which the display settings hold (starting
  // at path.bounces).
  ProgressiveRenderer(int width, int height, int maxSamples, const PathSettings& path);
  ~ProgressiveRenderer();  // stops the thread
  ProgressiveRenderer(const ProgressiveRenderer&) = delete;
  ProgressiveRenderer& operator=(const ProgressiveRenderer&) = delete;

  void setScene(std::shared_ptr<const TracedScene> scene);
  // Hands over a scene whose tracer the render thread builds itself before its next pass,
  // so the caller (the training loop) does not wait for the build. A newer one replaces
  // one not yet taken.
  void setUntracedScene(std::shared_ptr<const GaussianScene> scene, const TraceSettings& trace);
  std::shared_ptr<const TracedScene> scene() const;
  // Stops showing the scene and returns once the render thread holds no reference to it,
  // so that its owner may change it in place (an edit refitting its tracer); setScene shows
  // one again. Frames already published stay.
  void releaseScene();
  void setCamera(const ViewerCamera& camera);
  ViewerCamera camera() const;
  void setSettings(const DisplaySettings& settings);
  DisplaySettings settings() const;
  int width() const { return width_; }
  int height() const { return height_; }

  // The newest frame once its id exceeds `after`, or the newest (possibly null) after timeout.
  std::shared_ptr<const ViewerFrame> waitForFrame(uint64_t after, std::chrono::milliseconds timeout) const;

 private:
  void run();
  void publish(Image image, int samples, double seconds);  // mutex_ held
  void restart();                                          // mutex_ held

  const int width_, height_, maxSamples_;
  const PathSettings path_;
  mutable std::mutex mutex_;
  mutable std::condition_variable wake_;        // the render thread waits for work
  mutable std::condition_variable frameReady_;  // requests wait for frames
  std::condition_variable passDone_;            // releaseScene waits for the pass to end
  bool stop_ = false;
  bool rendering_ = false;  // a pass is tracing a scene outside the lock
  std::shared_ptr<const TracedScene> scene_;
  std::shared_ptr<const GaussianScene> untraced_;
  TraceSettings untracedTrace_;
  ViewerCamera camera_;
  DisplaySettings settings_;
  uint64_t epoch_ = 0;   // bumped by every change that invalidates the samples
  int level_ = 0;        // 0: quarter size, 1: half size, 2: accumulating full size
  int movingScale_ = 4;  // the first level's divisor, raised when frames get slow
  bool redisplay_ = false;
  FrameAccumulator accumulator_;
  std::shared_ptr<const ViewerFrame> latest_;
  mutable std::chrono::steady_clock::time_point lastRequest_;  // of a frame
  uint64_t nextId_ = 1;
  std::thread thread_;
};

}  // namespace glint
