// Applying --edits between loading a scene and tracing it.
#include "app/scene_edits.h"

#include <cstdio>

#include "edit/edit_file.h"
#include "edit/gaussian_edits.h"
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
  // Relighting traces the unedited scene too: it keeps a copy with a tracer of its own.
  GaussianScene unedited;
  EditProvenance provenance;
  const bool traced = relight_.on() || heal_.on();  // both need the unedited scene and the provenance
  if (traced) unedited = scene, provenance = EditProvenance::identity(scene.size());
  EditReport report = applyEdits(document, scene, maxGaussians_, traced ? &provenance : nullptr);
  std::fprintf(stderr, "%s: edits from %s\n%s", command, path_.c_str(), formatEditReport(report).c_str());
  HealReport healed;
  if (heal_.on()) {  // before relighting, so that the filled surface is relit with the rest
    std::string line;
    healed = healAfterEdit(unedited, scene, provenance, heal_.settings(), &line);
    std::fprintf(stderr, "%s: %s\n", command, line.c_str());
  }
  UpdatedTracer updated = updateTracerAfterEdit(std::move(tracer), scene, settings, kind,
                                                report.countBefore == scene.size(), probeCamera, workRays);
  std::fprintf(stderr, "%s: after the edits: %s\n", command, describeTracerUpdate(updated.times).c_str());
  if (relight_.on()) {
    std::unique_ptr<GaussianTracer> uneditedTracer = makeGaussianTracer(kind);
    uneditedTracer->build(unedited, settings);
    std::fprintf(stderr, "%s: %s\n", command,
                 relightAfterEdit(*uneditedTracer, unedited, *updated.tracer, scene, provenance, healed,
                                  relight_.settings(path))
                     .c_str());
    updated.tracer->refit();  // tracers may keep copies of the colours
  }
  return std::move(updated.tracer);
}

}  // namespace glint
