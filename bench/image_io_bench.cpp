// Benchmark of Glint's image readers (io/image.h) against OpenImageIO's (issue 23): the median
// time of reading each kind of file Glint loads into float pixels, one thread each, in the
// same run, the values' largest difference, and the 2x box downscale of a render. Without
// OpenImageIO at build time only Glint's side runs. Prints a table and writes JSON (--json FILE).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bench_timing.h"
#include "image_io_samples.h"
#include "io/image.h"
#include "scene/downscale.h"
#ifdef GLINT_BENCH_HAVE_OIIO
#include "image_io_oiio.h"
#endif

using namespace glint;
namespace fs = std::filesystem;

namespace {

constexpr double kNotMeasured = std::numeric_limits<double>::quiet_NaN();

struct Row {
  std::string kind;
  uintmax_t fileBytes = 0;  // 0 for the downscale, which reads no file
  int width = 0, height = 0, channels = 0;
  double glintMs = kNotMeasured;
  double oiioMs = kNotMeasured;          // one thread, timed alternately with Glint's
  double oiioDefaultMs = kNotMeasured;   // OpenImageIO's default threads, timed afterwards
  double maxAbsDifference = kNotMeasured;
};

double medianMs(std::vector<double> seconds) {
  std::sort(seconds.begin(), seconds.end());
  size_t n = seconds.size();
  return 1e3 * (n % 2 ? seconds[n / 2] : 0.5 * (seconds[n / 2 - 1] + seconds[n / 2]));
}

// Largest |a - b| over all samples, or infinity when the images differ in size or channels.
// (This and timeAlternately go unused when OpenImageIO is missing.)
[[maybe_unused]] double maxAbsDifference(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels) return INFINITY;
  double largest = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) largest = std::max(largest, double(std::fabs(a.pixels[i] - b.pixels[i])));
  return largest;
}

// Times glint and other `repeats` times each, alternating which goes first, so that load
// from other processes on a shared machine falls on both alike. Returns their medians.
[[maybe_unused]] std::pair<double, double> timeAlternately(const std::function<Image()>& glint,
                                                           const std::function<Image()>& other, int repeats) {
  std::vector<double> glintSeconds, otherSeconds;
  for (int r = 0; r < repeats; ++r) {
    if (r % 2 == 0) {
      glintSeconds.push_back(secondsOf([&] { glint(); }));
      otherSeconds.push_back(secondsOf([&] { other(); }));
    } else {
      otherSeconds.push_back(secondsOf([&] { other(); }));
      glintSeconds.push_back(secondsOf([&] { glint(); }));
    }
  }
  return {medianMs(glintSeconds), medianMs(otherSeconds)};
}

double timeAlone(const std::function<Image()>& read, int repeats) {
  std::vector<double> seconds;
  for (int r = 0; r < repeats; ++r) seconds.push_back(secondsOf([&] { read(); }));
  return medianMs(seconds);
}

Image readWithGlint(const SampleFile& file) {
  return file.keepAlpha ? readImageWithAlpha(file.path) : readImage(file.path);
}

std::string formatMs(double ms) {
  if (std::isnan(ms)) return "-";
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f", ms);
  return text;
}

nlohmann::json numberOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Times Glint's image readers against OpenImageIO's on one file of each kind Glint loads."};
  int size = 800, repeats = 20;
  std::string jsonPath, folderOption;
  app.add_option("--size", size, "Width and height of every image")->check(CLI::Range(16, 8192))->capture_default_str();
  app.add_option("--repeats", repeats, "Timed reads per file and reader (the median counts)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_option("--dir", folderOption, "Folder for the image files, kept afterwards (default: a temporary folder, removed)");
  app.add_option("--json", jsonPath, "Also write the results to this JSON file");
  CLI11_PARSE(app, argc, argv);

  const fs::path folder = folderOption.empty()
                              ? fs::temp_directory_path() / ("glint_image_io_bench_" + std::to_string(getpid()))
                              : fs::path(folderOption);
  fs::create_directories(folder);
  const std::vector<SampleFile> files = writeSampleFiles(folder, size, /*seed=*/23);

  std::vector<Row> rows;
  for (const SampleFile& file : files) {
    const Image glintImage = readWithGlint(file);  // also the warm-up: the file is now in the page cache
    Row row{file.kind, fs::file_size(file.path), glintImage.width, glintImage.height, glintImage.channels};
#ifdef GLINT_BENCH_HAVE_OIIO
    useOiioSingleThread();
    row.maxAbsDifference = maxAbsDifference(glintImage, readWithOiio(file.path, file.channels));
    std::tie(row.glintMs, row.oiioMs) =
        timeAlternately([&] { return readWithGlint(file); }, [&] { return readWithOiio(file.path, file.channels); },
                        repeats);
#else
    row.glintMs = timeAlone([&] { return readWithGlint(file); }, repeats);
#endif
    rows.push_back(row);
  }

  // Resampling: a render at half resolution (--downscale 2 of a dataset), from an image whose
  // sides are even so that both keep every pixel.
  const Image full = readImage(files.front().path);
  Image render(full.width - full.width % 2, full.height - full.height % 2, 3);
  for (int y = 0; y < render.height; ++y)
    for (int x = 0; x < render.width; ++x) render.setRgb(x, y, full.rgb(x, y));
  Row downscale{"downscale 2x box (render)", 0, render.width / 2, render.height / 2, 3};
#ifdef GLINT_BENCH_HAVE_OIIO
  downscale.maxAbsDifference =
      maxAbsDifference(downscaleBuffer(render, Buffer::Render, 2), downscaleWithOiio(render, 2));
  std::tie(downscale.glintMs, downscale.oiioMs) = timeAlternately(
      [&] { return downscaleBuffer(render, Buffer::Render, 2); }, [&] { return downscaleWithOiio(render, 2); }, repeats);
#else
  downscale.glintMs = timeAlone([&] { return downscaleBuffer(render, Buffer::Render, 2); }, repeats);
#endif

#ifdef GLINT_BENCH_HAVE_OIIO
  // Afterwards, not interleaved: OpenImageIO's default starts OpenEXR's thread pool, which
  // is global to the process and would speed up Glint's EXR reads too.
  useOiioDefaultThreads();
  for (size_t i = 0; i < files.size(); ++i) {
    readWithOiio(files[i].path, files[i].channels);  // the pool's threads start here, untimed
    rows[i].oiioDefaultMs = timeAlone([&] { return readWithOiio(files[i].path, files[i].channels); }, repeats);
  }
  downscale.oiioDefaultMs = timeAlone([&] { return downscaleWithOiio(render, 2); }, repeats);
#endif
  rows.push_back(downscale);

  std::printf("image_io_bench: %dx%d images, median of %d reads per file and reader, files in the page cache\n", size,
              size, repeats);
#ifdef GLINT_BENCH_HAVE_OIIO
  std::printf("%s\n", oiioDescription().c_str());
  std::printf("OIIO 1T: one thread, timed alternately with Glint; OIIO/Glint: its ratio (below 1: OpenImageIO faster);\n"
              "OIIO def: OpenImageIO's default threads (%u hardware threads here), timed afterwards\n\n",
              std::thread::hardware_concurrency());
#else
  std::printf("OpenImageIO was not found when this benchmark was built: the comparison is skipped\n\n");
#endif
  std::printf("%-30s %8s %10s %9s %9s %10s %9s %10s\n", "file", "KiB", "channels", "Glint ms", "OIIO 1T", "OIIO/Glint",
              "OIIO def", "max |diff|");
  nlohmann::json json = nlohmann::json::array();
  for (const Row& r : rows) {
    const double ratio = r.oiioMs / r.glintMs;
    std::string kib = r.fileBytes ? std::to_string((r.fileBytes + 512) / 1024) : "-";
    char ratioText[16] = "-", differenceText[16] = "-";
    if (!std::isnan(ratio)) std::snprintf(ratioText, sizeof(ratioText), "%.2f", ratio);
    if (!std::isnan(r.maxAbsDifference)) std::snprintf(differenceText, sizeof(differenceText), "%.2g", r.maxAbsDifference);
    std::printf("%-30s %8s %10d %9s %9s %10s %9s %10s\n", r.kind.c_str(), kib.c_str(), r.channels,
                formatMs(r.glintMs).c_str(), formatMs(r.oiioMs).c_str(), ratioText, formatMs(r.oiioDefaultMs).c_str(),
                differenceText);
    json.push_back({{"kind", r.kind}, {"file_bytes", r.fileBytes}, {"width", r.width}, {"height", r.height},
                    {"channels", r.channels}, {"repeats", repeats}, {"glint_ms", numberOrNull(r.glintMs)},
                    {"oiio_one_thread_ms", numberOrNull(r.oiioMs)}, {"oiio_over_glint", numberOrNull(ratio)},
                    {"oiio_default_threads_ms", numberOrNull(r.oiioDefaultMs)},
                    {"max_abs_difference", numberOrNull(r.maxAbsDifference)}});
  }
  if (!jsonPath.empty()) {
    std::ofstream out(jsonPath);
    out << json.dump(2) << "\n";
    std::printf("\nwrote %s\n", jsonPath.c_str());
  }
  if (folderOption.empty()) fs::remove_all(folder);
  return 0;
}
