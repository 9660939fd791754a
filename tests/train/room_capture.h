// A small capture of builtin:room for the tests of training on captures: 9 views (8
// training, every 8th held out) at one sample per pixel, with the given prior errors.
#pragma once

#include <filesystem>

#include "synth/builtin_scenes.h"
#include "synth/capture_generator.h"

namespace glint::test {

inline void writeRoomCapture(const std::filesystem::path& root, PriorErrors errors, int width = 64, int height = 48,
                             int sparsePoints = 2000) {
  SynthSettings settings;
  settings.trainViews = 9;
  settings.width = width, settings.height = height;
  settings.spp = 1, settings.testSpp = 1, settings.bounces = 1;
  CaptureSynthSettings capture;
  capture.sparsePoints = sparsePoints;
  capture.priorErrors = errors;
  generateCapture(makeBuiltinScene("room"), settings, capture, root);
}

}  // namespace glint::test
