// `glint eval RUN --dataset D --split test`: renders every view of a split from a trained
// scene and compares it with the dataset's ground truth, writing RUN/eval/metrics.json.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <span>
#include <type_traits>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli_parsing.h"
#include "app/commands.h"
#include "app/dataset_flags.h"
#include "app/rendered_buffers.h"
#include "app/scene_edits.h"
#include "app/scene_source.h"
#include "app/thread_flag.h"
#include "app/trace_flags.h"
#include "core/atomic_file.h"
#include "core/activity.h"
#include "core/cluster.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "eval/error_breakdown.h"
#include "eval/region_metrics.h"
#include "eval/view_metrics.h"
#include "io/image.h"
#include "raytrace/gaussian_tracer.h"
#include "render/denoise.h"
#include "render/gaussian_renderer.h"
#include "scene/dataset.h"
#include "scene/view_sharing.h"
#include "math/percentile.h"
#include "train/camera_refinement.h"
#include "train/pose_alignment.h"
#include "train/training_eval.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

struct EvalOptions {
  std::string run;
  std::string inputLayout = "auto";
  std::string dataset;
  std::string split = "test";
  std::string output;
  int spp = 16;
  uint64_t seed = 0;
  int threads = 0;
  bool saveImages = false;
  std::string denoise = "none";
  std::string region;
  bool breakdown = false;
  bool alignCameras = false;
  TraceFlags trace;
  EditsFlag edits;
  DatasetFlags reading;  // --downscale, --background
};

// RUN/eval/metrics.json unless -o names another file; a bare .ply has no run folder to
// write into, so it needs -o.
fs::path metricsPath(const EvalOptions& o) {
  if (!o.output.empty()) return o.output;
  if (!fs::is_directory(o.run))
    throw Error(o.run, "is a scene file, not a training run folder: pass -o FILE for the metrics");
  return fs::path(o.run) / "eval" / "metrics.json";
}

void printTable(const DatasetSplit& split, const std::vector<ViewMetrics>& views, const ViewMetrics& mean,
                Transfer display) {
  std::printf("%-32s %12s %12s %12s %12s %10s %10s\n", "view", "diffuse dB", "diffuse 8b", "final dB", "final 8b",
              "depth RMSE", "normal deg");
  auto row = [](const std::string& name, const ViewMetrics& m) {
    std::printf("%-32s %12s %12s %12s %12s %10s %10s\n", name.c_str(), formatMetric(m.diffuse.psnr, 2).c_str(),
                formatMetric(m.diffuse.psnrTonemapped, 2).c_str(), formatMetric(m.final.psnr, 2).c_str(),
                formatMetric(m.final.psnrTonemapped, 2).c_str(), formatMetric(m.depthRmse, 4).c_str(),
                formatMetric(m.normalAngleDegrees, 2).c_str());
  };
  for (size_t v = 0; v < views.size(); ++v) row(split.views[v].filePath, views[v]);
  row("mean", mean);
  std::printf("\n%-10s %8s %8s %12s %12s   (mean over views; 8-bit = %s, quantised)\n", "pass", "PSNR", "SSIM",
              "PSNR 8-bit", "SSIM 8-bit", display == Transfer::Filmic ? "filmic tonemap" : transferName(display));
  auto pass = [](const char* name, const PassMetrics& p) {
    std::printf("%-10s %8s %8s %12s %12s\n", name, formatMetric(p.psnr, 2).c_str(), formatMetric(p.ssim, 4).c_str(),
                formatMetric(p.psnrTonemapped, 2).c_str(), formatMetric(p.ssimTonemapped, 4).c_str());
  };
  pass("diffuse", mean.diffuse);
  pass("specular", mean.specular);
  pass("final", mean.final);
}

void printRegionTable(const DatasetSplit& split, const std::vector<RegionMetrics>& regions,
                      const RegionMetrics& pooled) {
  std::printf("\n%-32s %8s %12s %12s %12s %12s   (pixels whose true surface lies in --region)\n", "view", "pixels",
              "diffuse dB", "diffuse 8b", "final dB", "final 8b");
  auto row = [](const std::string& name, const RegionMetrics& r) {
    std::printf("%-32s %8zu %12s %12s %12s %12s\n", name.c_str(), r.pixels, formatMetric(r.diffuse.psnr(), 2).c_str(),
                formatMetric(r.diffuseTonemapped.psnr(), 2).c_str(), formatMetric(r.final.psnr(), 2).c_str(),
                formatMetric(r.finalTonemapped.psnr(), 2).c_str());
  };
  for (size_t v = 0; v < regions.size(); ++v)
    if (regions[v].pixels > 0) row(split.views[v].filePath, regions[v]);
  row("pooled over views", pooled);
}

// With --denoise, the passes are scored after the a-trous filter (render/denoise.h), as the
// paper scores its renders after the OptiX denoiser. "final" filters the render buffer
// only (the paper's choice); "specular" filters the specular buffer and makes the render
// the unfiltered diffuse plus it, so that specular and final are both scored denoised.
void denoisePasses(const std::string& target, ViewBuffers& rendered) {
  if (target == "none") return;
  DenoiseSettings settings;
  settings.target = target == "final" ? DenoiseTarget::Render : DenoiseTarget::Specular;
  Image filtered = denoiseView(rendered, settings);
  if (target == "specular") {
    Image& specular = rendered[Buffer::Specular];
    const Image& diffuse = rendered[Buffer::Diffuse];
    for (size_t i = 0; i < specular.pixels.size(); ++i) specular.pixels[i] = filtered.pixels[i] - diffuse.pixels[i];
  }
  rendered[Buffer::Render] = std::move(filtered);
}

// The render as the mean of two renders of half the samples each with independent seeds, so
// that their difference measures the noise (eval/error_breakdown.h); G-buffers of the first.
ViewBuffers renderInHalves(const GaussianTracer& tracer, const Camera& camera, RenderSettings settings, uint64_t viewKey,
                           ViewBuffers halves[2]) {
  settings.spp /= 2;
  halves[0] = renderScoredView(tracer, camera, settings, viewKey);
  settings.seed = settings.seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull;  // any seed unlike the first
  halves[1] = renderScoredView(tracer, camera, settings, viewKey);
  ViewBuffers mean = halves[0];
  for (Buffer b : {Buffer::Render, Buffer::Diffuse, Buffer::Specular}) {
    std::vector<float>& m = mean[b].pixels;
    const std::vector<float>& other = halves[1][b].pixels;
    for (size_t i = 0; i < m.size(); ++i) m[i] = 0.5f * (m[i] + other[i]);
  }
  return mean;
}

// What one view contributes to the report, sent as bytes from the rank that scored it to
// rank 0, which puts the views back in order before averaging and summing them exactly as
// one process does.
struct ScoredView {
  uint64_t view = 0;
  ViewMetrics metrics;
  RegionMetrics region;
  ErrorBreakdown breakdown;
  // With --align-cameras: whether the view's camera moved, and by how much.
  bool aligned = false;
  double alignedDegrees = 0, alignedDistance = 0;
};
static_assert(std::is_trivially_copyable_v<ScoredView>);

// Every rank's scored views, on rank 0, in view order (an empty list on the other ranks).
std::vector<ScoredView> gatherScoredViews(const std::vector<ScoredView>& mine, size_t viewCount) {
  std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(mine.data()), mine.size() * sizeof(ScoredView));
  std::vector<ScoredView> all;
  if (!cluster::isRoot()) {
    cluster::gatherToRoot(bytes);
    return all;
  }
  all.resize(viewCount);
  std::vector<bool> seen(viewCount, false);
  for (const std::vector<std::byte>& part : cluster::gatherToRoot(bytes)) {
    for (size_t at = 0; at + sizeof(ScoredView) <= part.size(); at += sizeof(ScoredView)) {
      ScoredView view;
      std::memcpy(&view, part.data() + at, sizeof view);
      GLINT_CHECK(view.view < viewCount && !seen[view.view], "eval: a view scored twice or out of range");
      seen[view.view] = true;
      all[view.view] = view;
    }
  }
  for (size_t v = 0; v < viewCount; ++v) GLINT_CHECK(seen[v], "eval: a view was scored by no rank");
  return all;
}

void runEval(const EvalOptions& o) {
  ThreadLimit threads(o.threads);
  std::optional<WorldBox> region;
  if (!o.region.empty()) region = parseBox(o.region, "--region");
  if (o.breakdown && (o.spp < 2 || o.spp % 2 != 0))
    throw Error("command line", "--breakdown renders two independent halves of the samples: --spp must be even and "
                "at least 2 (got " + std::to_string(o.spp) + ")");
  SceneSource source = loadSceneSource(o.run, parseInputLayout(o.inputLayout));
  fs::path output = metricsPath(o);
  const SceneRendering rendering = o.trace.resolve(source.settings);
  const TraceSettings& trace = rendering.trace;
  fs::path datasetPath = o.dataset.empty() ? fs::path(source.settings.dataset) : fs::path(o.dataset);
  if (datasetPath.empty())
    throw Error(o.run, "names no dataset to compare with (only a training run's config.json can): pass --dataset");

  const DatasetReading reading = o.reading.resolve(source.settings, /*requireBuffers=*/true);
  Dataset dataset = Dataset::open(datasetPath, reading);
  // The 8-bit figures go through the transfer the dataset's images were stored with
  // (NeRF-synthetic's and photographs' sRGB, as published methods score them), else the
  // paper's filmic tonemap of Glint's linear buffers.
  const Transfer display = dataset.capture() ? dataset.capture()->decoding.photoTransfer : Transfer::Filmic;
  const DatasetSplit& split = dataset.split(o.split);
  if (split.views.empty()) throw Error(datasetPath.string(), "the " + o.split + " split has no views to evaluate");

  // Radiance with spp samples of 1 + bounces segments, and the pixel-centre G-buffer pass.
  double workRays = double(split.views.size()) * split.width * split.height *
                    (double(o.spp) * (1 + rendering.path.bounces) + (o.spp > 1 ? 1 : 0));
  std::unique_ptr<GaussianTracer> tracer =
      o.edits.prepareTracer(source.scene, trace, rendering.path, rendering.tracer, split.camera(0), workRays,
                            "glint eval");
  std::fprintf(stderr, "glint eval: %zu Gaussians, %s tracer; %zu %s views at %dx%d, %d spp\n", source.scene.size(),
               tracer->name(), split.views.size(), o.split.c_str(), split.width, split.height, o.spp);

  // Rendered as training scores its test views (train/training_eval.h). With --spp 1 the
  // radiance goes through the pixel centre only, which aliases edges (3 dB lower on
  // builtin:spheres than jittered samples).
  const RenderSettings settings = scoringSettings(o.spp, rendering.path, o.seed);
  fs::path imagesFolder = output.parent_path() / o.split;
  // Rank 0 makes the folders before any rank writes into them.
  if (cluster::isRoot()) {
    if (output.has_parent_path()) fs::create_directories(output.parent_path());
    if (o.saveImages) {
      for (Buffer b : kRenderedBuffers)
        fs::create_directories(renderedBufferPath(imagesFolder, split.views[0].filePath, b).parent_path());
      if (o.breakdown) fs::create_directories(imagesFolder / "pixel_kinds");
    }
  }
  cluster::barrier();
  // Views go to the ranks whole, or, with fewer views than ranks, as bands of rows that rank 0
  // joins and scores (SSIM and the pixel classes look across the band edges).
  const ViewShare share(split.views.size(), /*allowBands=*/true);
  std::vector<ScoredView> scored;
  auto start = std::chrono::steady_clock::now();
  {
    ProgressBar progress(share.progressLabel("eval"), int64_t(share.myCount()), "views");
    for (size_t v = 0; v < split.views.size(); ++v) {
      if (!share.mine(v)) continue;
      ActivityScope activity("rendering view " + split.views[v].filePath);
      // A capture's view may lack some buffers: their metrics are left empty ("-").
      ViewBuffers truth;
      for (Buffer b : kAllBuffers)
        if (dataset.findBufferFile(split.views[v], b)) truth[b] = dataset.loadBuffer(split, v, b);
      Camera camera = split.camera(v);
      PoseAlignment alignment;
      if (o.alignCameras) {
        // The whole view on every rank that scores a band of it: the same camera for all.
        const bool finalColour = truth[Buffer::Diffuse].empty();
        const Image& target = truth[finalColour ? Buffer::Render : Buffer::Diffuse];
        if (target.empty())
          throw Error(datasetPath.string(), "--align-cameras needs the diffuse or the final image of view " +
                                                split.views[v].filePath);
        const ViewBuffers model = renderForAlignment(*tracer, camera, rendering.path, finalColour, uint64_t(v));
        alignment = alignCameraPose(camera, alignmentColour(model, finalColour), model[Buffer::Depth], target);
        camera = alignment.camera;
      }
      RenderSettings mine = settings;
      const cluster::Share rows = share.myRows(camera.height);
      mine.rowBegin = int(rows.begin);
      mine.rowEnd = int(rows.end);
      ViewBuffers halves[2];
      ViewBuffers rendered = o.breakdown ? renderInHalves(*tracer, camera, mine, uint64_t(v), halves)
                                         : renderScoredView(*tracer, camera, mine, uint64_t(v));
      if (share.banded()) {
        rendered = joinBandsOnRoot(rendered);
        if (o.breakdown)
          for (ViewBuffers& half : halves) half = joinBandsOnRoot(half);
        if (!cluster::isRoot()) {
          progress.advance();
          continue;
        }
      }
      denoisePasses(o.denoise, rendered);
      ScoredView& score = scored.emplace_back();
      score.view = v;
      score.aligned = alignment.accepted;
      score.alignedDegrees = alignment.rotationDegrees;
      score.alignedDistance = alignment.translation;
      score.metrics = evaluateView(rendered, truth, display);
      if (o.breakdown) {
        std::vector<PixelKind> kinds = classifyPixels(camera, truth);
        // Noise is measured on the raw halves; after --denoise it no longer describes the render.
        bool raw = o.denoise == "none";
        score.breakdown =
            breakdownView(kinds, rendered, truth, raw ? &halves[0] : nullptr, raw ? &halves[1] : nullptr);
        if (o.saveImages) {
          fs::path kindsFolder = imagesFolder / "pixel_kinds";
          writeImage(kindsFolder / (fs::path(split.views[v].filePath).filename().string() + ".png"),
                     pixelKindImage(kinds, split.width, split.height));
        }
      }
      if (region)
        score.region = evaluateRegion(rendered, truth, regionMask(camera, truth[Buffer::Depth], *region));
      if (o.saveImages) writeRenderedBuffers(imagesFolder, split.views[v].filePath, rendered);
      progress.advance();
    }
  }
  // Rank 0 writes the report and prints the tables; its time includes waiting for the others.
  const std::vector<ScoredView> all = gatherScoredViews(scored, split.views.size());
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!cluster::isRoot()) return;
  std::vector<ViewMetrics> views;
  std::vector<RegionMetrics> regions;
  ErrorBreakdown breakdown;
  for (const ScoredView& view : all) {  // in view order, as one process adds them
    views.push_back(view.metrics);
    if (region) regions.push_back(view.region);
    if (o.breakdown) breakdown += view.breakdown;
  }
  ViewMetrics mean = averageViewMetrics(views);
  nlohmann::json cameraAlignment;
  if (o.alignCameras) {
    std::vector<float> degrees, distances;
    for (const ScoredView& view : all)
      if (view.aligned) degrees.push_back(float(view.alignedDegrees)), distances.push_back(float(view.alignedDistance));
    cameraAlignment = {{"views_moved", degrees.size()},
                       {"degrees_median", percentileOf(degrees, 0.5)},
                       {"degrees_max", percentileOf(degrees, 1.0)},
                       {"distance_median", percentileOf(distances, 0.5)},
                       {"distance_max", percentileOf(distances, 1.0)}};
    std::fprintf(stderr,
                 "glint eval: --align-cameras moved %zu of %zu cameras to their images, median %.3f deg and %.4g "
                 "(at most %.3f deg and %.4g)\n",
                 degrees.size(), all.size(), percentileOf(degrees, 0.5), percentileOf(distances, 0.5),
                 percentileOf(degrees, 1.0), percentileOf(distances, 1.0));
  }

  nlohmann::json report = {
      {"scene", o.run},
      {"dataset", fs::absolute(datasetPath).lexically_normal().string()},  // glint report finds it from anywhere
      {"split", o.split},
      {"downscale", reading.downscale},
      {"background", choiceName(reading.background)},
      {"views", split.views.size()},
      {"width", split.width},
      {"height", split.height},
      {"spp", o.spp},
      {"bounces", rendering.path.bounces},
      {"denoise", o.denoise},
      {"tracer", tracer->name()},
      {"display_transfer", transferName(display)},  // of the 8-bit ("tonemapped") figures
      {"trace",
       {{"kernel_power", trace.kernelPower},
        {"alpha_min", trace.alphaMin},
        {"min_transmittance", trace.minTransmittance},
        {"exact_tail", trace.exactTail}}},
      {"invalid_normal_length", rendering.path.invalidNormalLength},
      {"backface_skip", rendering.path.backfaceSkip},
      {"seconds", seconds},
      {"mean", toJson(mean)},
  };
  if (o.edits.given()) report["edits"] = o.edits.path();
  if (o.alignCameras) report["camera_alignment"] = cameraAlignment;
  nlohmann::json perView = nlohmann::json::array();
  for (size_t v = 0; v < views.size(); ++v) {
    nlohmann::json entry = toJson(views[v]);
    entry["view"] = split.views[v].filePath;
    if (region) entry["region"] = toJson(regions[v]);
    perView.push_back(entry);
  }
  report["per_view"] = perView;
  RegionMetrics pooled;
  for (const RegionMetrics& r : regions) pooled += r;
  if (o.breakdown) report["breakdown"] = toJson(breakdown);
  if (region) {
    report["region"] = {{"box", {region->lo.x, region->lo.y, region->lo.z, region->hi.x, region->hi.y, region->hi.z}},
                        {"pooled", toJson(pooled)}};
  }
  writeTextAtomically(output, report.dump(2) + "\n");

  printTable(split, views, mean, display);
  if (region) printRegionTable(split, regions, pooled);
  if (o.breakdown) printBreakdown(breakdown);
  std::printf("\nmetrics: %s%s\n", output.string().c_str(),
              o.saveImages ? (", images: " + imagesFolder.string()).c_str() : "");
}

}  // namespace

void addEvalCommand(CLI::App& app) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand(
      "eval",
      "Render every view of a dataset split from a trained scene and compare with the ground truth: PSNR and SSIM "
      "(11x11 Gaussian window, sigma 1.5) of the diffuse, specular and final passes, in linear space (data range 1) "
      "and on 8-bit images (through the filmic tonemap, or a display-referred dataset's own transfer, such as "
      "NeRF-synthetic's sRGB); depth RMSE and mean normal angle (degrees) where the ground truth "
      "has a surface. Writes RUN/eval/metrics.json (per view and averaged) and prints a table.");
  cmd->add_option("run", o->run,
                  "Training run folder (scene.ply, config.json), or a Gaussian scene .ply (then -o is required)")
      ->required();
  addInputLayoutFlag(*cmd, o->inputLayout);
  cmd->add_option("--dataset", o->dataset, "Dataset with the ground truth; default: the run's dataset");
  cmd->add_option("--split", o->split, "Split to evaluate")
      ->check(CLI::IsMember({"train", "test"}))
      ->capture_default_str();
  cmd->add_option("-o,--output", o->output, "Metrics file (default RUN/eval/metrics.json), written atomically");
  cmd->add_option("--spp", o->spp, "Rays per pixel for the radiance passes (diffuse, specular, final), jittered and averaged like the "
                  "ground truth's pixels; 1 goes through the pixel centre. G-buffers always use the pixel centre")
      ->check(CLI::Range(1, 1 << 16))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the sub-pixel jitter (with --spp > 1)")->capture_default_str();
  addThreadsFlag(cmd, &o->threads);
  cmd->add_option("--region", o->region,
                  "X0,Y0,Z0,X1,Y1,Z1: also score the pixels whose true surface point lies in this world-space box "
                  "(diffuse and final PSNR per view and pooled), e.g. one object's reconstruction");
  cmd->add_option("--denoise", o->denoise,
                  "Score the passes after the a-trous denoiser (guided by the diffuse, normal and depth buffers), "
                  "as the paper scores its renders after the OptiX denoiser: none; final (filter the render buffer "
                  "only, as the paper); specular (filter the specular buffer, render = diffuse + filtered specular)")
      ->check(CLI::IsMember({"none", "final", "specular"}))
      ->capture_default_str();
  cmd->add_flag("--breakdown", o->breakdown,
                "Also say where the error lies: every pixel is classed from the ground truth's buffers as silhouette "
                "(depth step or grazing view), highlight edge (steep step of the true specular), flat or curved mirror "
                "(roughness < 0.1), glossy (< 0.45) or rough, and the specular and final squared error (8-bit "
                "tonemapped) is split by class, with the part expected from Monte Carlo noise (the render is made as "
                "two independent halves of --spp, which must be even). With --save-images, writes a picture of the "
                "classes to <split>/pixel_kinds/");
  cmd->add_flag("--align-cameras", o->alignCameras,
                "Before scoring a view, move its camera to where the scene's render agrees best with the view's own "
                "image (its diffuse buffer, else its final image), the scene held fixed: direct image alignment, "
                "as papers on estimated cameras score their test views. For captures whose cameras COLMAP "
                "estimated: a held-out camera a degree off its photograph costs decibels that say nothing of the "
                "scene. Reported in metrics.json (camera_alignment); the scores of both ways are worth giving");
  o->trace.add(cmd);
  o->edits.add(cmd);
  o->reading.add(cmd, /*withBackground=*/true);
  cmd->add_flag("--save-images", o->saveImages,
                "Also write the rendered buffers as EXR next to the metrics file, under <split>/ (RUN/eval/test/...)");
  cmd->callback([o]() { runEval(*o); });
}

}  // namespace glint
