// Memory of training at the paper's resolution: writes a dataset of many large views with
// every buffer (by default 200 views of 1152x768, a textured floor seen from a ring of
// cameras, PNG buffers and EXR depth as predictors write them), loads its training targets
// in this process (bytes per pixel, load time), then runs `glint train` on it for a few
// steps and reports the command's peak resident memory (issue 21 asks for < 4 GB). Prints a
// table and writes JSON (--json FILE).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "scene/dataset.h"
#include "train/training_views.h"

using namespace glint;
namespace fs = std::filesystem;

namespace {

// The floor z = 0 seen by a camera: a checker of two diffuse colours with a slight gloss;
// pixels above the horizon have no surface.
ViewBuffers floorView(const Camera& camera) {
  ViewBuffers b = ViewBuffers::allocate(camera.width, camera.height);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      Ray ray = camera.generateRay(x + 0.5, y + 0.5);
      const double t = ray.direction.z < -1e-6 ? -ray.origin.z / ray.direction.z : -1.0;
      if (t <= 0.0) {
        b[Buffer::Render].setRgb(x, y, Rgb(0.6f, 0.7f, 0.9f));
        b[Buffer::Diffuse].setRgb(x, y, Rgb(0.6f, 0.7f, 0.9f));
        b[Buffer::Normal].setRgb(x, y, Rgb(0.0f, 0.0f, 1.0f));
        continue;
      }
      const Vec3d p = ray.origin + t * ray.direction;
      const bool dark = (int(std::floor(p.x * 4.0)) + int(std::floor(p.y * 4.0))) % 2 != 0;
      const Rgb diffuse = dark ? Rgb(0.1f, 0.08f, 0.05f) : Rgb(0.7f, 0.6f, 0.4f);
      const Rgb specular(0.02f + 0.01f * float(std::sin(p.x * 7.0)));
      b[Buffer::Diffuse].setRgb(x, y, diffuse);
      b[Buffer::Specular].setRgb(x, y, specular);
      b[Buffer::Render].setRgb(x, y, diffuse + specular);
      b[Buffer::Depth].at(x, y) = float(t);  // distance along the unit ray
      b[Buffer::Normal].setRgb(x, y, Rgb(0.0f, 0.0f, 1.0f));
      b[Buffer::Roughness].at(x, y) = dark ? 0.3f : 0.6f;
      b[Buffer::F0].setRgb(x, y, Rgb(0.04f));
    }
  return b;
}

DatasetSplit ringSplit(const std::string& name, int views, int width, int height, double phase) {
  DatasetSplit split;
  split.name = name;
  split.width = width, split.height = height;
  for (int i = 0; i < views; ++i) {
    const double a = 2.0 * 3.14159265358979 * (double(i) + phase) / double(views);
    const Vec3d eye(3.0 * std::cos(a), 3.0 * std::sin(a), 1.2 + 0.3 * std::sin(3.0 * a));
    char file[64];
    std::snprintf(file, sizeof(file), "%s/render/render_%04d", name.c_str(), i);
    split.views.push_back(
        {file, Camera::fromFieldOfView(Mat4::lookAt(eye, Vec3d(0, 0, 0), Vec3d(0, 0, 1)), 0.9, width, height), {}});
  }
  return split;
}

void writeDataset(const fs::path& root, int trainViews, int width, int height) {
  ProgressBar progress("write dataset", trainViews + 2, "views");
  for (auto [name, count] : {std::pair{std::string("train"), trainViews}, {std::string("test"), 2}}) {
    DatasetSplit split = ringSplit(name, count, width, height, name == "test" ? 0.5 : 0.0);
    parallelFor(int64_t(count), 1, [&](int64_t v) {
      writeViewBuffers(root, split.views[size_t(v)], floorView(split.camera(size_t(v))), ImageFormat::Png);
      progress.advance();
    });
    writeTransforms(root, split);
  }
  progress.finish();
}

// Runs argv to completion; returns its peak resident set in bytes (getrusage of the child).
size_t peakMemoryOf(const std::vector<std::string>& argv, double* seconds) {
  auto start = std::chrono::steady_clock::now();
  pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    std::perror("memory_bench: exec");
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) < 0) throw Error("memory_bench", "wait4 failed");
  *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error(argv[0], "failed (exit status " + std::to_string(status) + ")");
  return size_t(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Peak memory of glint train at the paper's resolution (200 views of 1152x768, every buffer)"};
  int views = 200, iters = 20;
  std::string resolution = "1152x768", work = "/tmp/glint_memory_bench", glint, jsonPath;
  bool keep = false;
  app.add_option("--views", views, "Training views to write")->check(CLI::Range(1, 100000));
  app.add_option("--res", resolution, "Size of every view, WxH");
  app.add_option("--work", work, "Folder for the dataset and the run (reused when the dataset is there)");
  app.add_option("--iters", iters, "Training steps glint train runs")->check(CLI::Range(1, 1000000));
  app.add_option("--glint", glint, "The glint program (default: ../glint beside this benchmark)");
  app.add_flag("--keep", keep, "Keep the dataset and run afterwards (they take about 1 GB at the defaults)");
  app.add_option("--json", jsonPath, "Write the results as JSON here");
  CLI11_PARSE(app, argc, argv);
  try {
    int width = 0, height = 0;
    if (std::sscanf(resolution.c_str(), "%dx%d", &width, &height) != 2 || width < 8 || height < 8)
      throw Error("--res", "expected WxH of at least 8x8, got \"" + resolution + "\"");
    if (glint.empty()) glint = (fs::canonical("/proc/self/exe").parent_path().parent_path() / "glint").string();
    const fs::path dataset = fs::path(work) / "dataset", run = fs::path(work) / "run";
    const size_t pixels = size_t(views) * size_t(width) * size_t(height);

    auto tag = fs::path(work) / ("dataset_" + std::to_string(views) + "_" + resolution);
    if (!fs::exists(tag)) {
      fs::remove_all(dataset);
      fs::create_directories(dataset);
      writeDataset(dataset, views, width, height);
      std::ofstream(tag) << "complete\n";
    }

    // The targets in this process: what TrainingViews holds, and how long loading takes.
    auto start = std::chrono::steady_clock::now();
    Dataset opened = Dataset::open(dataset);
    size_t targetBytes = 0;
    {
      TrainingViews loaded = TrainingViews::load(opened, opened.train());
      targetBytes = loaded.memoryBytes();
    }
    const double loadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    double trainSeconds = 0;
    const size_t peak = peakMemoryOf(
        {glint, "train", dataset.string(), "-o", run.string(), "--iters", std::to_string(iters), "--force"},
        &trainSeconds);
    const double gib = 1024.0 * 1024.0 * 1024.0;
    std::printf("memory_bench: %d training views of %dx%d (%.1f Mpixels), every buffer, %d threads\n", views, width,
                height, double(pixels) * 1e-6, maxThreads());
    std::printf("%-52s %12s\n", "quantity", "value");
    std::printf("%-52s %9.2f GiB\n", "training targets held (TrainingViews::memoryBytes)", double(targetBytes) / gib);
    std::printf("%-52s %10.1f B\n", "  per pixel (the unpacked layout before: 68 B)",
                double(targetBytes) / double(pixels));
    std::printf("%-52s %10.1f s\n", "loading the targets (parallel)", loadSeconds);
    std::printf("%-52s %9.2f GiB\n",
                ("glint train --iters " + std::to_string(iters) + ": peak resident memory").c_str(),
                double(peak) / gib);
    std::printf("%-52s %10.1f s\n", "  its wall time (loading, initialisation, steps)", trainSeconds);
    std::printf("%-52s %12s\n", "target: peak < 4 GiB", peak < size_t(4) * size_t(1 << 30) ? "met" : "NOT met");
    if (!jsonPath.empty()) {
      nlohmann::json j = {{"views", views},
                          {"width", width},
                          {"height", height},
                          {"target_bytes", targetBytes},
                          {"target_bytes_per_pixel", double(targetBytes) / double(pixels)},
                          {"load_seconds", loadSeconds},
                          {"train_iters", iters},
                          {"train_peak_rss_bytes", peak},
                          {"train_seconds", trainSeconds},
                          {"threads", maxThreads()}};
      std::ofstream(jsonPath) << j.dump(2) << "\n";
    }
    if (!keep) fs::remove_all(work);
  } catch (const Error& e) {
    std::fprintf(stderr, "memory_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
