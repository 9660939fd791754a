// `glint export RUN_OR_PLY --format 3dgs|glint|spz|compressed-ply -o OUT`: rewrites a Gaussian
// scene in the standard 3D Gaussian Splatting layout (for the wider ecosystem's viewers), in
// the compressed forms splat users share, or in Glint's; optionally with the reflections
// baked into SH colours, without the far field, or cropped to a box.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "app/bake_flags.h"
#include "app/cli_parsing.h"
#include "app/commands.h"
#include "app/export_filters.h"
#include "app/output_file.h"
#include "app/scene_source.h"
#include "app/thread_flag.h"
#include "core/error.h"
#include "core/parallel.h"
#include "scene/dataset.h"
#include "scene/compressed_ply_writer.h"
#include "scene/gaussian_ply.h"
#include "scene/spz_writer.h"

namespace glint {

namespace {

struct ExportOptions {
  std::string input;
  std::string output;
  std::string format = "3dgs";
  std::string inputLayout = "auto";
  bool force = false;
  // 3DGS colour and view dependence.
  std::string colour = "display";
  float exposure = 1.0f;
  int shDegree = -1;  // -1: 3 for 3dgs (INRIA's layout) or when baking, else 0
  BakeFlags bake;
  int threads = 0;
  // Which Gaussians to write.
  bool keepFarField = false;
  bool dropFarField = false;
  float farFieldRadius = kDefaultFarFieldRadius;
  std::string dataset;
  std::string crop;
};

// The training cameras' sphere for the far-field cut: from --dataset, else the run's
// dataset. Nullopt (and a line saying why) when no cameras can be had.
std::optional<SceneSphere> trainingCameras(const ExportOptions& o, const SceneSource& source) {
  const bool explicitDataset = !o.dataset.empty();
  const std::string path = explicitDataset ? o.dataset : source.settings.dataset;
  if (path.empty()) {
    std::fprintf(stderr, "glint export: far-field Gaussians kept: no training cameras known (a .ply without "
                         "--dataset)\n");
    return std::nullopt;
  }
  try {
    Dataset dataset = Dataset::open(path, /*requireBuffers=*/false, source.settings.holdout);
    SceneSphere sphere = sceneSphere(dataset.split("train"));
    if (sphere.radius <= 0.0f) throw Error(path, "has a single training camera position: no scene extent");
    return sphere;
  } catch (const Error& e) {
    if (explicitDataset) throw;
    // The run's dataset may have moved since training: export all rather than fail.
    std::fprintf(stderr, "glint export: far-field Gaussians kept: the run's training cameras cannot be read (%s); "
                         "pass --dataset\n", e.what());
    return std::nullopt;
  }
}

// Which Gaussians the options keep, saying how many go.
std::vector<bool> keptGaussians(const ExportOptions& o, bool splatFormat, const SceneSource& source) {
  const GaussianScene& scene = source.scene;
  std::vector<bool> keep(scene.size(), true);
  const bool dropFarField = o.dropFarField || (splatFormat && !o.keepFarField);
  if (dropFarField) {
    if (std::optional<SceneSphere> cameras = trainingCameras(o, source)) {
      std::vector<bool> near = nearTheCameras(scene, *cameras, o.farFieldRadius);
      std::fprintf(stderr, "glint export: dropped %zu far-field Gaussians (centre more than %g x %.3g = %.3g from "
                           "the training cameras' centre; --keep-far-field keeps them)\n",
                   countDropped(near), double(o.farFieldRadius), double(cameras->radius),
                   double(o.farFieldRadius) * double(cameras->radius));
      for (size_t i = 0; i < keep.size(); ++i) keep[i] = keep[i] && near[i];
    }
  }
  if (!o.crop.empty()) {
    std::vector<bool> inside = insideBox(scene, parseBox(o.crop, "--crop"));
    std::fprintf(stderr, "glint export: dropped %zu Gaussians outside the --crop box\n", countDropped(inside));
    for (size_t i = 0; i < keep.size(); ++i) keep[i] = keep[i] && inside[i];
  }
  return keep;
}

// A splat format stores one colour per Gaussian (and its SH): without a bake, the
// reflections Glint traces are not in it, and mirrors and metals show their diffuse colour,
// which is dark. Says so when the scene has such Gaussians.
void warnAboutUnbakedReflections(const GaussianScene& scene) {
  constexpr float kReflectiveF0 = 0.3f;  // well above dielectrics' 0.02-0.08: metals and mirrors
  size_t reflective = 0;
  for (const Rgb& f0 : scene.f0) reflective += maxComponent(f0) > kReflectiveF0;
  if (reflective == 0) return;
  std::fprintf(stderr,
               "glint export: warning: %zu of %zu Gaussians are reflective (F0 above %g: metal or mirror), and "
               "without --bake-reflections a plain splat viewer shows only their diffuse colour, dark or black for "
               "chrome and mirrors\n",
               reflective, scene.size(), double(kReflectiveF0));
}

void runExport(const ExportOptions& o) {
  const bool glintLayout = o.format == "glint", threeDgs = o.format == "3dgs";
  if (glintLayout && (o.colour != "display" || o.exposure != 1.0f || o.shDegree > 0 || o.bake.given()))
    throw Error("command line", "--colour, --exposure, --sh-degree and --bake-reflections do not apply to --format "
                                "glint (Glint's layout stores the linear diffuse colour and materials)");
  if (o.colour == "linear" && !(threeDgs && !o.bake.given()))
    throw Error("--colour linear", "applies to --format 3dgs without --bake-reflections only (spz, compressed-ply "
                                   "and baked colours are display-referred)");
  if (o.keepFarField && o.dropFarField) throw Error("command line", "give --keep-far-field or --drop-far-field, not both");
  o.bake.check();
  // Refuse what can be refused before reading a large scene.
  refuseExistingOutput(o.output, o.force);
  if (!o.crop.empty()) parseBox(o.crop, "--crop");
  // 3dgs writes INRIA's layout, all 45 f_rest (zeros without a bake: Glint's diffuse colour
  // has no view dependence), which every 3DGS loader expects.
  const int shDegree = o.shDegree >= 0 ? o.shDegree : (o.bake.given() || threeDgs ? 3 : 0);

  SceneSource source = loadSceneSource(o.input, parseInputLayout(o.inputLayout));
  GaussianScene& scene = source.scene;
  // The bake traces the whole scene, far field included: reflections show it.
  std::optional<SplatColour> colour;
  if (o.bake.given()) colour = o.bake.bake(scene, source.settings, shDegree, o.dataset, o.exposure);
  else if (!glintLayout && !threeDgs) colour = displayColour(scene, o.exposure).withDegree(shDegree);
  const std::vector<bool> keep = keptGaussians(o, !glintLayout, source);
  scene.filter(keep);
  if (colour) colour->filter(keep);
  if (!glintLayout && !o.bake.given()) warnAboutUnbakedReflections(scene);

  std::string written;
  if (glintLayout) {
    writeGaussianPly(o.output, scene);
  } else if (threeDgs) {
    ThreeDgsExportOptions options;
    options.colour.colour = o.colour == "linear" ? SplatColourSpace::Linear : SplatColourSpace::Display;
    options.colour.exposure = o.exposure;
    options.shDegree = shDegree;
    if (colour) options.baked = &*colour;
    exportGaussianPly3dgs(o.output, scene, options);
  } else if (o.format == "spz") {
    writeSpz(o.output, scene, *colour);
  } else {
    writeCompressedPly(o.output, scene, *colour);
  }
  if (!glintLayout) {
    char details[128];
    std::snprintf(details, sizeof(details), ", %s colour%s, exposure %g, SH degree %d",
                  o.colour == "linear" ? "linear" : "display", o.bake.given() ? " with baked reflections" : "",
                  double(o.exposure), shDegree);
    written = details;
  }
  std::fprintf(stderr, "glint export: %s (%s layout) -> %s (%s%s), %zu Gaussians\n", source.sceneFile.string().c_str(),
               plyLayoutName(source.import.layout), o.output.c_str(), o.format.c_str(), written.c_str(),
               scene.size());
}

}  // namespace

void addExportCommand(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Write a Gaussian scene for other tools. '3dgs' is the standard 3D Gaussian Splatting PLY layout "
      "(x y z nx ny nz f_dc_0..2 f_rest_* opacity scale_0..2 rot_0..3) that splat viewers open: colour as the SH DC "
      "term, display-referred by default, normals, roughness and F0 dropped, and the far-field Gaussians left out. "
      "'spz' (Niantic's gzip-compressed .spz, about a tenth of the 3dgs size) and 'compressed-ply' (PlayCanvas's "
      ".compressed.ply, chunks of 256 quantised Gaussians, read by SuperSplat and splat-transform) are the "
      "compressed forms splat users share, display-referred and without the far field likewise. 'glint' is Glint's "
      "own layout (diffuse colour, normal, roughness, F0), e.g. to import a 3DGS scene. --bake-reflections puts "
      "the path-traced reflections (of the current, edited scene) into the SH colours of the splat formats.");
  cmd->add_option("input", o->input,
                  "Gaussian scene .ply (Glint or 3DGS layout), or a training run folder containing scene.ply")
      ->required();
  cmd->add_option("-o,--output", o->output, "Output file (written atomically)")->required();
  cmd->add_flag("--force", o->force, "Replace the output file if it exists");
  cmd->add_option("--format", o->format, "What to write: 3dgs, spz, compressed-ply or glint")
      ->check(CLI::IsMember({"3dgs", "glint", "spz", "compressed-ply"}))
      ->capture_default_str();
  addInputLayoutFlag(*cmd, o->inputLayout);
  cmd->add_option("--colour,--color", o->colour,
                  "3dgs: what f_dc holds. display: tonemapFilmic(exposure x linear diffuse), the filmic curve of "
                  "Glint's 8-bit images, so that viewers show what Glint's renders show; linear: the linear diffuse "
                  "as is (dark in viewers, values above 1 clip). Recorded in a header comment, from which Glint "
                  "reads its own export back exactly. spz, compressed-ply and baked colours are always display")
      ->check(CLI::IsMember({"display", "linear"}))
      ->capture_default_str();
  cmd->add_option("--exposure", o->exposure,
                  "Splat formats with display colour: linear multiplier of the colour (and of baked radiance) before "
                  "the tonemap (2 is one stop brighter)")
      ->check(positiveNumber())
      ->capture_default_str();
  cmd->add_option("--sh-degree", o->shDegree,
                  "Splat formats: spherical-harmonics degree, 0..3 (3dgs writes 0, 9, 24 or 45 f_rest). Default 3 for "
                  "3dgs (INRIA's layout) and with --bake-reflections, which fits them, else 0 (without a bake they "
                  "are zeros: Glint's diffuse colour has no view dependence)")
      ->check(CLI::Range(0, 3));
  cmd->add_flag("--keep-far-field", o->keepFarField,
                "Splat formats: keep the far-field Gaussians (dropped by default: a Gaussian is far field when its centre lies "
                "more than --far-field-radius camera-sphere radii from the training cameras' centre)");
  cmd->add_flag("--drop-far-field", o->dropFarField, "glint: drop the far-field Gaussians too (kept by default)");
  cmd->add_option("--far-field-radius", o->farFieldRadius,
                  "Far-field cut in units of S, the radius of the training cameras' sphere (1.1 x the farthest "
                  "camera from their centre, as 3DGS measures a scene)")
      ->check(positiveNumber())
      ->capture_default_str();
  cmd->add_option("--dataset", o->dataset,
                  "Dataset whose training cameras define the far-field cut and --bake-reflections' directions "
                  "(default: the run's dataset; a bare .ply without it keeps its far field)");
  cmd->add_option("--crop", o->crop,
                  "Keep only the Gaussians whose centre lies in the box X0,Y0,Z0,X1,Y1,Z1 (two opposite corners, "
                  "world units)");
  o->bake.add(cmd);
  addThreadsFlag(cmd, &o->threads, "the bake traces with them");
  cmd->callback([o]() {
    ThreadLimit threads(o->threads);
    runExport(*o);
  });
}

}  // namespace glint
