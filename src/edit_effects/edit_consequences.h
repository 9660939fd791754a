// An edit and its consequences in one place: the edit document applied, the surface it
// uncovered healed, and the diffuse colours it changed relit (now, or later and
// cancellable, as the viewer needs). `glint edit`, `render`/`eval --edits` and the viewer
// call these; they differ only in how they get their tracers.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "edit/edit_file.h"
#include "edit/gaussian_edits.h"
#include "edit/heal_uncovered.h"
#include "raytrace/gaussian_tracer.h"
#include "render/differential_relight.h"
#include "scene/gaussians.h"

namespace glint {

struct EditConsequenceSettings {
  size_t maxGaussians = kDefaultMaxGaussians;  // the most Gaussians the edits may leave
  std::optional<HealSettings> heal;            // fill the uncovered surface (edit/heal_uncovered.h)
  std::optional<RelightSettings> relight;      // relight the diffuse layer (render/differential_relight.h)
  // Leave the relighting to relightEdit, later (the viewer shows a moved object at once).
  // Only an edit that moves, adds or removes Gaussians is deferred: a material edit has no
  // changed region, traces no ray, and is relit at once.
  bool deferRelighting = false;
};

// What relighting an edit needs besides the scenes: which Gaussians it moved, added or
// removed, and what healing added (empty without healing).
struct RelightInputs {
  EditProvenance provenance;
  HealReport healed;
};

// What applyEditDocument did.
struct EditOutcome {
  EditReport report;                     // per operation: counts and warnings
  size_t healedCount = 0;                // Gaussians healing added
  std::optional<RelightInputs> pending;  // set when the relighting was deferred
  std::string relightLine;               // relightEdit's line when it relit now
  double relightSeconds = 0;
};

// The tracer of the edited scene and the scene object it traces: the edited scene itself,
// or where the caller moved it (the viewer moves it into the object its tracer references).
struct TracedScenePointers {
  GaussianTracer* tracer = nullptr;
  GaussianScene* scene = nullptr;
};

// What the caller provides: its tracers and where messages go. `uneditedTracer` is called
// only when relighting runs. `editedTracer`, when set, is called once the edits and the
// healing are applied, before the relighting, which then works on the scene object it
// returns and refits its tracer (tracers may keep copies of the colours); with relighting
// deferred, that tracer is what the caller keeps for relightEdit. `report` receives the
// edit report (formatEditReport's lines) as soon as the edits are applied, and `step` one
// line per later step (healing, relighting) with what it did and how long it took.
struct EditCallbacks {
  std::function<const GaussianTracer&(const GaussianScene& unedited)> uneditedTracer;
  std::function<TracedScenePointers(GaussianScene& edited)> editedTracer;
  std::function<void(const std::string& text)> report;
  std::function<void(const std::string& line)> step;
};

// Callbacks that print the report to stderr as it is and each step's line after
// "<command>: " (the tracers are left to the caller).
EditCallbacks printingCallbacks(const std::string& command);

// Applies `document` to `scene` in place (or to where editedTracer moves it), then its consequences: healing (before relighting,
// so that the filled surface is relit with the rest), then relighting against the scene as
// it was. `unedited` is that scene when the caller keeps it (the viewer's pristine scene);
// otherwise a copy is made when healing or relighting needs one. Throws what applyEdits
// throws before `scene` changes.
EditOutcome applyEditDocument(const EditDocument& document, GaussianScene& scene, const GaussianScene* unedited,
                              const EditConsequenceSettings& settings, const EditCallbacks& callbacks);

// Differential relighting of an edited scene: the diffuse colour of every Gaussian the edit
// left in place follows the change of its irradiance (render/differential_relight.h), then
// the healed Gaussians take their relit surroundings' colour, lit where they stand
// (edit_effects/healed_lighting.h). `editedTracer` traces the edited scene as it was before
// this call; the new colours go to `relit` (the edited scene itself, or a copy of it).
// Cancellable through settings.cancel (throws RelightCancelled). Returns the line that says
// what it did and how long it took.
std::string relightEdit(const GaussianTracer& uneditedTracer, const GaussianScene& unedited,
                        const GaussianTracer& editedTracer, GaussianScene& relit, const RelightInputs& inputs,
                        const RelightSettings& settings);

}  // namespace glint
