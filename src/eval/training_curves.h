// The charts of a training log: loss terms, Gaussian count and test PSNR against step.
#pragma once

#include <span>
#include <vector>

#include "eval/svg_chart.h"
#include "eval/training_log.h"

namespace glint {

// Steps over which the curves are averaged: per-step losses of a 16k-ray batch are noisy.
constexpr int kSmoothingSteps = 50;

// Centred running mean over `window` values (window / 2 on each side, fewer at the ends),
// ignoring NaN; NaN where the window holds no number.
std::vector<double> runningMean(std::span<const double> values, int window);

// From a log with a "step" column, each chart only if its data exists:
// - "Total loss": loss, smoothed, over the faint raw values (log scale);
// - "L1 terms": every *_l1 column with a positive value, each smoothed over its raw values
//   (log scale; zeros, e.g. specular_l1 before reflections start, are gaps);
// - "Gaussians" against step;
// - "Test diffuse PSNR during training" from the rows that have test_diffuse_psnr.
std::vector<LineChart> trainingCharts(const TrainingLog& log);

}  // namespace glint
