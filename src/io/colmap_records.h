// Checks of single COLMAP records that the text and binary parsers share, so that both
// forms accept exactly the same models.
#pragma once

#include <string>

#include "io/colmap_model.h"

namespace glint {

// Largest width or height accepted: far beyond any camera, small enough that a corrupt
// size is caught before anything is allocated from it.
constexpr int kMaxColmapImageSide = 1 << 20;
// A stored quaternion whose norm differs from 1 by more than this is not a rotation that
// lost digits in printing (COLMAP prints 17) but a corrupt or hand-mangled pose.
constexpr double kColmapQuaternionTolerance = 1e-3;

// The problem with a record, or "" when it is valid: known model, the model's number of
// parameters, width and height in [1, kMaxColmapImageSide], finite parameters.
std::string colmapCameraProblem(const ColmapCamera& camera);
// The image size of a camera record as the file gives it (decimal text): "" when both sides
// are whole numbers in [1, kMaxColmapImageSide], otherwise the problem, quoting the sides
// exactly as written (a 2^63 or a -64 is named as such, not as a clamped value).
std::string colmapImageSizeProblem(std::string_view width, std::string_view height);
// Finite pose, quaternion norm within kColmapQuaternionTolerance of 1, a valid name.
std::string colmapImageProblem(const ColmapImage& image);
// An image name must be non-empty, relative, without "..", control characters, or
// leading or trailing spaces (the text form ends a name at the end of its line).
std::string colmapImageNameProblem(const std::string& name);
// Finite position and error.
std::string colmapPointProblem(const ColmapPoint& point);

}  // namespace glint
