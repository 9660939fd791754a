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
}

std::unique_ptr<GaussianTracer> EditsFlag::prepareTracer(GaussianScene& scene, const TraceSettings& settings,
                                                         const std::string& kind, const Camera& probeCamera,
                                                         double workRays, const char* command) const {
  std::unique_ptr<GaussianTracer> tracer = makeGaussianTracer(kind);
  if (!given()) {
    tracer->build(scene, settings);
    return tracer;
  }
  EditDocument document = readEditFile(path_);  // before any work: a bad file fails fast
  tracer->build(scene, settings);
  EditReport report = applyEdits(document, scene, maxGaussians_);
  std::fprintf(stderr, "%s: edits from %s\n%s", command, path_.c_str(), formatEditReport(report).c_str());
  UpdatedTracer updated =
      updateTracerAfterEdit(std::move(tracer), scene, settings, kind, !report.countChanged(), probeCamera, workRays);
  std::fprintf(stderr, "%s: after the edits: %s\n", command, describeTracerUpdate(updated.times).c_str());
  return std::move(updated.tracer);
}

}  // namespace glint
