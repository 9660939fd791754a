// `glint export RUN_OR_PLY --format 3dgs|glint -o OUT.ply`: rewrites a Gaussian scene in
// the standard 3D Gaussian Splatting layout (for the wider ecosystem's viewers) or in Glint's,
// optionally without the far field or cropped to a box.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "app/cli_parsing.h"
#include "app/commands.h"
#include "app/export_filters.h"
#include "app/output_file.h"
#include "app/scene_source.h"
#include "core/error.h"
#include "scene/dataset.h"
#include "scene/gaussian_ply.h"

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
  int shDegree = 0;
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

// Drops what the options exclude, saying how many went.
void filterGaussians(const ExportOptions& o, PlyLayout format, SceneSource& source) {
  GaussianScene& scene = source.scene;
  const bool dropFarField = o.dropFarField || (format == PlyLayout::ThreeDgs && !o.keepFarField);
  if (dropFarField) {
    if (std::optional<SceneSphere> cameras = trainingCameras(o, source)) {
      std::vector<bool> keep = nearTheCameras(scene, *cameras, o.farFieldRadius);
      size_t dropped = countDropped(keep);
      scene.filter(keep);
      std::fprintf(stderr, "glint export: dropped %zu far-field Gaussians (centre more than %g x %.3g = %.3g from "
                           "the training cameras' centre; --keep-far-field keeps them)\n",
                   dropped, double(o.farFieldRadius), double(cameras->radius),
                   double(o.farFieldRadius) * double(cameras->radius));
    }
  }
  if (!o.crop.empty()) {
    std::vector<bool> keep = insideBox(scene, parseBox(o.crop, "--crop"));
    size_t dropped = countDropped(keep);
    scene.filter(keep);
    std::fprintf(stderr, "glint export: dropped %zu Gaussians outside the --crop box\n", dropped);
  }
}

void runExport(const ExportOptions& o) {
  const PlyLayout format = o.format == "glint" ? PlyLayout::Glint : PlyLayout::ThreeDgs;
  if (format == PlyLayout::Glint && (o.colour != "display" || o.exposure != 1.0f || o.shDegree != 0))
    throw Error("command line", "--colour, --exposure and --sh-degree apply to --format 3dgs only");
  if (o.keepFarField && o.dropFarField) throw Error("command line", "give --keep-far-field or --drop-far-field, not both");
  // Refuse what can be refused before reading a large scene.
  refuseExistingOutput(o.output, o.force);
  if (!o.crop.empty()) parseBox(o.crop, "--crop");

  SceneSource source = loadSceneSource(o.input, parseInputLayout(o.inputLayout));
  filterGaussians(o, format, source);
  std::string written;
  if (format == PlyLayout::ThreeDgs) {
    ThreeDgsExportOptions options;
    options.colour.colour = o.colour == "linear" ? SplatColour::Linear : SplatColour::Display;
    options.colour.exposure = o.exposure;
    options.shDegree = o.shDegree;
    exportGaussianPly3dgs(o.output, source.scene, options);
    char details[96];
    std::snprintf(details, sizeof(details), ", %s colour, exposure %g, SH degree %d",
                  splatColourName(options.colour.colour), double(o.exposure), o.shDegree);
    written = details;
  } else {
    writeGaussianPly(o.output, source.scene);
  }
  std::fprintf(stderr, "glint export: %s (%s layout) -> %s (%s layout%s), %zu Gaussians\n",
               source.sceneFile.string().c_str(), plyLayoutName(source.import.layout), o.output.c_str(),
               plyLayoutName(format), written.c_str(), source.scene.size());
}

}  // namespace

void addExportCommand(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Write a Gaussian scene in another PLY layout. '3dgs' is the standard 3D Gaussian Splatting layout "
      "(x y z nx ny nz f_dc_0..2 f_rest_* opacity scale_0..2 rot_0..3) that splat viewers open: colour as the SH DC "
      "term, display-referred by default, normals, roughness and F0 dropped, and the far-field Gaussians left out. "
      "'glint' is Glint's own layout (diffuse colour, normal, roughness, F0), e.g. to import a 3DGS scene.");
  cmd->add_option("input", o->input,
                  "Gaussian scene .ply (Glint or 3DGS layout), or a training run folder containing scene.ply")
      ->required();
  cmd->add_option("-o,--output", o->output, "Output .ply file (written atomically)")->required();
  cmd->add_flag("--force", o->force, "Replace the output file if it exists");
  cmd->add_option("--format", o->format, "Layout to write: 3dgs or glint")
      ->check(CLI::IsMember({"3dgs", "glint"}))
      ->capture_default_str();
  addInputLayoutFlag(*cmd, o->inputLayout);
  cmd->add_option("--colour,--color", o->colour,
                  "3dgs: what f_dc holds. display: tonemapFilmic(exposure x linear diffuse), the filmic curve of "
                  "Glint's 8-bit images, so that viewers show what Glint's renders show; linear: the linear diffuse "
                  "as is (dark in viewers, values above 1 clip). Recorded in a header comment, from which Glint "
                  "reads its own export back exactly")
      ->check(CLI::IsMember({"display", "linear"}))
      ->capture_default_str();
  cmd->add_option("--exposure", o->exposure,
                  "3dgs with --colour display: linear multiplier of the diffuse colour before the tonemap (2 is one "
                  "stop brighter)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--sh-degree", o->shDegree,
                  "3dgs: spherical-harmonics degree of the file: 0 writes no f_rest, 1, 2, 3 write 9, 24, 45 "
                  "f_rest (zeros: Glint's diffuse colour has no view dependence)")
      ->check(CLI::Range(0, 3))
      ->capture_default_str();
  cmd->add_flag("--keep-far-field", o->keepFarField,
                "3dgs: keep the far-field Gaussians (dropped by default: a Gaussian is far field when its centre lies "
                "more than --far-field-radius camera-sphere radii from the training cameras' centre)");
  cmd->add_flag("--drop-far-field", o->dropFarField, "glint: drop the far-field Gaussians too (kept by default)");
  cmd->add_option("--far-field-radius", o->farFieldRadius,
                  "Far-field cut in units of S, the radius of the training cameras' sphere (1.1 x the farthest "
                  "camera from their centre, as 3DGS measures a scene)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--dataset", o->dataset,
                  "Dataset whose training cameras define the far-field cut (default: the run's dataset; a bare .ply "
                  "without it keeps its far field)");
  cmd->add_option("--crop", o->crop,
                  "Keep only the Gaussians whose centre lies in the box X0,Y0,Z0,X1,Y1,Z1 (two opposite corners, "
                  "world units)");
  cmd->callback([o]() { runExport(*o); });
}

}  // namespace glint
