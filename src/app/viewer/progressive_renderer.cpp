// The viewer's progressive render loop.
#include "app/viewer/progressive_renderer.h"

#include <algorithm>

#include "render/gaussian_renderer.h"

namespace glint {

namespace {

// Frames slower than this while moving make the first level coarser; faster than a
// quarter of it finer (the target is above 10 frames/s while interacting).
constexpr double kMovingFrameBudget = 0.08;
constexpr int kMaxMovingScale = 16;
// Rendering pauses when no frame was requested for this long.
constexpr std::chrono::seconds kIdleAfter{3};

}  // namespace

namespace {
std::string& viewerTracerKind() {
  static std::string kind = "fast";
  return kind;
}
}  // namespace

const std::string& viewerTracer() { return viewerTracerKind(); }
void setViewerTracer(const std::string& kind) { viewerTracerKind() = kind; }

std::shared_ptr<TracedScene> traceScene(std::shared_ptr<const GaussianScene> scene, const TraceSettings& trace) {
  auto traced = std::make_shared<TracedScene>();
  traced->scene = std::move(scene);
  traced->tracer = makeGaussianTracer(viewerTracer());
  traced->tracer->build(*traced->scene, trace);
  return traced;
}

ProgressiveRenderer::ProgressiveRenderer(int width, int height, int maxSamples, const PathSettings& path)
    : width_(width), height_(height), maxSamples_(maxSamples), path_(path),
      lastRequest_(std::chrono::steady_clock::now()) {
  settings_.bounces = std::clamp(path.bounces, 0, DisplaySettings::kMaxBounces);
  accumulator_.reset(width, height);
  thread_ = std::thread([this] { run(); });
}

ProgressiveRenderer::~ProgressiveRenderer() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void ProgressiveRenderer::restart() {
  ++epoch_;
  level_ = 0;
  wake_.notify_all();
}

void ProgressiveRenderer::setScene(std::shared_ptr<const TracedScene> scene) {
  std::lock_guard lock(mutex_);
  scene_ = std::move(scene);
  restart();
}

void ProgressiveRenderer::releaseScene() {
  std::unique_lock lock(mutex_);
  scene_.reset();
  restart();
  passDone_.wait(lock, [&] { return !rendering_; });
}

void ProgressiveRenderer::setUntracedScene(std::shared_ptr<const GaussianScene> scene, const TraceSettings& trace) {
  std::lock_guard lock(mutex_);
  untraced_ = std::move(scene);
  untracedTrace_ = trace;
  wake_.notify_all();
}

std::shared_ptr<const TracedScene> ProgressiveRenderer::scene() const {
  std::lock_guard lock(mutex_);
  return scene_;
}

void ProgressiveRenderer::setCamera(const ViewerCamera& camera) {
  std::lock_guard lock(mutex_);
  camera_ = camera;
  restart();
}

ViewerCamera ProgressiveRenderer::camera() const {
  std::lock_guard lock(mutex_);
  return camera_;
}

void ProgressiveRenderer::setSettings(const DisplaySettings& settings) {
  std::lock_guard lock(mutex_);
  bool resample = changesSamples(settings_, settings);
  settings_ = settings;
  if (resample) {
    restart();
  } else {
    redisplay_ = true;
    wake_.notify_all();
  }
}

DisplaySettings ProgressiveRenderer::settings() const {
  std::lock_guard lock(mutex_);
  return settings_;
}

std::shared_ptr<const ViewerFrame> ProgressiveRenderer::waitForFrame(uint64_t after, std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  bool wasIdle = std::chrono::steady_clock::now() - lastRequest_ > kIdleAfter;
  lastRequest_ = std::chrono::steady_clock::now();
  if (wasIdle) wake_.notify_all();
  frameReady_.wait_for(lock, timeout, [&] { return stop_ || (latest_ && latest_->id > after); });
  return latest_;
}

void ProgressiveRenderer::publish(Image image, int samples, double seconds) {
  auto frame = std::make_shared<ViewerFrame>();
  frame->id = nextId_++;
  frame->image = std::move(image);
  frame->samples = samples;
  frame->renderSeconds = seconds;
  latest_ = std::move(frame);
  frameReady_.notify_all();
}

void ProgressiveRenderer::run() {
  std::unique_lock lock(mutex_);
  while (true) {
    // Woken by changes and frame requests; the timeout notices when requests stop.
    bool work = wake_.wait_for(lock, kIdleAfter, [&] {
      bool watched = std::chrono::steady_clock::now() - lastRequest_ <= kIdleAfter;
      return stop_ || (watched && (redisplay_ || untraced_ ||
                                   (scene_ && (level_ < 2 || accumulator_.samples() < maxSamples_))));
    });
    if (stop_) return;
    if (!work) continue;
    if (untraced_) {
      std::shared_ptr<const GaussianScene> untraced = std::move(untraced_);
      untraced_.reset();
      TraceSettings trace = untracedTrace_;
      lock.unlock();
      std::shared_ptr<const TracedScene> traced = traceScene(std::move(untraced), trace);
      lock.lock();
      scene_ = std::move(traced);
      restart();
      continue;
    }
    if (redisplay_ && (!scene_ || (level_ == 2 && accumulator_.samples() >= maxSamples_))) {
      // Only the display changed and no pass is coming to show it.
      redisplay_ = false;
      if (accumulator_.samples() > 0) publish(accumulator_.display(settings_), accumulator_.samples(), 0);
      continue;
    }
    redisplay_ = false;
    if (level_ == 0) accumulator_.reset(width_, height_, settings_.bounces);

    // Take what this pass needs, then render without the lock so requests stay quick.
    std::shared_ptr<const TracedScene> scene = scene_;
    DisplaySettings settings = settings_;
    uint64_t epoch = epoch_;
    int level = level_;
    int scale = level == 0 ? movingScale_ : level == 1 ? std::max(1, movingScale_ / 2) : 1;
    int sample = accumulator_.samples();
    Camera camera = camera_.camera(std::max(1, width_ / scale), std::max(1, height_ / scale));
    RenderSettings render;
    render.spp = 1;
    render.path = path_;
    render.path.bounces = settings.bounces;
    // Low-resolution frames go through pixel centres; full-resolution sample k is sample k
    // of `glint render` (seed 0, view 0), so N accumulated samples are its --spp N render.
    render.jitter = level == 2;
    render.firstSample = sample;
    rendering_ = true;
    lock.unlock();
    auto start = std::chrono::steady_clock::now();
    // Every bounce's light is kept, so a switch between bounce modes needs no new samples.
    std::vector<Image> bounceLight;
    ViewBuffers buffers = renderGaussianView(*scene->tracer, camera, render, 0, &bounceLight);
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    scene.reset();  // before rendering_ goes false: releaseScene promises no reference is left
    lock.lock();
    rendering_ = false;
    passDone_.notify_all();

    if (level < 2) {
      // Shown even if the camera moved meanwhile: while dragging, a frame one step behind
      // beats no frame at all.
      FrameAccumulator single;
      single.reset(camera.width, camera.height, settings.bounces);
      single.add(buffers, bounceLight);
      publish(single.display(settings_), 0, seconds);
      if (level == 0) {
        if (seconds > kMovingFrameBudget && movingScale_ < kMaxMovingScale) movingScale_ *= 2;
        if (seconds < kMovingFrameBudget / 8 && movingScale_ > 4) movingScale_ /= 2;
      }
      if (epoch == epoch_) ++level_;
    } else if (epoch == epoch_) {
      accumulator_.add(buffers, bounceLight);
      publish(accumulator_.display(settings_), accumulator_.samples(), seconds);
    }
  }
}

}  // namespace glint
