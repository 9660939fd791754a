// The colour of a standard 3D Gaussian Splatting PLY: its f_dc SH coefficient against
// Glint's linear diffuse, and the header comment in which Glint's export records which
// mapping it used (docs/data-format.md, "Trained scenes: PLY").
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace glint {

// Zeroth-order real spherical harmonic, Y_0^0 = 1 / (2 sqrt(pi)). 3DGS stores colour as
// SH coefficients whose DC term maps to colour = 0.5 + kShC0 * f_dc (Kerbl et al. 2023,
// utils/sh_utils.py, RGB2SH / SH2RGB).
inline constexpr double kShC0 = 0.28209479177387814;

// What the colour 0.5 + kShC0 * f_dc of a 3DGS file means.
enum class SplatColour {
  // Display-referred, as 3DGS viewers show it: Glint writes tonemapFilmic(exposure x
  // diffuse) and reads untonemapFilmic(colour) / exposure. Files from other tools are
  // read this way with exposure 1, so that Glint's 8-bit renders show their colours.
  Display,
  Linear,  // Glint's linear diffuse as is (values above 1 clip in viewers)
};

const char* splatColourName(SplatColour colour);  // "display", "linear"

// How a file's colour is encoded: the mapping and, for Display, the linear multiplier
// applied before the tonemap.
struct SplatColourEncoding {
  SplatColour colour = SplatColour::Display;
  float exposure = 1.0f;
};

// One channel of linear diffuse as f_dc, and back.
float encodeSplatColour(float diffuse, const SplatColourEncoding& encoding);
float decodeSplatColour(float fdc, const SplatColourEncoding& encoding);

// The header comment of Glint's 3DGS export, e.g. "Glint 3DGS export: colour display,
// exposure 1 (f_dc is the SH DC of tonemapFilmic(exposure x linear diffuse))".
std::string splatColourComment(const SplatColourEncoding& encoding);
// The encoding a header's comments record: nullopt when none is Glint's export comment.
// Throws Error naming `file` for a Glint export comment it cannot parse.
std::optional<SplatColourEncoding> splatColourFromComments(const std::vector<std::string>& comments,
                                                           const std::string& file);
// True when a comment is Glint's export comment (it starts with its prefix).
bool isSplatColourComment(const std::string& comment);

}  // namespace glint
