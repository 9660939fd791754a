// Gaussian scenes as PLY files: Glint's own layout (the paper's trained scenes) and the
// standard 3D Gaussian Splatting layout, built on the generic tables of io/ply.h.
#pragma once

#include <filesystem>

#include "io/ply.h"
#include "scene/gaussians.h"
#include "scene/splat_colour.h"

namespace glint {

// Zeroth-order real spherical harmonic, Y_0^0 = 1 / (2 sqrt(pi)). 3DGS stores colour as
// SH coefficients whose DC term maps to colour = 0.5 + kShC0 * f_dc (Kerbl et al. 2023,
// utils/sh_utils.py, RGB2SH / SH2RGB).
inline constexpr double kShC0 = 0.28209479177387814;

// How f_dc_0..2 of a Gaussian PLY are to be read.
enum class PlyLayout {
  Auto,      // decide from the properties (see detectGaussianPlyLayout)
  Glint,     // f_dc is the linear diffuse colour as is (docs/data-format.md, "Trained scene")
  ThreeDgs,  // f_dc is the SH DC coefficient: colour = 0.5 + kShC0 * f_dc
};

const char* plyLayoutName(PlyLayout layout);  // "auto", "glint", "3dgs"

// The layout of a table, by this rule: a file is standard 3DGS when it has any of the
// properties only 3DGS writes (f_rest_0 or nx) and none of the properties only Glint
// writes (normal_0, roughness, f0_0); every other file is Glint's. Never returns Auto.
// (A 3DGS file of SH degree 0 without nx/ny/nz is read as Glint: pass ThreeDgs explicitly.)
PlyLayout detectGaussianPlyLayout(const PlyTable& table);

// Builds a scene from a table, properties looked up by name and unknown ones ignored.
// Required: x y z, f_dc_0..2, opacity (logit), scale_0..2 (log), rot_0..3 (w x y z).
// Optional, each group all-or-nothing: normal_0..2 (default 0), roughness (default 0),
// f0_0..2 (default 0.04). Throws Error naming table.source for a missing property, a
// partial optional group, or a zero rotation quaternion (naming the vertex).
GaussianScene gaussianSceneFromPly(const PlyTable& table, PlyLayout layout = PlyLayout::Auto);

// Reads a binary little-endian PLY Gaussian scene (any scalar property types, any order).
// If detected is given, it receives the layout that was used. Throws Error naming the file.
GaussianScene readGaussianPly(const std::filesystem::path& path, PlyLayout layout = PlyLayout::Auto,
                              PlyLayout* detected = nullptr);

// Writes the scene atomically in Glint's layout: binary little-endian float32
// x y z f_dc_0..2 opacity scale_0..2 rot_0..3 normal_0..2 roughness f0_0..2 (the order of
// the paper's code). Values round-trip bit for bit. Throws Error naming the file for NaN
// or infinite values.
void writeGaussianPly(const std::filesystem::path& path, const GaussianScene& scene);

// Writes the scene atomically in the standard 3DGS layout that viewers of the wider
// ecosystem read: x y z nx ny nz f_dc_0..2 f_rest_0..44 opacity scale_0..2 rot_0..3, with
// f_dc = (colour - 0.5) / kShC0, f_rest = 0 (view-independent colour) and nx ny nz = 0
// (as 3DGS writes them). Normals, roughness and F0 are not exported.
void exportGaussianPly3dgs(const std::filesystem::path& path, const GaussianScene& scene);

// The same layout with the given colours (colour.consistent(scene.size())): f_dc =
// (base - 0.5) / kShC0 and f_rest_0 .. f_rest_(3 r - 1) the SH coefficients, channel-major
// (the r coefficients of red, then green, then blue; r = colour.restCount()), so a degree-0
// colour writes no f_rest at all.
void exportGaussianPly3dgs(const std::filesystem::path& path, const GaussianScene& scene, const SplatColour& colour);

}  // namespace glint
