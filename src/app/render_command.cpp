// `glint render SCENE.ply --dataset D --split test -o OUT`: renders a Gaussian scene from
// the cameras of a dataset split into per-view buffers named like the dataset's.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "app/cli_parsing.h"
#include "app/commands.h"
#include "core/error.h"
#include "core/progress.h"
#include "io/image.h"
#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_renderer.h"
#include "scene/dataset.h"
#include "scene/gaussian_ply.h"

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
  float kernelPower = 3.0f;
  float alphaMin = 0.005f;
  float minTransmittance = 0.01f;
  std::string tracer = "fast";
  bool force = false;
};

// The buffers `glint render` writes (no specular until reflections exist).
constexpr Buffer kRenderedBuffers[] = {Buffer::Render, Buffer::Diffuse, Buffer::Depth,
                                       Buffer::Normal, Buffer::Roughness, Buffer::F0};

void checkOutputFolder(const fs::path& out, bool force) {
  if (!fs::exists(out) || force) return;
  if (!fs::is_directory(out)) throw Error(out.string(), "exists and is not a folder");
  if (!fs::is_empty(out) && !fs::exists(out / "render"))
    throw Error(out.string(), "folder is not empty and does not hold an earlier render; choose another -o folder "
                              "or pass --force");
}

// "test/render/render_0007" -> "OUT/depth/depth_0007.exr".
fs::path outputPath(const fs::path& out, const std::string& renderFilePath, Buffer buffer) {
  std::string relative = bufferFilePath(renderFilePath, buffer);
  fs::path p(relative);
  return out / p.parent_path().filename() / (p.filename().string() + ".exr");
}

void runRender(const RenderOptions& o) {
  TraceSettings trace;
  trace.kernelPower = o.kernelPower;
  trace.alphaMin = o.alphaMin;
  trace.minTransmittance = o.minTransmittance;

  GaussianScene scene = readGaussianPly(o.scene);
  Dataset dataset = Dataset::open(o.dataset, /*requireBuffers=*/false);
  const DatasetSplit& split = dataset.split(o.split);
  int width, height;
  if (!o.resolution.empty()) {
    Vec2i r = parseResolution(o.resolution, "--res");
    width = r.x, height = r.y;
  } else {
    std::optional<fs::path> first = dataset.findBufferFile(split.views[0], Buffer::Render);
    if (!first)
      throw Error(o.dataset, "has no " + o.split + " render images to take the image size from; pass --res WxH");
    Image image = readImage(*first);
    width = image.width, height = image.height;
  }
  checkOutputFolder(o.output, o.force);

  std::unique_ptr<GaussianTracer> tracer = makeGaussianTracer(o.tracer);
  auto start = std::chrono::steady_clock::now();
  tracer->build(scene, trace);
  double buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "glint render: %zu Gaussians, %s tracer built in %.3f s; %zu %s views at %dx%d, %d spp\n",
               scene.size(), tracer->name(), buildSeconds, split.views.size(), o.split.c_str(), width, height, o.spp);

  RenderSettings settings;
  settings.spp = o.spp;
  settings.jitter = !o.noJitter;
  settings.seed = o.seed;
  ProgressBar progress("render", int64_t(split.views.size()), "views");
  for (size_t v = 0; v < split.views.size(); ++v) {
    Camera camera{split.views[v].cameraToWorld, split.cameraAngleX, width, height};
    ViewBuffers buffers = renderGaussianView(*tracer, camera, settings, uint64_t(v));
    for (Buffer b : kRenderedBuffers) writeImage(outputPath(o.output, split.views[v].filePath, b), buffers[b]);
    progress.advance();
  }
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render", "Render a Gaussian scene (.ply) from the cameras of a dataset split. Writes "
                "OUT/{render,diffuse,depth,normal,roughness,f0}/NAME_####.exr with the dataset's file names; until "
                "reflections exist, render = diffuse.");
  cmd->add_option("scene", o->scene, "Gaussian scene (.ply in Glint's or the 3DGS layout)")->required();
  cmd->add_option("--dataset", o->dataset, "Dataset whose cameras to use (only transforms_*.json is needed)")
      ->required();
  cmd->add_option("--split", o->split, "Camera split")->check(CLI::IsMember({"train", "test"}))->capture_default_str();
  cmd->add_option("-o,--output", o->output, "Output folder")->required();
  cmd->add_option("--res", o->resolution, "Image size WIDTHxHEIGHT (default: that of the split's render images)");
  cmd->add_option("--spp", o->spp, "Rays per pixel, averaged")->check(CLI::Range(1, 1 << 16))->capture_default_str();
  cmd->add_flag("--no-jitter", o->noJitter, "Send every ray through the pixel centre instead of a random sub-pixel position");
  cmd->add_option("--seed", o->seed, "Seed of the sub-pixel jitter")->capture_default_str();
  cmd->add_option("--kernel-power", o->kernelPower, "Generalised Gaussian exponent p (1 = ordinary Gaussian)")
      ->check(CLI::Range(0.25, 16.0))
      ->capture_default_str();
  cmd->add_option("--alpha-min", o->alphaMin, "Hits with alpha below this are ignored; sets the proxy size")
      ->check(CLI::Range(1e-6, 0.5))
      ->capture_default_str();
  cmd->add_option("--min-transmittance", o->minTransmittance, "Compositing stops below this transmittance")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--tracer", o->tracer, "Gaussian tracer: " + [] {
    std::string names;
    for (const std::string& n : gaussianTracerNames()) names += (names.empty() ? "" : ", ") + n;
    return names;
  }())->capture_default_str();
  cmd->add_flag("--force", o->force, "Write into a non-empty output folder");
  cmd->callback([o]() { runRender(*o); });
}

}  // namespace glint
