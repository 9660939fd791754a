// Image-quality metrics of evaluation: PSNR, SSIM (linear and on the paper's tonemapped
// 8-bit images), depth RMSE and the mean angular error of normals.
#pragma once

#include "io/image.h"
#include "io/transfer.h"

namespace glint {

// PSNR = 10 log10(1 / MSE) over every pixel and channel, with the data range fixed at 1
// even for linear radiance that exceeds 1: the number then stays comparable between
// images and runs (a per-image peak would not). +infinity when the images are equal.
// Throws Error when sizes or channel counts differ.
double psnr(const Image& a, const Image& b);

// SSIM of Wang et al. 2004 ("Image quality assessment: from error visibility to structural
// similarity"): 11x11 Gaussian window with sigma 1.5 (normalised to sum 1), K1 = 0.01,
// K2 = 0.03, data range L = 1, weighted (biased) local moments. The map is evaluated on
// the 'valid' region only, where the window lies inside the image (no padding), as the
// authors' reference code does; its mean is taken per channel and the channels averaged.
// 1 for equal images. Throws Error when sizes or channels differ, or when the image is
// smaller than the window (11 pixels) in either direction.
double ssim(const Image& a, const Image& b);

// The 8-bit comparison image: each channel through the display transfer (the paper's
// filmic tonemap for Glint's linear datasets; a display-referred dataset's own, such as
// NeRF-synthetic's sRGB, so that figures compare with published ones), clamped to [0, 1]
// and quantised to 8 bits, round(y * 255) / 255. Values stay floats in [0, 1].
Image tonemapTo8Bit(const Image& linear, Transfer transfer = Transfer::Filmic);
// PSNR and SSIM of the 8-bit versions of two linear radiance images.
double psnrTonemapped8Bit(const Image& a, const Image& b, Transfer transfer = Transfer::Filmic);
double ssimTonemapped8Bit(const Image& a, const Image& b, Transfer transfer = Transfer::Filmic);

// Root mean square depth error over the pixels where the ground truth has a surface
// (hasSurface in scene/buffers.h); a prediction of "no surface" there counts with its
// stored value (0), i.e. as an error of the full depth. NaN when the ground truth has no
// surface pixel at all. Both images have 1 channel; throws Error otherwise or for
// mismatched sizes.
double depthRmse(const Image& predictedDepth, const Image& truthDepth);

// Mean angle in degrees between predicted and true normals (both normalised first) over
// the pixels where truthDepth has a surface and the true normal is non-zero. A zero
// predicted normal there (nothing rendered) counts as 90 degrees: it carries no direction,
// and dropping it would reward leaving holes. NaN when no pixel qualifies. Normals have 3
// channels, depth 1; throws Error otherwise or for mismatched sizes.
double normalAngleDegrees(const Image& predictedNormal, const Image& truthNormal, const Image& truthDepth);

}  // namespace glint
