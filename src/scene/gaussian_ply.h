// Gaussian scenes as PLY files: Glint's own layout (the paper's trained scenes) and the
// standard 3D Gaussian Splatting layout, built on the generic tables of io/ply.h.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "io/ply.h"
#include "scene/gaussians.h"
#include "scene/splat_colour.h"
#include "scene/three_dgs_colour.h"

namespace glint {

// How f_dc_0..2 of a Gaussian PLY are to be read.
enum class PlyLayout {
  Auto,      // decide from the header (see detectGaussianPlyLayout)
  Glint,     // f_dc is the linear diffuse colour as is (docs/data-format.md, "Trained scenes")
  ThreeDgs,  // f_dc is the SH DC coefficient of a colour (scene/three_dgs_colour.h)
};

const char* plyLayoutName(PlyLayout layout);  // "auto", "glint", "3dgs"

// The layout of a table, from its comments and its whole set of property names:
// 1. A comment decides: Glint's writer says "Glint Gaussian scene: ...", its 3DGS export
//    "Glint 3DGS export: ...". A file whose header says Glint's layout but that has 3DGS's
//    own properties (f_rest_*, nx ny nz), or that carries both comments, contradicts itself:
//    throws Error naming table.source and the --input-layout flag.
// 2. Otherwise Glint's material properties (normal_0..2, roughness, f0_0..2) without any of
//    3DGS's own mean Glint's layout, and anything else is a 3DGS file, as splat tools write
//    them (*assumedThreeDgs is set when nothing but the missing header decided: a degree-0
//    file holds only the properties both layouts share). Never returns Auto.
PlyLayout detectGaussianPlyLayout(const PlyTable& table, bool* assumedThreeDgs = nullptr);

// What reading a Gaussian PLY did, for the command line to report.
struct GaussianPlyImport {
  PlyLayout layout = PlyLayout::Glint;  // the layout used (never Auto)
  bool layoutAssumed = false;           // 3DGS for want of Glint's header or properties alone
  // 3DGS only:
  SplatColourEncoding colour;       // how f_dc was decoded (the export comment's, else display)
  // Which material groups the file lacked and were set to the imported defaults.
  bool normalsSet = false, roughnessSet = false, f0Set = false;
  int shDegree = 0;                 // the SH degree the f_rest_* properties hold (0 for none)
  size_t gaussiansWithShRest = 0;   // Gaussians with a non-zero f_rest coefficient (dropped)
};

// One line for the user about a 3DGS import: the colour and material defaults used;
// empty for Glint's layout.
std::string describeImport(const GaussianPlyImport& import);
// A warning line naming `file` when non-zero f_rest coefficients were dropped; else empty.
std::string droppedShWarning(const GaussianPlyImport& import, const std::string& file);

// Builds a scene from a table, properties looked up by name and unknown ones ignored.
// Required: x y z, f_dc_0..2, opacity (logit), scale_0..2 (log), rot_0..3 (w x y z).
// Optional, each group all-or-nothing: normal_0..2, roughness, f0_0..2. Absent, they are 0,
// 0 and 0.04 for Glint's layout, and for 3DGS a rough dielectric (scene/imported_materials.h:
// normals along each Gaussian's shortest axis, facing away from the median position).
// Throws Error naming table.source for a missing property, a partial optional group, an
// ambiguous layout (Auto), or a zero rotation quaternion (naming the vertex).
GaussianScene gaussianSceneFromPly(const PlyTable& table, PlyLayout layout = PlyLayout::Auto,
                                   GaussianPlyImport* import = nullptr);

// Reads a Gaussian scene from a PLY file (any format readPly reads, any scalar property
// types, any order). If import is given, it receives what was done. Throws Error naming the file.
GaussianScene readGaussianPly(const std::filesystem::path& path, PlyLayout layout = PlyLayout::Auto,
                              GaussianPlyImport* import = nullptr);

// Writes the scene atomically in Glint's layout: binary little-endian float32
// x y z f_dc_0..2 opacity scale_0..2 rot_0..3 normal_0..2 roughness f0_0..2 (the order of
// the paper's code), with the comment "Glint Gaussian scene: ...". Values round-trip bit
// for bit. Throws Error naming the file for NaN or infinite values.
void writeGaussianPly(const std::filesystem::path& path, const GaussianScene& scene);

// The number of f_rest coefficients per colour channel of SH degree 0..3: (degree + 1)^2 - 1.
int shRestPerChannel(int degree);

struct ThreeDgsExportOptions {
  SplatColourEncoding colour;  // display-referred (exposure 1) by default
  int shDegree = 0;            // 0..3: writes 3 x shRestPerChannel(shDegree) f_rest properties
  // Colours baked with their view dependence (render/sh_bake.h), display-referred, of degree
  // shDegree: f_dc = (base - 0.5) / kShC0 and f_rest their SH coefficients, channel-major
  // (R's coefficients, then G's, then B's). Null: f_dc encodes the diffuse colour as
  // `colour` says and f_rest are zeros.
  const SplatColour* baked = nullptr;
};

// Writes the scene atomically in the standard 3DGS layout that viewers of the wider
// ecosystem read: x y z nx ny nz f_dc_0..2 f_rest_* opacity scale_0..2 rot_0..3, with f_dc
// encoding the diffuse colour as options.colour says (recorded in a header comment) and
// nx ny nz = 0 (as 3DGS writes them). Normals, roughness and F0 are not exported.
void exportGaussianPly3dgs(const std::filesystem::path& path, const GaussianScene& scene,
                           const ThreeDgsExportOptions& options = {});

}  // namespace glint
