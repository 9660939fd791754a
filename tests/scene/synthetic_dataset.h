// Writes a small valid dataset (docs/data-format.md) for the scene tests: 8x6 pixels, two train
// views and one test view, plausible buffers with unit normals and some no-surface pixels.
#pragma once

#include <filesystem>
#include <vector>

#include "io/image.h"
#include "scene/dataset.h"

namespace glint::test {

constexpr int kSyntheticWidth = 8;
constexpr int kSyntheticHeight = 6;

struct SyntheticDataset {
  DatasetSplit train, test;
  std::vector<ViewBuffers> trainBuffers, testBuffers;  // the linear values written
};

// Deterministic buffers of one view. No surface in column 0 (depth 0) and at pixel (7, 0)
// (depth 1e10); elsewhere render = diffuse + specular in [0, 4], unit normals, roughness
// and f0 in [0, 1].
ViewBuffers syntheticBuffers(int width, int height, int viewSeed);

// Writes transforms_train.json, transforms_test.json, every buffer in the given format and
// (optionally) point_cloud_dense.ply under root; returns what was written.
SyntheticDataset writeSyntheticDataset(const std::filesystem::path& root, ImageFormat format = ImageFormat::Exr,
                                       int trainViews = 2, int testViews = 1, bool pointCloud = true);

}  // namespace glint::test
