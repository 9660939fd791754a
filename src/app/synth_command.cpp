// `glint synth SCENE -o OUT`: turns a built-in or glTF scene into a dataset with exact buffers.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/cli_parsing.h"
#include "app/commands.h"
#include "app/thread_flag.h"
#include "core/activity.h"
#include "core/cluster.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "edit/edit_file.h"
#include "io/image.h"
#include "synth/builtin_scenes.h"
#include "synth/camera_paths.h"
#include "synth/capture_generator.h"
#include "synth/dataset_generator.h"
#include "synth/gltf_import.h"
#include "synth_edit/mesh_edits.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

struct SynthOptions {
  std::string scene;
  std::string output;
  int train = 100;
  int test = 20;
  std::string resolution = "256x192";
  int spp = 256;
  int testSpp = 0;
  int bounces = 6;
  uint64_t seed = 0;
  std::string format = "exr";
  float exposure = 1.0f;
  std::string environment;
  float environmentIntensity = 1.0f;
  std::string edits;
  int threads = 0;
  bool force = false;
  std::string layout = "transforms";
  int holdout = Dataset::kDefaultHoldout;
  std::string degrade = "none";
  std::vector<std::string> degradeOnly;
  int points = 4000;
};

std::string lowercaseExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

MeshScene loadScene(const std::string& spec) {
  const std::string prefix = "builtin:";
  if (spec.rfind(prefix, 0) == 0) return makeBuiltinScene(spec.substr(prefix.size()));
  fs::path path(spec);
  std::string ext = lowercaseExtension(path);
  if (ext != ".gltf" && ext != ".glb")
    throw Error(spec, "a scene is builtin:NAME or a .gltf/.glb file (unknown extension '" + ext + "')");
  ActivityScope activity("importing " + path.string());
  return loadGltfScene(path);
}

bool hasAnyLight(const MeshScene& scene) {
  if (!scene.lights.empty() || !scene.environment.isBlack()) return true;
  for (const Material& m : scene.materials)
    if (maxComponent(m.emission) > 0) return true;
  return false;
}

void applyEnvironment(MeshScene& scene, const SynthOptions& o) {
  if (!o.environment.empty()) {
    fs::path path(o.environment);
    std::string ext = lowercaseExtension(path);
    if (ext == ".exr" || ext == ".tif" || ext == ".tiff") {
      scene.environment.map = readImage(path);
      if (scene.environment.map.channels < 3) throw Error(o.environment, "an environment map needs 3 channels (RGB)");
      for (float v : scene.environment.map.pixels)
        if (!std::isfinite(v) || v < 0) throw Error(o.environment, "the environment map has negative or non-finite values");
    } else {
      scene.environment.constant = parseColor(o.environment, "--env");
      scene.environment.map = Image();
    }
  }
  scene.environment.intensity = o.environmentIntensity;
  if (!hasAnyLight(scene)) {
    std::fprintf(stderr, "glint synth: the scene has no lights; using a uniform white environment (set one with --env)\n");
    scene.environment.constant = Rgb(1.0f);
  }
}

// Applies an edit file to the scene's meshes and spheres (docs/edit-files.md). The camera
// rig is fixed from the unedited scene first, so an edited dataset has exactly the cameras
// of the unedited one even when the edit changes the scene's bounds.
void applyEditFile(MeshScene& scene, const std::string& path) {
  ActivityScope activity("applying the edits of " + path);
  EditDocument document = readEditFile(path);
  scene.cameras = sceneCameraRig(scene);
  scene.hasCameraRig = true;
  MeshEditReport report = applyMeshEdits(document, scene);
  std::fprintf(stderr, "glint synth: edits from %s\n%s", path.c_str(), formatMeshEditReport(report).c_str());
  scene.validate(path);  // e.g. an edit that deletes every node
}

// Refuses to write into a folder with unrelated content, so nothing a user made is lost.
// A folder holding the other layout is refused even with --force: mixing them would leave
// a folder that opens as neither cleanly.
void checkOutputFolder(const fs::path& out, bool force, bool capture) {
  if (!fs::exists(out)) return;
  if (!fs::is_directory(out)) throw Error(out.string(), "exists and is not a folder");
  bool empty = fs::is_empty(out);
  bool isTransforms = fs::exists(out / "transforms_train.json");
  bool isCapture = fs::exists(out / "capture.json") && fs::exists(out / "sparse" / "0");
  if (!empty && !isTransforms && !isCapture)
    throw Error(out.string(), "folder is not empty and is not a Glint dataset; choose another -o folder");
  if ((isTransforms && capture) || (isCapture && !capture))
    throw Error(out.string(), std::string("already holds a dataset of the ") + (capture ? "transforms" : "capture") +
                                  " layout; choose another -o folder");
  if (!empty && !force) throw Error(out.string(), "already holds a dataset; pass --force to overwrite it");
}

void runSynth(const SynthOptions& o) {
  SynthSettings settings;
  Vec2i res = parseResolution(o.resolution, "--res");
  settings.width = res.x;
  settings.height = res.y;
  settings.trainViews = o.train;
  settings.testViews = o.test;
  settings.spp = o.spp;
  settings.testSpp = o.testSpp;
  settings.bounces = o.bounces;
  settings.seed = o.seed;
  settings.format = o.format == "png" ? ImageFormat::Png : (o.format == "tiff" ? ImageFormat::Tiff : ImageFormat::Exr);
  settings.exposure = o.exposure;

  MeshScene scene = loadScene(o.scene);
  // The lights are chosen before edits, so a deleted emitter never swaps in a default environment.
  applyEnvironment(scene, o);
  if (!o.edits.empty()) applyEditFile(scene, o.edits);
  const bool capture = o.layout == "capture";
  if (!capture && o.degrade != "none")
    throw Error("--degrade", "degraded priors are written in the capture layout only (add --layout capture)");
  if (!o.degradeOnly.empty() && o.degrade == "none")
    throw Error("--degrade-only", "names the priors that --degrade degrades: give --degrade network or monocular too");
  // Rank 0 alone looks at the folder; the generators make their folders on rank 0 and wait
  // for it before any rank writes.
  if (cluster::isRoot()) checkOutputFolder(o.output, o.force, capture);

  ThreadLimit limit(o.threads);
  auto start = std::chrono::steady_clock::now();
  if (capture) {
    CaptureSynthSettings captureSettings;
    captureSettings.holdout = o.holdout;
    captureSettings.priorErrors = o.degrade == "network"     ? PriorErrors::Network
                                  : o.degrade == "monocular" ? PriorErrors::Monocular
                                                             : PriorErrors::None;
    captureSettings.sparsePoints = o.points;
    for (const std::string& name : o.degradeOnly) captureSettings.degradedPriors.push_back(*bufferFromName(name));
    const int testViews = o.holdout > 1 ? (o.train + o.holdout - 1) / o.holdout : 0;
    std::string priors = o.degrade == "none" ? "exact" : o.degrade + "-like";
    if (!o.degradeOnly.empty()) {
      priors += " (only " + o.degradeOnly[0];
      for (size_t k = 1; k < o.degradeOnly.size(); ++k) priors += ", " + o.degradeOnly[k];
      priors += ")";
    }
    std::fprintf(stderr,
                 "glint synth: %s -> %s (capture): %d views, %d held out (every %d-th) at %d spp, the rest at %d "
                 "spp, %dx%d, %d bounces, %s priors, %d threads\n",
                 o.scene.c_str(), o.output.c_str(), o.train, testViews, o.holdout, settings.testSamplesPerPixel(),
                 o.spp, res.x, res.y, o.bounces, priors.c_str(), maxThreads());
    generateCapture(scene, settings, captureSettings, o.output);
  } else {
    std::fprintf(stderr,
                 "glint synth: %s -> %s: %d train views at %d spp + %d test views at %d spp, %dx%d, %d bounces, %d "
                 "threads\n",
                 o.scene.c_str(), o.output.c_str(), o.train, o.spp, o.test, settings.testSamplesPerPixel(), res.x,
                 res.y, o.bounces, maxThreads());
    generateDataset(scene, settings, o.output);
  }
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "glint synth: wrote %s in %s\n", o.output.c_str(), formatDuration(seconds).c_str());
}

}  // namespace

void addSynthCommand(CLI::App& app) {
  auto options = std::make_shared<SynthOptions>();
  CLI::App* cmd = app.add_subcommand(
      "synth",
      "Render a scene with the reference path tracer into a dataset with exact buffers: render, diffuse, specular, "
      "depth, normal, roughness, F0 for every view, cameras in transforms_{train,test}.json, and "
      "point_cloud_dense.ply from the training depth buffers. With --layout capture: a real-capture-like folder "
      "(docs/capture-format.md) of tonemapped JPEG photographs, priors and a COLMAP model of the true cameras.");
  cmd->add_option("scene", options->scene, "builtin:spheres, builtin:room, builtin:gallery (textured for COLMAP), or a "
                                           ".gltf/.glb file")
      ->required();
  cmd->add_option("-o,--output", options->output, "Output dataset folder (created if needed)")->required();
  cmd->add_option("--train", options->train, "Number of training views (on the training camera path)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--test", options->test, "Number of test views (on a different camera path)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--res", options->resolution, "Image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--spp", options->spp, "Path samples per pixel for render/diffuse/specular")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  cmd->add_option("--test-spp", options->testSpp,
                  "Path samples per pixel of the test views (0 = --spp). The test views are the ground truth of "
                  "`glint eval`, and their own noise counts as error there: rendering them closer to convergence "
                  "(e.g. 1024) makes the scores measure the reconstruction")
      ->check(CLI::Range(0, 1 << 20))
      ->capture_default_str();
  cmd->add_option("--bounces", options->bounces,
                  "Maximum surface interactions per path (1 = direct light only); Russian roulette after 3")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_option("--seed", options->seed, "Random seed; the same seed gives the same dataset")->capture_default_str();
  cmd->add_option("--format", options->format,
                  "Buffer encoding: exr (float32), tiff (16-bit float) or png (8-bit, radiance tonemapped; depth "
                  "stays EXR)")
      ->check(CLI::IsMember({"exr", "tiff", "png"}))
      ->capture_default_str();
  cmd->add_option("--exposure", options->exposure, "Multiplies render, diffuse and specular (the paper's data uses 3.5)")
      ->check(CLI::Range(1e-6, 1e6))
      ->capture_default_str();
  cmd->add_option("--env", options->environment,
                  "Environment light: a radiance value ('1' or '1,0.9,0.8') or an equirectangular .exr/.tiff map "
                  "(Y up). Scenes without any light get a white environment of 1");
  cmd->add_option("--env-intensity", options->environmentIntensity, "Multiplies the environment")
      ->check(CLI::Range(0.0, 1e6))
      ->capture_default_str();
  cmd->add_option("--edits", options->edits,
                  "Edit file (docs/edit-files.md) applied to the scene before rendering: shapes select whole meshes "
                  "and spheres by the centre of their bounds, material operations change their glTF materials. "
                  "Cameras stay those of the unedited scene")
      ->check(CLI::ExistingFile);
  addThreadsFlag(cmd, &options->threads);
  cmd->add_flag("--force", options->force, "Overwrite an existing dataset in the output folder");
  cmd->add_option("--layout", options->layout,
                  "transforms: the synthetic layout (docs/data-format.md). capture: a capture folder "
                  "(docs/capture-format.md) of the --train views along the training path: images/view_####.jpg "
                  "(8-bit, filmic tonemapped), priors/ in the paper's encodings, sparse/0 (COLMAP text model of the "
                  "true cameras, --points points from the training depth) and capture.json; --test is not used")
      ->check(CLI::IsMember({"transforms", "capture"}))
      ->capture_default_str();
  cmd->add_option("--holdout", options->holdout,
                  "Capture layout: every N-th view from the first is a test view of `glint train --holdout N` (LLFF "
                  "convention) and is rendered at --test-spp; 1 = no test views")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--degrade", options->degrade,
                  "Capture layout: none writes the exact buffers as priors; network degrades them like a predictor's "
                  "(blur 1 px, per-view depth scale 0.95-1.05 and offset +-0.1 m, depth noise 0.01 m, 4 degree "
                  "normal tilt, roughness 0.8 (r + noise 0.03) + 0.1; per 320 px of width, see README). The "
                  "photographs stay exact. monocular is a second kind (docs/captures.md): blur 0.7 px and 8-bit noise on "
                  "diffuse and specular, a non-affine per-view depth warp (power 0.85-1.15, a smooth 4% scale field, "
                  "edges blurred, 0.5% noise), 3 degrees of per-pixel normal noise plus a 1.5 degree tilt per view, "
                  "roughness + 0.05 + noise 0.05, and metalness instead of F0 (per 160 px of width)")
      ->check(CLI::IsMember({"none", "network", "monocular"}))
      ->capture_default_str();
  cmd->add_option("--degrade-only", options->degradeOnly,
                  "Capture layout: degrade only these priors (diffuse, specular, depth, normal, roughness, f0; "
                  "default all) and write the others exact, to measure what each one's error costs")
      ->check(CLI::IsMember({"diffuse", "specular", "depth", "normal", "roughness", "f0"}))
      ->delimiter(',');
  cmd->add_option("--points", options->points, "Capture layout: sparse points in points3D.txt")
      ->check(CLI::Range(1, 10000000))
      ->capture_default_str();
  cmd->callback([options]() { runSynth(*options); });
}

}  // namespace glint
