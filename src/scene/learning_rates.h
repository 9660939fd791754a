// Adam's learning rate of each Gaussian parameter, beside the parameters themselves so that
// the parameter table (scene/gaussian_parameters.h) can name each one's rate, as 3DGS's
// parameter groups carry theirs. The config's "lr" keys are the table's (train/train_config.cpp).
#pragma once

namespace glint {

// Adam learning rates per parameter group (defaults of the paper's code). The position
// rate is multiplied by the scene extent and decays log-linearly from positionInit to
// positionFinal over positionDecaySteps steps (3DGS). A decaying rate holds its initial
// value until its decay start, then falls over its decay steps.
struct LearningRates {
  float positionInit = 1.6e-4f;
  float positionFinal = 1.6e-6f;
  int positionDecaySteps = 32000;
  int positionDecayStart = 0;
  float rotation = 1e-3f;
  float scale = 5e-3f;
  float opacity = 2.5e-2f;
  float diffuse = 5e-3f;
  float normal = 2.5e-3f;
  // The normal rate decays log-linearly from `normal` to this over normalDecaySteps steps
  // (constant afterwards); equal to `normal` (the paper's schedule), it stays constant.
  // Adam moves each parameter by about its rate per step whatever the gradient's size, so
  // a constant rate keeps normals jittering by about that much: reflected rays magnify it.
  float normalFinal = 2.5e-3f;
  int normalDecaySteps = 8000;
  int normalDecayStart = 0;
  float roughness = 2.5e-3f;
  // The roughness rate decays the same way when asked (constant by default): roughness
  // priors are noisy too. Measured on predicted buffers it gained nothing beyond the
  // normal rate's decay (docs/captures.md), so it stays off.
  float roughnessFinal = 2.5e-3f;
  int roughnessDecaySteps = 8000;
  int roughnessDecayStart = 0;
  float f0 = 2.5e-3f;
};

}  // namespace glint
