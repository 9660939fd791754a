// `glint render SCENE.ply|RUN --dataset D --split test -o OUT`: renders a Gaussian scene (or a
// training run's) from the cameras of a dataset split into per-view buffers named like the
// dataset's, or along a camera path (--path) into numbered frames and an MP4.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <future>

#include "app/cli_parsing.h"
#include "app/commands.h"
#include "app/dataset_flags.h"
#include "app/rendered_buffers.h"
#include "app/scene_edits.h"
#include "app/scene_source.h"
#include "app/thread_flag.h"
#include "app/trace_flags.h"
#include "app/video_encoder.h"
#include "core/activity.h"
#include "core/cluster.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "io/image.h"
#include "raytrace/gaussian_tracer.h"
#include "render/camera_path.h"
#include "render/denoise.h"
#include "render/gaussian_renderer.h"
#include "render/progressive_render.h"
#include "scene/buffer_codec.h"
#include "scene/dataset.h"
#include "scene/view_sharing.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

struct RenderOptions {
  std::string scene;
  std::string inputLayout = "auto";
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
  bool progressive = false;  // passes of 1, 1, 2, 4, ... samples, files rewritten after each
  std::string path;          // "orbit", "spiral", "dataset-test": frames instead of the split's views
  int frames = 0;            // of the path; 0: 120, or the test views for dataset-test
  int fps = 30;
  bool noVideo = false;
  std::string debugPixel;  // "x,y": print that pixel's paths instead of rendering
  int debugView = 0;
  int threads = 0;
  DatasetFlags reading;  // --downscale
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
        std::printf("    hit %zu: Gaussian %u t %.4f alpha %.4f\n", h, hit.id, hit.t, hit.alpha);
      }
      if (seg.hits.hits.size() > shown) std::printf("    ... %zu more hits\n", seg.hits.hits.size() - shown);
    }
  }
}

ImageFormat outputFormat(const RenderOptions& o) { return o.format == "png" ? ImageFormat::Png : ImageFormat::Exr; }

// The output folder must be new, empty, or hold an earlier render of the same kind (its
// `marker` subfolder: "render" for views, "path" for camera-path frames).
void checkOutputFolder(const fs::path& out, bool force, const char* marker) {
  if (!fs::exists(out) || force) return;
  if (!fs::is_directory(out)) throw Error(out.string(), "exists and is not a folder");
  if (!fs::is_empty(out) && !fs::exists(out / marker))
    throw Error(out.string(), "folder is not empty and does not hold an earlier render; choose another -o folder "
                              "or pass --force");
}

// Renders this rank's part of one view (all of it, or its band of rows), in one pass or
// progressively, and hands every result to write on the rank that writes the view's files
// (the progressive passes' means too, so the files on disk improve while the render runs).
// Banded, rank 0 joins the bands and writes; the other ranks only render.
void renderView(const RenderOptions& o, const GaussianTracer& tracer, const Camera& camera,
                const RenderSettings& settings, const ViewShare& share, uint64_t viewKey,
                const ProgressivePassCallback& write) {
  RenderSettings mine = settings;
  const cluster::Share rows = share.myRows(camera.height);
  mine.rowBegin = int(rows.begin);
  mine.rowEnd = int(rows.end);
  ProgressivePassCallback handOut = [&](const ViewBuffers& buffers, int samples) {
    if (!share.banded()) return write(buffers, samples);
    ViewBuffers whole = joinBandsOnRoot(buffers);
    if (cluster::isRoot()) write(whole, samples);
  };
  if (o.progressive)
    renderProgressively(tracer, camera, mine, viewKey, handOut);
  else
    handOut(renderGaussianView(tracer, camera, mine, viewKey), mine.spp);
}

// The final image as the viewer shows it: the filmic tonemap of the dataset's 8-bit files.
void writeFramePng(const fs::path& path, const Image& radiance) {
  writeImage(path, encodeBuffer(radiance, Buffer::Render, ImageFormat::Png));
}

// Renders frames along the camera path into OUT/path/frame_####.png (and, with --denoise,
// OUT/path_denoised/), then encodes OUT/path.mp4 from the shown frames when ffmpeg exists.
// Under MPI the frames are shared like views (ViewShare), and rank 0 encodes the video once
// every rank has written its frames.
void renderCameraPath(const RenderOptions& o, const GaussianTracer& tracer, const RenderSettings& settings,
                      const std::vector<Mat4>& path, const Camera& intrinsics) {
  fs::path framesDir = fs::path(o.output) / "path", denoisedDir = fs::path(o.output) / "path_denoised";
  if (cluster::isRoot()) {
    fs::create_directories(framesDir);
    if (o.denoise) fs::create_directories(denoisedDir);
  }
  cluster::barrier();  // the folders exist before any rank writes into them
  const ViewShare share(path.size(), /*allowBands=*/true);
  char name[32];
  ProgressBar progress(share.progressLabel("render " + o.path), int64_t(share.myCount()), "frames");
  for (size_t f = 0; f < path.size(); ++f) {
    if (!share.mine(f)) continue;
    std::snprintf(name, sizeof(name), "frame_%04zu.png", f);
    Camera camera = intrinsics;
    camera.cameraToWorld = path[f];
    auto write = [&](const ViewBuffers& buffers, int /*samples*/) {
      writeFramePng(framesDir / name, buffers[Buffer::Render]);
      if (o.denoise) writeFramePng(denoisedDir / name, denoiseView(buffers));
    };
    renderView(o, tracer, camera, settings, share, uint64_t(f), write);
    progress.advance();
  }
  progress.finish();
  cluster::barrier();  // every frame is on disk
  fs::path video = fs::path(o.output) / "path.mp4";
  if (o.noVideo || !cluster::isRoot()) return;
  std::optional<fs::path> ffmpeg = findFfmpeg();
  if (!ffmpeg) {
    std::fprintf(stderr, "glint render: ffmpeg is not installed, so no %s (the frames are in %s)\n",
                 video.string().c_str(), framesDir.string().c_str());
    return;
  }
  encodeVideo(*ffmpeg, (o.denoise ? denoisedDir : framesDir) / "frame_%04d.png", o.fps, video);
  std::fprintf(stderr, "glint render: wrote %s (%zu frames at %d fps)\n", video.string().c_str(), path.size(),
               o.fps);
}

void runRender(const RenderOptions& o) {
  if (o.output.empty() && o.debugPixel.empty()) throw Error("glint render", "needs an output folder: pass -o OUT");
  ThreadLimit threads(o.threads);
  SceneSource source = loadSceneSource(o.scene, parseInputLayout(o.inputLayout));
  GaussianScene& scene = source.scene;
  const SceneRendering rendering = o.trace.resolve(source.settings);
  const TraceSettings& trace = rendering.trace;
  fs::path datasetPath = o.dataset.empty() ? fs::path(source.settings.dataset) : fs::path(o.dataset);
  if (datasetPath.empty())
    throw Error(o.scene, "names no dataset to take the cameras from (only a training run's config.json can): "
                         "pass --dataset");

  std::optional<CameraPathKind> pathKind;
  if (!o.path.empty()) {
    pathKind = cameraPathFromName(o.path);
    if (!o.debugPixel.empty()) throw Error("--path", "renders frames; it cannot be combined with --debug-pixel");
  }
  Dataset dataset = Dataset::open(datasetPath, o.reading.resolve(source.settings, /*requireBuffers=*/false));
  // dataset-test walks through the test cameras whatever --split says.
  const DatasetSplit& split = dataset.split(pathKind == CameraPathKind::DatasetTest ? "test" : o.split);
  // Each view renders at its own size and intrinsics, or every one resized to --res.
  std::optional<Vec2i> resolution;
  if (!o.resolution.empty()) resolution = parseResolution(o.resolution, "--res");
  if (!resolution && split.width <= 0)
    throw Error(datasetPath.string(),
                "has no " + split.name + " render images to take the image size from; pass --res WxH");
  auto viewCamera = [&](size_t v) {
    const Camera& camera = split.camera(v);
    return resolution ? camera.resized(resolution->x, resolution->y) : camera;
  };
  const Camera first = viewCamera(0);
  // Rank 0 alone looks at the folder, before any rank writes into it (the barrier below).
  if (o.debugPixel.empty() && cluster::isRoot()) checkOutputFolder(o.output, o.force, pathKind ? "path" : "render");

  // The frames of the camera path, through the split's cameras with the first one's intrinsics.
  std::vector<Mat4> path;
  if (pathKind) {
    for (const DatasetView& view : split.views) path.push_back(view.camera.cameraToWorld);
    int frames = o.frames > 0 ? o.frames : (*pathKind == CameraPathKind::DatasetTest ? int(path.size()) : 120);
    path = makeCameraPath(*pathKind, path, frames);
  }
  const size_t imageCount = pathKind ? path.size() : split.views.size();

  auto start = std::chrono::steady_clock::now();
  double workRays = 0;
  for (size_t v = 0; v < split.views.size(); ++v) {
    const Camera camera = viewCamera(v);
    workRays += double(camera.width) * camera.height * o.spp * (1 + rendering.path.bounces);
  }
  if (pathKind) workRays *= double(path.size()) / double(split.views.size());
  std::unique_ptr<GaussianTracer> tracer =
      o.edits.prepareTracer(scene, trace, rendering.path, rendering.tracer, first, workRays, "glint render");
  double buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr,
               "glint render: %zu Gaussians, %s tracer ready in %.3f s (p = %g, alpha_min = %g, "
               "min_transmittance = %g, %d bounces); %zu %s at %dx%d%s, %d spp%s\n",
               scene.size(), tracer->name(), buildSeconds, trace.kernelPower, trace.alphaMin, trace.minTransmittance,
               rendering.path.bounces, imageCount, (pathKind ? o.path + " frames" : split.name + " views").c_str(),
               first.width, first.height, resolution || pathKind ? "" : " (the first view's size)", o.spp,
               o.progressive ? " (progressive)" : "");

  RenderSettings settings;
  settings.spp = o.spp;
  settings.jitter = !o.noJitter;
  settings.seed = o.seed;
  settings.path = rendering.path;
  if (!o.debugPixel.empty()) {
    Vec2i p = parsePixel(o.debugPixel, "--debug-pixel");
    if (o.debugView < 0 || size_t(o.debugView) >= split.views.size())
      throw Error("--view", std::to_string(o.debugView) + " is not a view of the " + o.split + " split (it has " +
                                std::to_string(split.views.size()) + ")");
    const Camera camera = viewCamera(size_t(o.debugView));
    if (p.x < 0 || p.y < 0 || p.x >= camera.width || p.y >= camera.height)
      throw Error("--debug-pixel", o.debugPixel + " lies outside the " + std::to_string(camera.width) + "x" +
                                       std::to_string(camera.height) + " image");
    printPixelPaths(tracePixelPaths(*tracer, camera, settings, uint64_t(o.debugView), p.x, p.y), p.x, p.y,
                    size_t(o.debugView));
    return;
  }
  if (pathKind) {
    renderCameraPath(o, *tracer, settings, path, first);
    return;
  }
  if (cluster::isRoot()) {
    std::vector<fs::path> folders = {o.output};
    for (Buffer b : kRenderedBuffers)
      folders.push_back(renderedBufferPath(o.output, split.views[0].filePath, b, outputFormat(o)).parent_path());
    if (o.denoise) folders.push_back(denoisedRenderPath(o.output, split.views[0].filePath).parent_path());
    for (const fs::path& folder : folders) fs::create_directories(folder);
  }
  cluster::barrier();  // the folders exist before any rank writes into them
  const ViewShare share(split.views.size(), /*allowBands=*/true);
  ProgressBar progress(share.progressLabel("render"), int64_t(share.myCount()), "views");
  // A view's files are written on another thread while the next view renders (on the GPU
  // the writing would otherwise take as long as the rendering); one write at a time, in
  // order, and a failed write stops the command at the next view.
  std::future<void> writing;
  auto finishWriting = [&] {
    if (writing.valid()) writing.get();
  };
  for (size_t v = 0; v < split.views.size(); ++v) {
    if (!share.mine(v)) continue;
    ActivityScope activity("rendering view " + split.views[v].filePath);
    const Camera camera = viewCamera(v);
    auto write = [&, v](const ViewBuffers& buffers, int /*samples*/) {
      finishWriting();
      writing = std::async(std::launch::async, [&o, &split, v, buffers] {
        writeRenderedBuffers(o.output, split.views[v].filePath, buffers, outputFormat(o));
        if (o.denoise) writeImage(denoisedRenderPath(o.output, split.views[v].filePath), denoiseView(buffers));
      });
    };
    renderView(o, *tracer, camera, settings, share, uint64_t(v), write);
    progress.advance();
  }
  finishWriting();
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
                  "config.json for the dataset and the trace and path settings it was trained with)")
      ->required();
  addInputLayoutFlag(*cmd, o->inputLayout);
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
  o->reading.add(cmd, /*withBackground=*/false);
  cmd->add_option("--debug-pixel", o->debugPixel,
                  "X,Y: print the paths of this pixel of --view (segments, throughputs, blended values, hits), "
                  "traced exactly as in the full render, and write nothing");
  cmd->add_option("--view", o->debugView, "View index (in the split) for --debug-pixel")->capture_default_str();
  cmd->add_flag("--denoise", o->denoise,
                "Also write the final image denoised, OUT/render_denoised/NAME.exr (edge-avoiding a-trous filter "
                "guided by the diffuse, normal and depth buffers); the raw buffers are written as without it");
  cmd->add_flag("--progressive", o->progressive,
                "Trace each view (or frame) in passes of 1, 1, 2, 4, ... samples up to --spp, rewriting its files "
                "with the mean so far after every pass: look at them while the render runs, or stop it early; the "
                "end result is the render of --spp samples");
  cmd->add_option("--path", o->path,
                  "Render a camera path instead of the split's views: orbit (one turn around the point the "
                  "split's cameras look at, at their mean distance and height), spiral (two turns rising from the "
                  "lowest camera to the highest and back), dataset-test (through the test cameras in order). Writes "
                  "OUT/path/frame_####.png (the final image, filmic tonemap), OUT/path_denoised/ with --denoise, "
                  "and OUT/path.mp4 when ffmpeg is installed")
      ->check(CLI::IsMember({"orbit", "spiral", "dataset-test"}));
  cmd->add_option("--frames", o->frames,
                  "Frames of --path (default: 120; for dataset-test the number of test views, and other counts "
                  "interpolate smoothly between the test cameras)")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--fps", o->fps, "Frames per second of the --path video")->check(CLI::Range(1, 240))->capture_default_str();
  cmd->add_flag("--no-video", o->noVideo, "With --path, write the frames only (no MP4)");
  cmd->add_flag("--force", o->force, "Write into a non-empty output folder");
  addThreadsFlag(cmd, &o->threads);
  cmd->add_option("--format", o->format, "exr: linear float buffers; png: 8-bit, encoded as datasets store them "
                                         "(radiance through the filmic tonemap, as the viewer shows it; depth stays EXR)")
      ->check(CLI::IsMember({"exr", "png"}))
      ->capture_default_str();
  cmd->callback([o]() { runRender(*o); });
}

}  // namespace glint
