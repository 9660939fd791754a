// Benchmark of the viewer's progressive renderer (issue 7): frames per second while the
// camera moves (the low-resolution frames the page shows during a drag) and full-resolution
// samples per second while it rests, at 320x240 with 2 bounces. On a training run folder
// (the demo scene) or, without one, on a generated scene of 100k surface Gaussians: a
// floor and three spheres, opaque and flat like trained ones, some smooth and metallic.
// Prints a table and writes JSON (--json FILE).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/scene_source.h"
#include "app/viewer/progressive_renderer.h"
#include "core/parallel.h"
#include "io/image.h"
#include "math/rng.h"

using namespace glint;

namespace {

using Clock = std::chrono::steady_clock;

// A flat Gaussian at p facing n (its thin axis along n).
void addSurfel(GaussianScene& scene, size_t i, Vec3f p, Vec3f n, float size, Rgb diffuse, float roughness, Rgb f0) {
  scene.position[i] = p;
  // Rotation taking local z to n (half-way quaternion; n = -z turns about x).
  Vec3f z(0, 0, 1), axis = cross(z, n);
  float w = 1.0f + dot(z, n);
  scene.rotation[i] = w < 1e-6f ? Quatf(0, 1, 0, 0) : Quatf(w, axis.x, axis.y, axis.z);
  scene.logScale[i] = Vec3f(std::log(size), std::log(size), std::log(size * 0.1f));
  scene.opacityLogit[i] = logit(0.95f);
  scene.diffuse[i] = diffuse;
  scene.normal[i] = n;
  scene.roughness[i] = roughness;
  scene.f0[i] = f0;
}

GaussianScene makeSurfaceScene(size_t n, uint64_t seed) {
  Rng rng(seed);
  GaussianScene scene;
  scene.resize(n);
  const Vec3f centers[3] = {{-1.3f, 0.6f, 0.0f}, {0.0f, 0.6f, -0.8f}, {1.3f, 0.6f, 0.0f}};
  const float radius = 0.6f;
  size_t floorCount = n / 2;
  for (size_t i = 0; i < n; ++i) {
    if (i < floorCount) {  // a 6 x 6 m checker floor
      Vec3f p(rng.uniform() * 6 - 3, 0, rng.uniform() * 6 - 3);
      bool dark = (int(std::floor(p.x * 2)) + int(std::floor(p.z * 2))) & 1;
      addSurfel(scene, i, p, {0, 1, 0}, 0.03f, Rgb(dark ? 0.1f : 0.7f), 0.5f, Rgb(0.04f));
    } else {  // three spheres: chrome, gold, rough plastic
      int s = int(i % 3);
      float zc = rng.uniform() * 2 - 1, phi = 6.2831853f * rng.uniform();
      float r = std::sqrt(std::max(0.0f, 1 - zc * zc));
      Vec3f dir(r * std::cos(phi), zc, r * std::sin(phi));
      Rgb f0 = s == 0 ? Rgb(0.95f) : s == 1 ? Rgb(1.0f, 0.77f, 0.34f) : Rgb(0.04f);
      addSurfel(scene, i, centers[s] + dir * radius, dir, 0.025f, Rgb(s == 2 ? 0.6f : 0.05f),
                s == 0 ? 0.05f : s == 1 ? 0.3f : 0.8f, f0);
    }
  }
  return scene;
}

// A camera orbiting the scene's centre at angle a.
ViewerCamera orbitCamera(double a, Vec3d center, double distance) {
  ViewerCamera c;
  c.eye = center + Vec3d(distance * std::sin(a), 0.4 * distance, distance * std::cos(a));
  c.forward = normalize(center - c.eye);
  c.fovX = 60.0 * 3.14159265 / 180.0;
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Measures the viewer's frames/s while moving and samples/s while still."};
  std::string run, jsonPath;
  int width = 320, height = 240, bounces = 2, threads = 2, gaussians = 100000;
  double seconds = 5;
  app.add_option("run", run, "Training run folder or .ply (default: a generated scene)");
  app.add_option("--gaussians", gaussians, "Size of the generated scene")->capture_default_str();
  app.add_option("--width", width, "Full image width")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--height", height, "Full image height")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--bounces", bounces, "Reflected segments")->check(CLI::Range(0, 8))->capture_default_str();
  app.add_option("--threads", threads, "Worker threads (0 = all)")->check(CLI::Range(0, 256))->capture_default_str();
  app.add_option("--seconds", seconds, "Duration of each measurement")->check(CLI::Range(0.5, 600.0))->capture_default_str();
  app.add_option("--json", jsonPath, "Also write the results to this JSON file");
  std::string framePath;
  app.add_option("--frame", framePath, "Also write the last still frame to this PNG (to see what was measured)");
  CLI11_PARSE(app, argc, argv);

  ThreadLimit limit(threads);
  SceneSource source;
  std::string sceneName = run;
  if (run.empty()) {
    source.scene = makeSurfaceScene(size_t(gaussians), 1);
    sceneName = "generated " + std::to_string(gaussians / 1000) + "k";
  } else {
    source = loadSceneSource(run);
  }
  Vec3f lo = source.scene.position[0], hi = lo;
  for (const Vec3f& p : source.scene.position) lo = min(lo, p), hi = max(hi, p);
  Vec3d center((lo + hi) * 0.5f);
  double distance = 0.6 * double(length(hi - lo));  // the scene fills most of the frame

  ProgressiveRenderer renderer(width, height, 1 << 20, source.settings.path());
  DisplaySettings settings;
  settings.bounces = bounces;
  renderer.setSettings(settings);
  renderer.setCamera(orbitCamera(0, center, distance));
  auto buildStart = Clock::now();
  renderer.setScene(traceScene(std::make_shared<const GaussianScene>(source.scene), source.settings.trace));
  double buildSeconds = std::chrono::duration<double>(Clock::now() - buildStart).count();

  // Moving: a new camera as soon as each frame arrives, as a drag does.
  uint64_t last = 0;
  int frames = 0, movingWidth = 0;
  double angle = 0;
  auto start = Clock::now();
  while (std::chrono::duration<double>(Clock::now() - start).count() < seconds) {
    std::shared_ptr<const Frame> frame = renderer.waitForFrame(last, std::chrono::milliseconds(10000));
    if (!frame || frame->id == last) continue;
    last = frame->id;
    ++frames;
    movingWidth = frame->image.width;
    angle += 0.02;
    renderer.setCamera(orbitCamera(angle, center, distance));
  }
  double movingFps = frames / std::chrono::duration<double>(Clock::now() - start).count();

  // Still: full-resolution samples accumulated per second, counted from the first one.
  renderer.setCamera(orbitCamera(angle, center, distance));
  std::shared_ptr<const Frame> frame;
  do frame = renderer.waitForFrame(last, std::chrono::milliseconds(10000)), last = frame->id;
  while (frame->samples == 0);
  int firstSamples = frame->samples;
  start = Clock::now();
  while (std::chrono::duration<double>(Clock::now() - start).count() < seconds)
    frame = renderer.waitForFrame(frame->id, std::chrono::milliseconds(10000));
  double stillSeconds = std::chrono::duration<double>(Clock::now() - start).count();
  double samplesPerSecond = (frame->samples - firstSamples) / stillSeconds;

  if (!framePath.empty()) writeImage(framePath, frame->image);
  std::printf("viewer_bench: %s (%zu Gaussians), %dx%d, %d bounces, %d threads, tracer built in %.2f s\n\n",
              sceneName.c_str(), source.scene.size(), width, height, bounces, maxThreads(), buildSeconds);
  std::printf("%-34s %10s\n", "measure", "value");
  std::printf("%-34s %10.1f\n", "moving: frames/s", movingFps);
  std::printf("%-34s %7dx%d\n", "moving: frame size (last)", movingWidth, movingWidth * height / width);
  std::printf("%-34s %10.2f\n", "still: full-size samples/s", samplesPerSecond);
  std::printf("%-34s %10.2f\n", "still: Mpixel-samples/s", samplesPerSecond * width * height / 1e6);
  if (!jsonPath.empty()) {
    nlohmann::json json = {{"scene", sceneName}, {"gaussians", source.scene.size()}, {"width", width},
                           {"height", height}, {"bounces", bounces}, {"threads", maxThreads()},
                           {"build_s", buildSeconds}, {"moving_fps", movingFps}, {"moving_width", movingWidth},
                           {"still_samples_per_s", samplesPerSecond}};
    std::ofstream(jsonPath) << json.dump(2) << "\n";
    std::printf("\nwrote %s\n", jsonPath.c_str());
  }
  return 0;
}
