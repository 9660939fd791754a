// Every hyper-parameter of a training run, with the paper's defaults, and its JSON form
// (RUN/config.json and --config files).
#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "raytrace/trace_settings.h"
#include "render/gaussian_path.h"
#include "scene/dataset.h"
#include "scene/downscale.h"
#include "scene/learning_rates.h"
#include "train/config_choices.h"
#include "train/dense_init.h"
#include "train/densify.h"
#include "train/far_field.h"

namespace glint {

// Weights of the L1 terms (paper section 3.2).
struct LossWeights {
  float diffuse = 5.0f;
  float depth = 2.5f;
  // The paper's 2.5 leaves normals 0.95 degrees off on builtin:spheres' test views; 10
  // brings that to 0.70 and specular up by 0.4 dB (with kernel power 2; README).
  float normal = 10.0f;
  float roughness = 1.0f;
  float f0 = 1.0f;
  float specular = 3.0f;  // L_r, on the specular buffer (reflected segments only)
  // When positive, the depth term counts only the pixels whose rendered depth is within
  // this fraction of their prior's (train/ray_loss.h, withinDepthBand): a predicted depth
  // that disagrees with the geometry the other views agree on stops pulling it. Not a
  // weight; an option beyond the paper, off: at 0.1 it gained 0.4 dB of specular on one
  // predicted capture and lost 0.3 on another (docs/captures.md).
  float depthBand = 0.0f;
  // When positive, the depth term also leaves out every pixel whose depth fewer than
  // depthConsistencyViews of its view's 8 most overlapping views confirm within this
  // fraction (train/depth_consistency.h), checked once when the views load: multi-view
  // consistency of the priors, beside the band's agreement with the geometry. Not a weight;
  // an option beyond the paper, off (docs/captures.md).
  float depthConsistency = 0.0f;
  int depthConsistencyViews = 2;
  // When positive, the normal term is a Huber loss of this width per component (quadratic
  // within it, the L1 slope beyond): the minimum over many views' priors is then near their
  // mean rather than their median, which for noise spread about the true normal scatters
  // less (a mean's variance is 2/pi of a median's for Gaussian noise), while outliers beyond
  // the width still pull only as L1. 0, the paper's L1. An option beyond the paper, off.
  float normalHuber = 0.0f;
  // Weights of L_r's gradient into the roughness and the F0 of the surfaces a path reflects
  // off, through each step's sample weight with its direction and density held fixed
  // (render/gaussian_path.h, PathGradientSettings; docs/derivations.md D15). 0, the paper's
  // detached throughputs: only the priors then set roughness and F0. Options beyond the
  // paper, off: at 2000 steps a roughness weight of 1 gained 1.1 dB of final on one
  // predicted capture and lost 1.3 on another and 0.6 on exact buffers (0.1: +0.6 and
  // -0.15); F0 from L_r lost 1.1 (docs/captures.md). Those runs let the gradient move the
  // geometry too, which it no longer does (PathGradientSettings::materialsMoveGeometry).
  float roughnessFromSpecular = 0.0f;
  float f0FromSpecular = 0.0f;
  // With TrainConfig::f0TintFromReflections, the share of the F0 term that still compares
  // every channel of a metal's F0 with its grey prior (PixelTarget::f0TintPrior), in [0, 1]:
  // a weak pull toward grey that L_r's evidence for a tint must overcome. Where a mirror
  // reflects what the training views see only in it, F0's tint and that light's colour
  // trade freely, and without the pull F0 drifts (builtin:room's mirror went pink). 0.1:
  // on builtin:spheres +0.31 dB of specular over 0 (0.3 and 1 not run there); on
  // builtin:room the same as 0 and 1, 0.26 dB above 0.3 (docs/captures.md; measured while
  // L_r's material gradient still moved the geometry).
  float f0TintPrior = 0.1f;
  // Beyond the paper: the weight of a term fitting the first diffuse plus the path's
  // specular to each view's photograph (its render buffer), beside the diffuse and specular
  // priors, once reflections train (train/ray_loss.h, photographLoss). A capture's priors
  // are a predictor's guesses, blurred and noisy, but its photographs are exact: the term
  // lets them correct the sum while the priors still split it. 0, off: on a monocular-kind
  // capture 3 gained 0.33 dB of specular and 0.51 of final on builtin:spheres, 0.34 and
  // 0.63 on builtin:room (docs/captures.md); under the paper's preset (no depth loss), on
  // the monocular kind +0.87 dB of specular and +1.01 of final under COLMAP's cameras
  // (builtin:gallery) but -0.97 and -0.74 on builtin:room, the depth drifting 2-7x further;
  // on the network kind under the preset -1.73 and -1.89 (room); not measured on exact buffers.
  float photograph = 0.0f;
};

struct AdamSettings {
  float beta1 = 0.9f;
  float beta2 = 0.999f;
  float epsilon = 1e-15f;
};

// Weight-based pruning (appendix A.4) and the removal of Gaussians near training cameras.
struct PruneSettings {
  int every = 125;             // steps between prunes
  int start = 1250;            // first step that prunes
  // A Gaussian is pruned when its blend weight per full training image, averaged over the
  // steps of the interval, is below this (the paper sums weights over all pixels of the
  // step's image; a step here traces batchRays rays, so weights are scaled by
  // pixels-per-view / batchRays).
  float weightThreshold = 0.1f;
  // When positive, weightThreshold holds for images of this many pixels and scales with the
  // training views' own pixel count, so that a Gaussian of a given size is kept or pruned
  // alike at any resolution: the paper's 0.1 is for its 1152x768 views (884,736 pixels),
  // where a Gaussian gets 46 times the weight it gets at 160x120. 0: the threshold holds
  // per training image as it is.
  double thresholdPixels = 0;
  float cameraSphereFactor = 0.8f;  // sphere radius = this x the nearest input depth
  // "in-view" culls only the part of a sphere its camera sees; "whole-sphere" is the
  // paper's rule, which also removes real walls behind cameras inside a room
  // (train/camera_culling.h).
  CullRegion cameraCullRegion = CullRegion::SphereInView;
};

// Camera pose refinement (train/camera_refinement.h): every `every` steps, up to step `until`,
// each training view's pose is aligned to the model's render by direct image alignment of its
// colour target. For cameras estimated from the photographs (COLMAP's), whose error of a
// degree or so puts each view's depth and colours where the others' are not. 0 = off.
struct CameraRefinementSettings {
  int every = 0;
  int until = 0;  // 0: three quarters of the run's steps, so the last poses settle before it ends
  // The step of the last refinement of a run of `iters` steps.
  int lastStep(int iters) const { return until > 0 ? until : iters / 4 * 3; }
};

// The allowed range of an integer setting, shared by the flag of `glint train` and the
// field of a config file, so that neither path accepts what the other refuses. Every other
// range is checked in TrainConfig::validate alone.
struct IntRange {
  int64_t min, max;
};
inline constexpr IntRange kItersRange{1, 100'000'000};
inline constexpr IntRange kThreadsRange{0, 1024};
inline constexpr IntRange kHoldoutRange{2, 1000};
inline constexpr IntRange kDownscaleRange{1, kMaxDownscale};
inline constexpr IntRange kBouncesRange{0, 8};
// `glint render` and `glint eval --bounces` may follow longer paths than training does.
inline constexpr IntRange kRenderBouncesRange{0, 64};
inline constexpr IntRange kBatchRaysRange{1, 1 << 24};
inline constexpr IntRange kBatchViewsRange{1, 1 << 20};
inline constexpr IntRange kBatchImagesRange{0, 1 << 20};
inline constexpr IntRange kEveryStepsRange{1, 100'000'000};  // eval_every, save_every, prune.every, decay steps
inline constexpr IntRange kDecayStartRange{0, 100'000'000};  // the step a learning rate starts to decay
// Loss weights above this would overflow Adam's second moment (gradients squared in float).
inline constexpr float kMaxLossWeight = 1e6f;
// Learning rates are in [0, this): an Adam step moves a parameter by about its rate.
inline constexpr float kMaxLearningRate = 10.0f;

struct TrainConfig {
  std::string dataset;  // absolute path of the dataset
  // A capture without a split of its own: every holdout-th image is a test view (LLFF's 8).
  int holdout = Dataset::kDefaultHoldout;
  // Behind the NeRF-synthetic layout's transparent pixels (scene/nerf_synthetic.h).
  AlphaBackground background = AlphaBackground::White;
  int downscale = 1;  // every view at 1/N resolution (scene/downscale.h)
  int iters = 8000;
  uint64_t seed = 0;
  int threads = 0;   // 0 = all cores
  int bounces = 2;   // reflected segments trained after the warm-up (0 = first segment only)
  // Reflected segments `glint render`, `eval` and `view` follow for the run (at least
  // `bounces`; none when it trains none). Training's 2 keep steps cheap, but the views'
  // reflections hold 6-8 bounces: 4 at render time gained 0.76 dB specular and final on
  // the Blender spheres_room and 0.03-0.07 dB on mirror_room (README).
  int renderBounces = 4;
  // "none" trains the method; "rgb" is the ray-traced RGB-only baseline: the first
  // segment's colour is fitted to the render buffer alone (no G-buffers, no reflections).
  Baseline baseline = Baseline::None;
  int reflectionWarmup = 750;  // steps of first-segment training before reflections start
  // When true, a capture whose F0 is a predicted metalness (grey: a tinted metal's colour
  // is lost) trains mostly the brightest channel of its metals' F0 (metalness >= 0.5;
  // greyF0IsMetal; the rest of the term is loss.f0_tint_prior's pull toward grey) and
  // leaves their tint to L_r, which needs loss.f0_from_specular > 0 to reach F0 and then
  // reaches metals only (PathGradientSettings::f0FromSpecularMetalsOnly); dielectrics keep
  // every channel of their prior. With an F0 prior (tinted already) L_r's F0 gradient is
  // withheld and the option does nothing. An option beyond the paper, off: under the
  // monocular kind's best setting +1.08 dB of specular on one scene's tinted chrome, +0.07
  // on another (docs/captures.md); under the paper's preset (no depth loss) -2.30 dB of
  // specular on builtin:room (its flat mirror -4.1; cause not separated) and +0.17 on
  // builtin:gallery under COLMAP's cameras, so the preset leaves it off.
  bool f0TintFromReflections = false;
  // When true, the roughness term ignores a constant offset between the priors and the
  // model: it compares r + b with the prior p, b the median of p - r over the previous
  // step's surface pixels (train/roughness_shift.h), so a prior biased as a whole gives
  // its structure but not its level. No other term sets the level (L_r's gradient never
  // reaches roughness unless loss.roughness_from_specular is set), so it stays where the
  // first steps leave it. An option beyond the paper, off: on one predicted capture
  // +1.3 dB of specular at 8000 steps with the depth loss and nothing without it, on
  // another nothing (docs/captures.md).
  bool roughnessShiftInvariant = false;
  float invalidNormalLength = 0.7f;  // paths end at shorter blended normals
  float backfaceSkip = 0.1f;         // reflection rays ignore back faces this close
  int batchRays = 16384;
  int batchViews = 4;  // training views a batch's rays are drawn from
  // When > 0, each step takes every pixel of this many training views (the paper's
  // protocol: whole images, the views visited in a new seeded order each epoch) in place
  // of batchRays random pixels of batchViews views (train/training_views.h,
  // drawWholeImages). On the CPU a ray costs the same either way (train_bench).
  int batchImages = 0;
  int evalEvery = 1000;
  int saveEvery = 1000;
  float scaleDecay = 0.9999f;
  LossWeights loss;
  LearningRates lr;
  AdamSettings adam;
  PruneSettings prune;
  DensifySettings densify;  // splitting where the losses pull hardest (train/densify.h)
  // Dense initialisation (appendix A.3): "auto" (point_cloud_dense.ply if present, else
  // the depth buffers), "depth" or "point-cloud", and the settings of either.
  InitChoice initSource = InitChoice::Auto;
  DenseInitSettings init;
  // With loss.depth_consistency on, the initialisation from depth buffers also leaves out
  // the pixels the check does not trust, instead of unprojecting every depth pixel: the
  // Gaussians a contradicted prior would place are never made. An option beyond the
  // paper, off (docs/captures.md).
  bool initConsistentDepthOnly = false;
  // Camera pose refinement during training, off (0): an option beyond the paper. Measured
  // on COLMAP's cameras of a synthesized capture it moved them further from the truth and
  // cost 1.3 dB of held-out specular and 2.6 of diffuse (docs/captures.md): kept to measure
  // again, not to use.
  CameraRefinementSettings cameras;
  FarFieldSettings farField;  // added when reflections start (bounces > 0)
  // Early termination, as in rendering: the exact final transmittance of the A.2 tail
  // estimate needs every hit behind the termination point, through walls and into the
  // far field (measured on builtin:spheres after the far field joined: 2x fewer rays/s),
  // so the estimate takes the tail as opaque instead (T_f = 0, compositor.h). Dropping the
  // estimate altogether is what the paper warns against: on builtin:spheres the depth L1
  // at step 500 rose from 0.031 to 0.055. "exact_tail": true restores the exact T_f.
  TraceSettings trace;

  // How the run reads its dataset: eval, render and report read it as training did.
  DatasetReading datasetReading(bool requireBuffers) const {
    return {.requireBuffers = requireBuffers, .holdout = holdout, .background = background, .downscale = downscale};
  }

  // The path settings of rendering and of the reflection loss: how the run renders.
  PathSettings path() const {
    PathSettings p;
    p.bounces = baseline == Baseline::Rgb ? 0 : bounces;
    p.invalidNormalLength = invalidNormalLength;
    p.backfaceSkip = backfaceSkip;
    return p;
  }

  // The path settings of `glint render`, `eval` and `view` for the run: path() with
  // renderBounces when the run trains reflections.
  PathSettings renderPath() const {
    PathSettings p = path();
    if (p.bounces > 0) p.bounces = std::max(p.bounces, renderBounces);
    return p;
  }

  // Throws Error(source, ...) for out-of-range values.
  void validate(const std::string& source) const;
};

nlohmann::json toJson(const TrainConfig& config);
// Overrides the fields present in json; unknown keys, wrong types and unknown spellings of
// a choice are errors naming `source` (a file name) and the key; then validates.
void applyJson(const nlohmann::json& json, TrainConfig* config, const std::string& source);
TrainConfig readTrainConfig(const std::filesystem::path& path);  // defaults + the file

// The setting for a capture whose buffers a network predicted (the paper's, for its real
// scenes): no depth loss, the specular weight 0.01, 2 trained bounces. `glint train`
// applies it to such captures unless --config is given; scripts/real-capture-train.json
// holds the same values for other tools.
void usePredictedBufferSetting(TrainConfig* config);

}  // namespace glint
