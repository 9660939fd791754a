// `glint export RUN_OR_PLY --format 3dgs|glint|spz|compressed-ply -o OUT`: rewrites a Gaussian
// scene in the standard 3D Gaussian Splatting layout (for the wider ecosystem's viewers), in
// Glint's, or in the compressed forms splat users share.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "app/bake_flags.h"
#include "app/commands.h"
#include "core/error.h"
#include "scene/compressed_ply_writer.h"
#include "scene/gaussian_ply.h"
#include "scene/spz_writer.h"
#include "train/run_folder.h"

namespace glint {

namespace {

namespace fs = std::filesystem;

struct ExportOptions {
  std::string input;
  std::string output;
  std::string format = "3dgs";
  std::string inputLayout = "auto";
  BakeFlags bake;
};

PlyLayout layoutFromName(const std::string& name) {
  if (name == "glint") return PlyLayout::Glint;
  if (name == "3dgs") return PlyLayout::ThreeDgs;
  return PlyLayout::Auto;
}

// The PLY file of the input: the path itself, or scene.ply inside a run folder.
fs::path scenePath(const fs::path& input) {
  if (!fs::is_directory(input)) return input;
  fs::path scene = RunFolder(input).sceneFile();
  const std::string name = scene.filename().string();
  if (!fs::is_regular_file(scene)) {
    throw Error(input.string(), "is a folder without " + name +
                                    " (give a Gaussian scene .ply, or a training run folder that contains " + name +
                                    ")");
  }
  return scene;
}

void runExport(const ExportOptions& o) {
  o.bake.check();
  if (o.bake.given() && o.format == "glint")
    throw Error("--bake-reflections", "writes SH colours, which Glint's layout has not: use --format 3dgs, spz or "
                                      "compressed-ply");
  fs::path input = scenePath(o.input);
  PlyLayout detected = PlyLayout::Auto;
  GaussianScene scene = readGaussianPly(input, layoutFromName(o.inputLayout), &detected);
  if (o.format == "spz" || o.format == "compressed-ply" || o.bake.given()) {
    // Display-referred colour (the filmic tonemap), as splat viewers expect; SH when baked.
    const SplatColour colour = o.bake.given() ? o.bake.bake(o.input, scene) : displayColour(scene);
    if (o.format == "spz") writeSpz(o.output, scene, colour);
    else if (o.format == "compressed-ply") writeCompressedPly(o.output, scene, colour);
    else exportGaussianPly3dgs(o.output, scene, colour);
    std::fprintf(stderr, "glint export: %s (%s layout) -> %s (%s, display-referred colour, SH degree %d), %zu Gaussians\n",
                 input.string().c_str(), plyLayoutName(detected), o.output.c_str(), o.format.c_str(), colour.shDegree,
                 scene.size());
    return;
  }
  PlyLayout format = layoutFromName(o.format);
  if (format == PlyLayout::ThreeDgs) {
    exportGaussianPly3dgs(o.output, scene);
  } else {
    writeGaussianPly(o.output, scene);
  }
  std::fprintf(stderr, "glint export: %s (%s layout) -> %s (%s layout), %zu Gaussians\n", input.string().c_str(),
               plyLayoutName(detected), o.output.c_str(), plyLayoutName(format), scene.size());
}

}  // namespace

void addExportCommand(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Write a Gaussian scene in another PLY layout. '3dgs' is the standard 3D Gaussian Splatting layout "
      "(x y z nx ny nz f_dc_0..2 f_rest_0..44 opacity scale_0..2 rot_0..3, colour as SH DC, no view "
      "dependence) that splat viewers open; normals, roughness and F0 are dropped. 'glint' is Glint's own "
      "layout (diffuse colour, normal, roughness, F0), e.g. to import a 3DGS scene. 'spz' and 'compressed-ply' are "
      "the compressed forms splat viewers share (docs/data-format.md, Compressed splats).");
  cmd->add_option("input", options->input,
                  "Gaussian scene .ply (Glint or 3DGS layout), or a training run folder containing scene.ply")
      ->required();
  cmd->add_option("-o,--output", options->output, "Output file (written atomically)")->required();
  cmd->add_option("--format", options->format,
                  "Layout to write: 3dgs or glint (.ply); spz (Niantic's gzip-compressed .spz, about a tenth of the "
                  "3dgs size) or compressed-ply (PlayCanvas's .compressed.ply, chunks of 256 quantised Gaussians, "
                  "read by SuperSplat and splat-transform). spz and compressed-ply store display-referred colour "
                  "(the filmic tonemap) and drop normals, roughness and F0")
      ->check(CLI::IsMember({"3dgs", "glint", "spz", "compressed-ply"}))
      ->capture_default_str();
  cmd->add_option("--input-layout", options->inputLayout,
                  "How to read the input's f_dc: auto (3DGS if it has f_rest_0 or nx and none of normal_0, "
                  "roughness, f0_0; otherwise Glint), glint (linear colour) or 3dgs (SH DC)")
      ->check(CLI::IsMember({"auto", "glint", "3dgs"}))
      ->capture_default_str();
  options->bake.add(cmd);
  cmd->callback([options]() { runExport(*options); });
}

}  // namespace glint
