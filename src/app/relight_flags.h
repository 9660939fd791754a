// The --relight flags of the commands that apply edits (`glint edit`, `render`/`eval
// --edits`): differential relighting of the diffuse layer after the edit.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "edit/gaussian_edits.h"
#include "edit/heal_uncovered.h"
#include "raytrace/gaussian_tracer.h"
#include "render/differential_relight.h"
#include "render/gaussian_path.h"

namespace glint {

class RelightFlags {
 public:
  // Declares --relight / --no-relight (on by default), --relight-rays, --relight-filter,
  // --relight-traced, --relight-bounces and --relight-max-ratio on cmd.
  void add(CLI::App* cmd);
  bool on() const { return on_; }
  // The settings of the flags, with the ray offsets of the scene's reflected rays.
  RelightSettings settings(const PathSettings& path) const;

 private:
  // On by default: on builtin:spheres it lowered the final-image drop of a move from 2.83 to
  // 1.56 dB, of a duplication from 1.69 to 1.20 and of a deletion from 4.22 to 2.27 (README,
  // "Edits that move shadows").
  bool on_ = true;
  RelightSettings settings_;
};

// Differential relighting of an edited scene (render/differential_relight.h): its changed
// regions and receivers from the provenance of the edit, tracing the scene before (with
// beforeTracer) and after (with afterTracer, which must be refitted afterwards). Then the
// Gaussians that healing added or recoloured (`healed`, empty without healing) take their
// relit surroundings' colour, lit where they stand (render/healed_lighting.h). Returns the
// line that says what it did and how long it took.
std::string relightAfterEdit(const GaussianTracer& beforeTracer, const GaussianScene& before,
                             const GaussianTracer& afterTracer, GaussianScene& after, const EditProvenance& provenance,
                             const HealReport& healed, const RelightSettings& settings);

}  // namespace glint
