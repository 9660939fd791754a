// `glint synth --layout capture`: renders a scene's training path as if it were a real
// capture (docs/capture-format.md): tonemapped JPEG photographs, priors in the paper's
// encodings (exact or network-like), and a COLMAP model of the true cameras.
#pragma once

#include <filesystem>
#include <vector>

#include "scene/dataset.h"
#include "synth/dataset_generator.h"
#include "synth/mesh_scene.h"

namespace glint {

// What the priors get wrong: nothing, or one of the documented predictor-like errors.
enum class PriorErrors {
  None,       // the exact buffers
  Network,    // networkLikePriors (network_degradation.h): smooth, affine depth error
  Monocular,  // monocularPriors (monocular_degradation.h): non-affine depth, metalness only
};

struct CaptureSynthSettings {
  // Every holdout-th view, from the first, is a test view of `glint train --holdout`
  // (LLFF's convention): those are rendered at SynthSettings::testSpp.
  int holdout = Dataset::kDefaultHoldout;
  PriorErrors priorErrors = PriorErrors::None;
  // The priors that get priorErrors' degradation; the others are written exact (empty: all).
  // For experiments that tell which buffer's error costs what. Leaving F0 out also keeps
  // the monocular kind's F0 file (no metalness in its place).
  std::vector<Buffer> degradedPriors;
  int sparsePoints = 4000;         // points3D: sampled from the training views' exact depth
};

// A view sees a sparse point (it joins the point's COLMAP track) when nothing of the scene
// lies between the camera and the point nearer than this fraction of its distance short of
// it: a point sampled within a pixel from that pixel's depth sits off its surface by up to
// the surface's slope across the pixel (up to about a millimetre per metre here).
constexpr double kSightingTolerance = 0.005;

// Renders SynthSettings::trainViews views along the scene's training camera path (the test
// path is not used: a capture's test views are held out of the same path) and writes the
// capture folder with writeCapture: images/view_####.jpg, priors/, sparse/0 (text, true
// PINHOLE cameras, points from depth) and capture.json.
void generateCapture(const MeshScene& scene, const SynthSettings& settings, const CaptureSynthSettings& capture,
                     const std::filesystem::path& outDir);

}  // namespace glint
