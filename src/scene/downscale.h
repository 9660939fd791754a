// --downscale N: a dataset view at 1/N resolution, its camera and its buffers box-filtered
// so that every pixel stands for the N x N pixels it covers (docs/data-format.md).
#pragma once

#include "io/image.h"
#include "scene/buffers.h"
#include "scene/camera.h"

namespace glint {

// The most a view may be downscaled by (an 800-pixel view becomes 12 pixels wide at 64).
inline constexpr int kMaxDownscale = 64;

// The camera of a view shrunk by n: width and height divided by n and rounded down (the
// last width % n columns and height % n rows are dropped), focal lengths and principal
// point divided by n, so that pixel (i, j) of the result covers pixels [n i, n i + n) x
// [n j, n j + n) of the original. n must not exceed the camera's width or height.
Camera downscaleCamera(const Camera& camera, int n);

// A buffer (linear values, docs/data-format.md) shrunk by n, over the same pixels as
// downscaleCamera. Radiance, roughness and F0: the mean of the block. Depth and normals
// describe one surface per pixel, so they average the block's pixels that have one (depth
// not "no surface"; normals not 0), renormalising the mean normal; the pixel has no
// surface when fewer than half its block do (silhouettes neither grow nor shrink).
Image downscaleBuffer(const Image& image, Buffer buffer, int n);

}  // namespace glint
