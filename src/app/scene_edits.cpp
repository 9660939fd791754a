// Applying --edits between loading a scene and tracing it.
#include "app/scene_edits.h"

#include <cstdio>

#include "edit/edit_file.h"
#include "edit_effects/edit_consequences.h"
#include "render/tracer_update.h"

namespace glint {

void EditsFlag::add(CLI::App* cmd) {
  cmd->add_option("--edits", path_,
                  "Edit file (docs/edit-files.md) applied to the scene right after loading it; the tracer is then "
                  "refitted or rebuilt, whichever is measured to be faster, and both costs are printed");
  cmd->add_option("--max-gaussians", maxGaussians_,
                  "Most Gaussians the --edits may leave in the scene; a file whose duplications would make more is "
                  "refused before they allocate")
      ->check(CLI::Range(size_t(1), size_t(1) << 40))
      ->capture_default_str();
  relight_.add(cmd);
  heal_.add(cmd);
}

std::unique_ptr<GaussianTracer> EditsFlag::prepareTracer(GaussianScene& scene, const TraceSettings& settings,
                                                         const PathSettings& path, const std::string& kind,
                                                         const Camera& probeCamera, double workRays,
                                                         const char* command) const {
  std::unique_ptr<GaussianTracer> tracer = makeGaussianTracer(kind);
  if (!given()) {
    tracer->build(scene, settings);
    return tracer;
  }
  EditDocument document = readEditFile(path_);  // before any work: a bad file fails fast
  tracer->build(scene, settings);
  const size_t countBefore = scene.size();
  std::fprintf(stderr, "%s: edits from %s\n", command, path_.c_str());
  // The tracer of the unedited scene is refitted or rebuilt for the edited one; relighting
  // builds another for the unedited scene.
  std::unique_ptr<GaussianTracer> unedited, edited;
  EditCallbacks callbacks = printingCallbacks(command);
  callbacks.uneditedTracer = [&](const GaussianScene& before) -> const GaussianTracer& {
    unedited = makeGaussianTracer(kind);
    unedited->build(before, settings);
    return *unedited;
  };
  callbacks.editedTracer = [&](GaussianScene& after) -> TracedScenePointers {
    UpdatedTracer updated = updateTracerAfterEdit(std::move(tracer), after, settings, kind,
                                                  countBefore == after.size(), probeCamera, workRays);
    std::fprintf(stderr, "%s: after the edits: %s\n", command, describeTracerUpdate(updated.times).c_str());
    edited = std::move(updated.tracer);
    return {edited.get(), &after};
  };
  EditConsequenceSettings consequences{maxGaussians_, heal_.chosen(), relight_.chosen(path)};
  applyEditDocument(document, scene, nullptr, consequences, callbacks);
  return edited;
}

}  // namespace glint
