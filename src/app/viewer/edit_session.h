// The viewer's edit stack: an EditDocument whose operations the page appends one at a
// time. Undo pops the last operation onto a redo list and redo pushes it back; either way
// the document is re-applied to a pristine copy of the scene, so what is shown is always
// exactly what `glint edit` would bake from the saved file. The tracer is then refitted or
// rebuilt, whichever render/tracer_update.h measures to be cheaper, as `glint render
// --edits` does.
#pragma once

#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/viewer/progressive_renderer.h"
#include "edit/edit_document.h"
#include "edit/heal_uncovered.h"
#include "edit_effects/edit_consequences.h"
#include "raytrace/trace_settings.h"
#include "render/differential_relight.h"
#include "render/tracer_update.h"
#include "scene/camera.h"

namespace glint {

// What choosing between refit and rebuild after an edit needs from the viewer.
struct TracerUpdateContext {
  Camera probeCamera;   // the camera shown: its primary rays probe both structures
  double workRays = 0;  // rays the viewer expects to trace on the edited scene
  // Stops every use of the shown scene (the render thread's), so that its tracer can be
  // refitted in place; called only when the Gaussian count allows a refit.
  std::function<void()> releaseShown;
};

class EditSession {
 public:
  // maxGaussians: the most Gaussians an edit may leave (gaussian_edits.h). With relight,
  // every edit is followed by differential relighting (edit_effects/edit_consequences.h) against the
  // pristine scene, whose tracer is built at the first edit. With heal, the surface an edit
  // uncovered is filled first (edit/heal_uncovered.h). With deferRelighting, apply, undo
  // and redo show an edit that moves, adds or removes Gaussians at once without relighting
  // it, and relight() then relights it: the viewer shows a moved object within milliseconds
  // and its shadows seconds later.
  EditSession(GaussianScene pristine, const TraceSettings& trace, size_t maxGaussians,
              std::optional<RelightSettings> relight = std::nullopt, std::optional<HealSettings> heal = std::nullopt,
              bool deferRelighting = false);

  std::shared_ptr<const TracedScene> current() const;

  // {"selection": S, "operation": O}: S a selection as in an edit file, O an operation as in
  // an edit file without its "selection" field. Returns the edited scene; throws
  // RequestError 400 for a malformed request (nothing changes, releaseShown is not called)
  // and 413 for an edit that would exceed maxGaussians (nothing changes).
  std::shared_ptr<const TracedScene> apply(const nlohmann::json& request, const TracerUpdateContext& context);
  // Throw RequestError 409 when there is nothing to undo or redo.
  std::shared_ptr<const TracedScene> undo(const TracerUpdateContext& context);
  std::shared_ptr<const TracedScene> redo(const TracerUpdateContext& context);
  // Relights the last edit when its relighting was deferred, and returns the relit scene
  // (the current one when nothing waits, or when an edit request arriving meanwhile cancelled
  // it). The colours are computed on a copy without the session's lock: the renderer keeps
  // tracing the shown scene, and status, previews, saves and edits answer meanwhile (an edit
  // goes ahead at once and makes the relighting stale). They replace the shown colours
  // (with a refit) when the renderer has let go of it (releaseShown), else a new tracer is
  // built.
  std::shared_ptr<const TracedScene> relight(const TracerUpdateContext& context);
  // A first look at the deferred relighting: the last edit relit from kPreviewTraced
  // Gaussians spread over those within its reach (RelightSettings::tracedBudget) with
  // kPreviewRays rays each (fewer when the flags ask for fewer), shown over a new tracer, both
  // made without the session's lock. The relighting stays pending: relight() then computes
  // the full one from the unrelit colours, exactly as without a preview. Returns the current
  // scene when nothing waits, the preview is shown already, or an edit came meanwhile.
  std::shared_ptr<const TracedScene> relightPreview();
  // On builtin:spheres, 4,000 Gaussians at 32 rays left a move's final and diffuse drops at
  // 1.36 and 3.54 dB, against 1.69 and 4.20 for 2,000 at 64 and 1.65 and 4.06 for 8,000 at
  // 16, for the same 0.25 M rays (README, "Edits that move shadows").
  static constexpr size_t kPreviewTraced = 4000;
  static constexpr int kPreviewRays = 32;
  // The preview counts the diffuse colour a ray meets alone (RelightSettings::path.bounces
  // 0) even when the flags ask for reflected segments: at 32 rays a mirror's reflected
  // segment adds more noise than light. With it the move's final and diffuse drops were
  // 1.12 and 3.20 dB, without it 0.96 and 2.79, with 0.25 M rays instead of 0.33 M.
  static constexpr int kPreviewBounces = 0;

  // {"operations", "redoable", "gaussians"} and, after an edit, "tracer_update": {"action":
  // "refit"|"rebuild", "refit_possible", "refit_ms", "rebuild_ms", "refit_probe_ms",
  // "rebuild_probe_ms", "probe_rays", "work_rays", and "no_refit" (why) when no refit was
  // possible} of the last tracer update, and with relighting "relight": what it did and its
  // time in "relight_ms", and "relight_pending": true while a deferred relighting waits;
  // "relight_preview": true while a preview of it is shown; with healing "healed": the
  // Gaussians it added.
  nlohmann::json status() const;
  // {"selection": S, "attribute": "roughness"|"f0"|"diffuse"|"metalness", "bins": 1..256}
  // -> {"count", "total", "attribute", "histogram": [...], "range": [lo, hi]}: how many
  // Gaussians of the current scene S holds and the histogram of the attribute over them.
  nlohmann::json preview(const nlohmann::json& request) const;
  EditDocument document() const;
  // Writes the current scene as a binary PLY; returns its Gaussian count. Under the session's
  // lock, like preview, so an edit cannot overwrite the scene while it is read.
  size_t exportPly(const std::filesystem::path& file) const;

  static constexpr size_t kMaxOperations = 1000;

 private:
  struct Step {
    std::string selectionName;
    Selection selection;
    Operation operation;
  };
  // The edit document of steps_.
  EditDocument documentOfSteps() const;
  // Applies steps_ to a copy of the pristine scene, then refits the shown tracer in place or
  // builds a new one (mutex_ held). Throws Error when an operation cannot apply; nothing
  // shown has changed then.
  void update(const TracerUpdateContext& context);
  // The shown tracer, taken for an update of the shown scene in place, when nobody else holds
  // the scene once the renderer has let go of it (context.releaseShown); else null.
  std::unique_ptr<GaussianTracer> takeShownTracer(const TracerUpdateContext& context);
  // Makes shownScene_, traced by `tracer`, the current scene.
  void show(std::unique_ptr<GaussianTracer> tracer);
  // The pristine scene's tracer, built at the first call (mutex_ held); read-only after.
  const GaussianTracer& pristineTracer();

  mutable std::mutex mutex_;
  std::shared_ptr<const GaussianScene> pristine_;
  TraceSettings trace_;
  size_t maxGaussians_;
  std::vector<Step> steps_;
  std::vector<Step> redo_;
  // The shown scene, a copy of the pristine one that edits overwrite in place so that its
  // tracer (which references the scene object) can be refitted.
  std::shared_ptr<GaussianScene> shownScene_;
  std::shared_ptr<TracedScene> current_;  // over shownScene_
  std::optional<TracerUpdateTimes> lastUpdate_;
  std::string noRefitReason_;  // of the last update, when it could not refit
  std::optional<RelightSettings> relight_;
  std::unique_ptr<GaussianTracer> pristineTracer_;  // built at the first relit edit
  std::string lastRelight_;                          // what the last relighting did
  // What a deferred relighting needs of the last update: which Gaussians the edit moved,
  // added or removed, and what healing added (its colours follow the relit surroundings).
  struct PendingRelight {
    RelightInputs inputs;
    // The edited scene with its colours not yet relit, while a preview is shown instead.
    std::shared_ptr<const TracedScene> unrelit;
  };
  std::optional<PendingRelight> pending_;
  // The last update's flag, set by the next edit request (lockForEdit): its deferred
  // relightings stop (RelightSettings::cancel), and one that finished meanwhile is not
  // shown, since the edit makes them stale. Each update makes a new one.
  std::shared_ptr<std::atomic<bool>> relightCancel_ = std::make_shared<std::atomic<bool>>(false);
  // The session's lock for an edit; cancels the deferred relightings still running.
  std::unique_lock<std::mutex> lockForEdit();
  // A deferred relighting: what it traced, and the colours and report it made.
  struct DeferredRelight {
    std::shared_ptr<std::atomic<bool>> stale;  // its edit's flag (relightCancel_)
    std::shared_ptr<const TracedScene> unrelit;
    RelightInputs inputs;
    std::chrono::steady_clock::time_point started;
    std::string line;      // what relightEdit did
    GaussianScene relit;   // the unrelit scene with its relit colours
  };
  // Relights the pending edit's unrelit scene with `settings`, tracing with `lock` released;
  // returns with it held. Nothing when nothing waits (or, for a preview, one is shown
  // already), when a newer edit cancelled it, or when an update or the full relighting came
  // while it traced.
  std::optional<DeferredRelight> startDeferred(std::unique_lock<std::mutex>& lock, const RelightSettings& settings,
                                               bool preview);
  double lastRelightSeconds_ = 0;
  std::optional<HealSettings> heal_;
  size_t lastHealed_ = 0;  // Gaussians the last healing added
  bool deferRelighting_ = false;
  int nextSelectionId_ = 0;
};

}  // namespace glint
