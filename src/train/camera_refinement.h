// Camera pose refinement during training: each training view's pose aligned to the model's
// render of it (train/pose_alignment.h), so that cameras estimated from the photographs,
// each a degree or so off, come to agree with the scene the views build together.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "raytrace/gaussian_tracer.h"
#include "scene/buffers.h"
#include "render/path_step.h"
#include "train/pose_alignment.h"
#include "train/training_views.h"

namespace glint {

// What one round did, for the line `glint train` prints.
struct CameraRefinementRound {
  int views = 0;
  int moved = 0;                    // views whose alignment was accepted
  double medianDegrees = 0, maxDegrees = 0;     // of the accepted changes
  double medianDistance = 0, maxDistance = 0;   // in the scene's units
  double costBefore = 0, costAfter = 0;         // mean robust cost over the moved views
  int refusedBeyondBounds = 0;      // refused as a turn or move beyond the bounds (a wrong basin)
  // The motion the moved views shared, taken out (removeCommonMotion): its angle and scale.
  double commonDegrees = 0, commonScale = 1;
  // "cameras refined: 97 of 100 views moved, median 0.21 deg and 0.9 cm (at most ...)".
  std::string summary() const;
};

// The model's render of a view for aligning its camera: colour averaged over a few jittered
// samples per pixel, as a dataset's radiance buffers average their pixels (centre samples
// alone alias the model's pixel-sized Gaussians into a biased alignment), the first segment's
// diffuse, or with finalColour the final image along `path`; depth from the pixel centre.
// alignmentColour() picks the colour buffer to align.
ViewBuffers renderForAlignment(const GaussianTracer& tracer, const Camera& camera, const PathSettings& path,
                               bool finalColour, uint64_t viewKey);
inline const Image& alignmentColour(const ViewBuffers& rendered, bool finalColour) {
  return rendered[finalColour ? Buffer::Render : Buffer::Diffuse];
}

// Takes out of `after` the similarity (rotation, uniform scale, offset) that best carries the
// poses `before` onto it: the rotation the mean of the views' rotation changes, then scale and
// offset by least squares on the centres. What is left is each view's own change. Returns the
// rotation's angle in degrees and the scale.
std::pair<double, double> removeCommonMotion(const std::vector<Camera>& before, std::vector<Camera>* after);

// Renders every training view from the model (pixel centres; the diffuse pass, or the final
// image where the views' colour target is the render buffer, along `path`), aligns its pose
// to its colour target and sets the views' camera where the alignment is accepted, less the
// motion the moved views share (removeCommonMotion): the model was built in the frame the
// cameras had, so a turn, scale or shift of them all is the alignments' drift, not the
// cameras' error, and the test views, which are not refined, would see the model moved by it.
// normalsFromCamera: the views' normal targets came from camera-space priors (they turn
// with the camera, TrainingViews::setCamera). Deterministic: every view is aligned on its own,
// so each rank of an MPI job computes the same poses.
CameraRefinementRound refineTrainingCameras(const GaussianTracer& tracer, const PathSettings& path,
                                            TrainingViews* views, bool normalsFromCamera,
                                            const PoseAlignmentOptions& options = {});

}  // namespace glint
