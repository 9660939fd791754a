// How well baked SH colours stand in for Glint's path-traced reflections in a plain 3DGS
// viewer: bakes a trained run's scene (render/sh_bake.h) at SH degrees 0-3, renders each
// baked scene as a 3DGS viewer would (SH colour per Gaussian and viewing direction, blended
// front to back through Glint's own tracer, no reflections; render/splat_blend.h) on the
// test views, and reports the PSNR of those 8-bit images against `glint render`'s final
// image through the filmic tonemap, with the unbaked export (tonemapped diffuse, what
// `glint export` writes without --bake-reflections) as the baseline, and against the
// dataset's ground truth. Prints a table and writes JSON (--json FILE).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/parallel.h"
#include "eval/image_metrics.h"
#include "io/image.h"
#include "io/tonemap.h"
#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_renderer.h"
#include "render/sh_bake.h"
#include "render/splat_blend.h"
#include "scene/dataset.h"
#include "scene/gaussian_ply.h"
#include "train/run_folder.h"

using namespace glint;

namespace {

// A 3DGS viewer's picture of `colour`: per pixel the mean of a 2x2 grid of rays, each the
// SH colours blended along the ray, clamped to [0, 1] and quantised to 8 bits as a display
// does.
Image renderSplats(const GaussianScene& scene, const SplatColour& colour, const GaussianTracer& tracer,
                   const Camera& camera) {
  Image image(camera.width, camera.height, 3);
  parallelFor(camera.height, 1, [&](int64_t y) {
    HitList hits;
    hits.capacity = 4096;
    for (int x = 0; x < camera.width; ++x) {
      Rgb sum(0.0f);
      for (int s = 0; s < 4; ++s) {
        const Ray ray = camera.generateRay(x + 0.25 + 0.5 * (s % 2), double(y) + 0.25 + 0.5 * (s / 2));
        const TraceRay traceRay{Vec3f(ray.origin), Vec3f(ray.direction)};
        hits.clear();
        tracer.trace(traceRay, &hits);
        const Rgb c = blendSplatColour(scene, colour, traceRay.origin, hits);
        for (int k = 0; k < 3; ++k) sum[k] += std::round(std::clamp(c[k], 0.0f, 1.0f) * 255.0f) / 255.0f;
      }
      for (int k = 0; k < 3; ++k) image.at(x, int(y), k) = sum[k] / 4.0f;
    }
  });
  return image;
}

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Baked SH reflections against Glint's path-traced renders"};
  std::string runPath;
  std::string jsonPath = "sh_bake_bench.json";
  int referenceSpp = 64, directions = 64, maxViews = 0, onlyDegree = -1;
  double ridge = 0.005;
  app.add_option("run", runPath, "Training run folder (scene.ply, config.json naming the dataset)")->required();
  app.add_option("--spp", referenceSpp, "Samples per pixel of the glint render reference")->capture_default_str();
  app.add_option("--directions", directions, "Paths per Gaussian of the bake")->capture_default_str();
  app.add_option("--ridge", ridge, "Ridge weight of the bake's fit")->capture_default_str();
  bool sphere = false;
  app.add_flag("--sphere", sphere, "Sample directions over the whole sphere instead of from the training cameras");
  app.add_option("--degree", onlyDegree, "Bake this SH degree only (default: 0 to 3)");
  app.add_option("--views", maxViews, "Test views to score (0 = all)")->capture_default_str();
  app.add_option("--json", jsonPath, "Where to write the results")->capture_default_str();
  std::string imagesPath;
  app.add_option("--save-images", imagesPath,
                 "Folder to write the first test view's pictures to (reference, truth, each row's), as PNG");
  CLI11_PARSE(app, argc, argv);

  const RunFolder run(runPath);
  const TrainConfig config = run.readConfig();
  const GaussianScene scene = readGaussianPly(run.sceneFile());
  const Dataset dataset = Dataset::open(config.dataset, /*requireBuffers=*/false, config.holdout);
  const DatasetSplit& train = dataset.split("train");
  const DatasetSplit& test = dataset.split("test");
  const size_t views = maxViews > 0 ? std::min(test.views.size(), size_t(maxViews)) : test.views.size();
  std::unique_ptr<GaussianTracer> tracer = makeGaussianTracer("fast");
  tracer->build(scene, config.trace);
  const PathSettings path = config.renderPath();
  std::printf("%s: %zu Gaussians, %d render bounces, %zu test views, reference %d spp, threads %d\n", runPath.c_str(),
              scene.size(), path.bounces, views, referenceSpp, maxThreads());

  // The reference: glint render's final image as its 8-bit PNG shows it; and the ground truth.
  std::vector<Image> reference, truth;
  auto start = std::chrono::steady_clock::now();
  for (size_t v = 0; v < views; ++v) {
    RenderSettings settings;
    settings.spp = referenceSpp;
    settings.path = path;
    reference.push_back(tonemapTo8Bit(renderGaussianView(*tracer, test.camera(v), settings, v)[Buffer::Render]));
    truth.push_back(tonemapTo8Bit(dataset.loadBuffer(test, v, Buffer::Render)));
  }
  const double referenceSeconds = seconds(start);
  double renderVsTruth = 0;
  for (size_t v = 0; v < views; ++v) renderVsTruth += psnr(reference[v], truth[v]) / double(views);

  struct Row {
    std::string name;
    int degree;
    double bakeSeconds, psnrVsRender, psnrVsTruth;
  };
  std::vector<Row> rows;
  auto save = [&](const std::string& name, const Image& image) {
    if (!imagesPath.empty()) writeImage(std::filesystem::path(imagesPath) / (name + ".png"), image);
  };
  save("reference", reference[0]);
  save("truth", truth[0]);
  auto score = [&](const std::string& name, const SplatColour& colour, double bakeSeconds) {
    Row row{name, colour.shDegree, bakeSeconds, 0, 0};
    for (size_t v = 0; v < views; ++v) {
      const Image shown = renderSplats(scene, colour, *tracer, test.camera(v));
      if (v == 0) save("row" + std::to_string(rows.size()), shown);
      row.psnrVsRender += psnr(shown, reference[v]) / double(views);
      row.psnrVsTruth += psnr(shown, truth[v]) / double(views);
    }
    rows.push_back(row);
  };
  score("no bake (tonemapped diffuse)", displayColour(scene), 0);
  for (int degree = 0; degree <= 3; ++degree) {
    if (onlyDegree >= 0 && degree != onlyDegree) continue;
    ShBakeSettings settings;
    settings.degree = degree;
    settings.directions = directions;
    settings.ridge = ridge;
    settings.path = path;
    if (!sphere)
      for (size_t v = 0; v < train.views.size(); ++v) settings.cameras.push_back(train.camera(v));
    start = std::chrono::steady_clock::now();
    const SplatColour colour = bakeReflections(scene, *tracer, settings);
    score("bake, SH degree " + std::to_string(degree), colour, seconds(start));
  }

  std::printf("\nglint render (%d spp) against the ground truth: %.2f dB (8-bit, filmic tonemap); %.1f s\n",
              referenceSpp, renderVsTruth, referenceSeconds);
  std::printf("%-30s %6s %9s %18s %18s\n", "3DGS-viewer picture", "degree", "bake s", "PSNR vs render dB",
              "PSNR vs truth dB");
  nlohmann::json json;
  json["run"] = runPath;
  json["gaussians"] = scene.size();
  json["views"] = views;
  json["reference_spp"] = referenceSpp;
  json["directions"] = directions;
  json["ridge"] = ridge;
  json["directions_from"] = sphere ? "sphere" : "training cameras";
  json["render_bounces"] = path.bounces;
  json["render_vs_truth_psnr"] = renderVsTruth;
  for (const Row& row : rows) {
    std::printf("%-30s %6d %9.1f %18.2f %18.2f\n", row.name.c_str(), row.degree, row.bakeSeconds, row.psnrVsRender,
                row.psnrVsTruth);
    json["rows"].push_back({{"name", row.name},
                            {"degree", row.degree},
                            {"bake_seconds", row.bakeSeconds},
                            {"psnr_vs_render", row.psnrVsRender},
                            {"psnr_vs_truth", row.psnrVsTruth}});
  }
  std::ofstream(jsonPath) << json.dump(2) << "\n";
  std::printf("wrote %s\n", jsonPath.c_str());
  return 0;
}
