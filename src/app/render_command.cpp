// `glint render SCENE.ply|RUN --dataset D --split test -o OUT`: renders a Gaussian scene (or a
// training run's) from the cameras of a dataset split into per-view buffers named like the dataset's.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "app/cli_parsing.h"
#include "app/commands.h"
#include "app/rendered_buffers.h"
#include "app/scene_edits.h"
#include "app/scene_source.h"
#include "app/trace_flags.h"
#include "core/error.h"
#include "core/progress.h"
#include "io/image.h"
#include "raytrace/gaussian_tracer.h"
#include "render/denoise.h"
#include "render/gaussian_renderer.h"
#include "scene/dataset.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

struct RenderOptions {
  std::string scene;
  std::string dataset;
  std::string split = "test";
  std::string output;
  std::string resolution;
  int spp = 1;
  bool noJitter = false;
  uint64_t seed = 0;
  TraceFlags trace;
  EditsFlag edits;
  bool force = false;
  std::string format = "exr";
  bool denoise = false;  // also write OUT/render_denoised/NAME.exr
  std::string debugPixel;  // "x,y": print that pixel's paths instead of rendering
  int debugView = 0;
};

// Prints every segment of a pixel's paths: where it starts and goes, its throughput, what
// it blends, and its composited hits (the first few).
void printPixelPaths(const std::vector<std::vector<PathSegment>>& paths, int x, int y, size_t view) {
  std::printf("pixel (%d, %d) of view %zu: %zu samples\n", x, y, view, paths.size());
  for (size_t s = 0; s < paths.size(); ++s) {
    for (size_t k = 0; k < paths[s].size(); ++k) {
      const PathSegment& seg = paths[s][k];
      const RayResult& r = seg.result;
      std::printf("sample %zu segment %zu: origin (%.4f, %.4f, %.4f) direction (%.4f, %.4f, %.4f) throughput "
                  "(%.4f, %.4f, %.4f)\n",
                  s, k, seg.ray.origin.x, seg.ray.origin.y, seg.ray.origin.z, seg.ray.direction.x,
                  seg.ray.direction.y, seg.ray.direction.z, seg.throughput.x, seg.throughput.y, seg.throughput.z);
      std::printf("  diffuse (%.4f, %.4f, %.4f) depth %.4f normal length %.3f roughness %.3f f0 (%.3f, %.3f, %.3f) "
                  "T %.4f hits %d%s\n",
                  r.diffuse.x, r.diffuse.y, r.diffuse.z, r.depth, r.normalLength, r.roughness, r.f0.x, r.f0.y, r.f0.z,
                  r.transmittance, r.hitCount, r.truncated ? " (truncated)" : "");
      size_t shown = std::min<size_t>(seg.hits.hits.size(), 8);
      for (size_t h = 0; h < shown; ++h) {
        const HitRecord& hit = seg.hits.hits[h];
        std::printf("    hit %zu: Gaussian %u t %.4f alpha %.4f response %.4f\n", h, hit.id, hit.t, hit.alpha,
                    hit.response);
      }
      if (seg.hits.hits.size() > shown) std::printf("    ... %zu more hits\n", seg.hits.hits.size() - shown);
    }
  }
}

void checkOutputFolder(const fs::path& out, bool force) {
  if (!fs::exists(out) || force) return;
  if (!fs::is_directory(out)) throw Error(out.string(), "exists and is not a folder");
  if (!fs::is_empty(out) && !fs::exists(out / "render"))
    throw Error(out.string(), "folder is not empty and does not hold an earlier render; choose another -o folder "
                              "or pass --force");
}

void runRender(const RenderOptions& o) {
  if (o.output.empty() && o.debugPixel.empty()) throw Error("glint render", "needs an output folder: pass -o OUT");
  SceneSource source = loadSceneSource(o.scene);
  GaussianScene& scene = source.scene;
  TraceSettings trace = o.trace.apply(source.trace);
  fs::path datasetPath = o.dataset.empty() ? source.dataset : fs::path(o.dataset);
  if (datasetPath.empty())
    throw Error(o.scene, "names no dataset to take the cameras from (only a training run's config.json can): "
                         "pass --dataset");

  Dataset dataset = Dataset::open(datasetPath, /*requireBuffers=*/false);
  const DatasetSplit& split = dataset.split(o.split);
  int width, height;
  if (!o.resolution.empty()) {
    Vec2i r = parseResolution(o.resolution, "--res");
    width = r.x, height = r.y;
  } else {
    std::optional<fs::path> first = dataset.findBufferFile(split.views[0], Buffer::Render);
    if (!first)
      throw Error(datasetPath.string(),
                  "has no " + o.split + " render images to take the image size from; pass --res WxH");
    Image image = readImage(*first);
    width = image.width, height = image.height;
  }
  if (o.debugPixel.empty()) checkOutputFolder(o.output, o.force);

  auto start = std::chrono::steady_clock::now();
  Camera probeCamera{split.views[0].cameraToWorld, split.cameraAngleX, width, height};
  double workRays = double(split.views.size()) * width * height * o.spp * (1 + o.trace.path().bounces);
  std::unique_ptr<GaussianTracer> tracer =
      o.edits.prepareTracer(scene, trace, o.trace.tracer(), probeCamera, workRays, "glint render");
  double buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr,
               "glint render: %zu Gaussians, %s tracer ready in %.3f s (p = %g, alpha_min = %g, "
               "min_transmittance = %g); %zu %s views at %dx%d, %d spp\n",
               scene.size(), tracer->name(), buildSeconds, trace.kernelPower, trace.alphaMin, trace.minTransmittance,
               split.views.size(), o.split.c_str(), width, height, o.spp);

  RenderSettings settings;
  settings.spp = o.spp;
  settings.jitter = !o.noJitter;
  settings.seed = o.seed;
  settings.path = o.trace.path();
  if (!o.debugPixel.empty()) {
    Vec2i p = parsePixel(o.debugPixel, "--debug-pixel");
    if (p.x < 0 || p.y < 0 || p.x >= width || p.y >= height)
      throw Error("--debug-pixel", o.debugPixel + " lies outside the " + std::to_string(width) + "x" +
                                       std::to_string(height) + " image");
    if (o.debugView < 0 || size_t(o.debugView) >= split.views.size())
      throw Error("--view", std::to_string(o.debugView) + " is not a view of the " + o.split + " split (it has " +
                                std::to_string(split.views.size()) + ")");
    Camera camera{split.views[o.debugView].cameraToWorld, split.cameraAngleX, width, height};
    printPixelPaths(tracePixelPaths(*tracer, camera, settings, uint64_t(o.debugView), p.x, p.y), p.x, p.y,
                    size_t(o.debugView));
    return;
  }
  ProgressBar progress("render", int64_t(split.views.size()), "views");
  for (size_t v = 0; v < split.views.size(); ++v) {
    Camera camera{split.views[v].cameraToWorld, split.cameraAngleX, width, height};
    ViewBuffers buffers = renderGaussianView(*tracer, camera, settings, uint64_t(v));
    writeRenderedBuffers(o.output, split.views[v].filePath, buffers,
                         o.format == "png" ? ImageFormat::Png : ImageFormat::Exr);
    if (o.denoise) writeImage(denoisedRenderPath(o.output, split.views[v].filePath), denoiseView(buffers));
    progress.advance();
  }
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render", "Render a Gaussian scene (.ply, or a training run folder) from the cameras of a dataset split. Writes "
                "OUT/{render,diffuse,specular,depth,normal,roughness,f0}/NAME_####.exr with the dataset's file names. "
                "Specular is path-traced through the Gaussians (--bounces segments after the first, GGX sampled from "
                "the blended roughness and F0); render = diffuse + specular.");
  cmd->add_option("scene", o->scene,
                  "Gaussian scene (.ply in Glint's or the 3DGS layout), or a training run folder (scene.ply, and "
                  "config.json for the dataset and trace settings)")
      ->required();
  cmd->add_option("--dataset", o->dataset,
                  "Dataset whose cameras to use (only transforms_*.json is needed); default: the run's dataset");
  cmd->add_option("--split", o->split, "Camera split")->check(CLI::IsMember({"train", "test"}))->capture_default_str();
  cmd->add_option("-o,--output", o->output, "Output folder (required unless --debug-pixel)");
  cmd->add_option("--res", o->resolution, "Image size WIDTHxHEIGHT (default: that of the split's render images)");
  cmd->add_option("--spp", o->spp, "Rays per pixel, averaged")->check(CLI::Range(1, 1 << 16))->capture_default_str();
  cmd->add_flag("--no-jitter", o->noJitter,
                "Send every ray through the pixel centre instead of a random sub-pixel position");
  cmd->add_option("--seed", o->seed, "Seed of the sub-pixel jitter")->capture_default_str();
  o->trace.add(cmd);
  o->edits.add(cmd);
  cmd->add_option("--debug-pixel", o->debugPixel,
                  "X,Y: print the paths of this pixel of --view (segments, throughputs, blended values, hits), "
                  "traced exactly as in the full render, and write nothing");
  cmd->add_option("--view", o->debugView, "View index (in the split) for --debug-pixel")->capture_default_str();
  cmd->add_flag("--denoise", o->denoise,
                "Also write the final image denoised, OUT/render_denoised/NAME.exr (edge-avoiding a-trous filter "
                "guided by the diffuse, normal and depth buffers); the raw buffers are written as without it");
  cmd->add_flag("--force", o->force, "Write into a non-empty output folder");
  cmd->add_option("--format", o->format, "exr: linear float buffers; png: 8-bit, encoded as datasets store them "
                                         "(radiance through the filmic tonemap, as the viewer shows it; depth stays EXR)")
      ->check(CLI::IsMember({"exr", "png"}))
      ->capture_default_str();
  cmd->callback([o]() { runRender(*o); });
}

}  // namespace glint
