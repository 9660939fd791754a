// `glint edit SCENE.ply|RUN EDITS.json -o OUT.ply`: bakes an edit file into a new Gaussian
// scene (Glint's PLY layout), printing how many Gaussians each operation changed.
#include <cstdio>
#include <memory>
#include <string>

#include "app/commands.h"
#include "app/output_file.h"
#include "app/heal_flags.h"
#include "app/relight_flags.h"
#include "app/scene_source.h"
#include "app/thread_flag.h"
#include "app/trace_flags.h"
#include "core/error.h"
#include "core/parallel.h"
#include "edit/edit_file.h"
#include "edit/gaussian_edits.h"
#include "edit_effects/edit_consequences.h"
#include "scene/gaussian_ply.h"

namespace glint {

namespace {

struct EditOptions {
  std::string scene;
  std::string inputLayout = "auto";
  std::string edits;
  std::string output;
  bool force = false;
  size_t maxGaussians = kDefaultMaxGaussians;
  int threads = 0;
  std::string device = "auto";  // where relighting traces
  RelightFlags relight;
  HealFlags heal;
};

void runEdit(const EditOptions& o) {
  ThreadLimit threads(o.threads);
  refuseExistingOutput(o.output, o.force);
  EditDocument document = readEditFile(o.edits);  // validate before loading a large scene
  SceneSource source = loadSceneSource(o.scene, parseInputLayout(o.inputLayout));
  std::fprintf(stderr, "glint edit: %s with %s\n", o.scene.c_str(), o.edits.c_str());
  // Relighting traces both scenes as the scene renders (the run's tracer settings), on the
  // GPU when there is one.
  const std::string kind =
      o.relight.on() ? resolveTracerForDevice(o.device, "fast", /*tracerGiven=*/false, "glint edit") : "fast";
  std::unique_ptr<GaussianTracer> unedited, edited;
  EditCallbacks callbacks = printingCallbacks("glint edit");
  callbacks.uneditedTracer = [&](const GaussianScene& scene) -> const GaussianTracer& {
    unedited = makeGaussianTracer(kind);
    unedited->build(scene, source.settings.trace);
    return *unedited;
  };
  if (o.relight.on())
    callbacks.editedTracer = [&](GaussianScene& scene) -> TracedScenePointers {
      edited = makeGaussianTracer(kind);
      edited->build(scene, source.settings.trace);
      return {edited.get(), &scene};
    };
  EditConsequenceSettings settings{o.maxGaussians, o.heal.chosen(), o.relight.chosen(source.settings.path())};
  applyEditDocument(document, source.scene, nullptr, settings, callbacks);
  writeGaussianPly(o.output, source.scene);
  std::fprintf(stderr, "glint edit: wrote %s (%zu Gaussians)\n", o.output.c_str(), source.scene.size());
}

}  // namespace

void addEditCommand(CLI::App& app) {
  auto o = std::make_shared<EditOptions>();
  CLI::App* cmd = app.add_subcommand(
      "edit",
      "Apply an edit file (named selections and an ordered list of operations: translate, rotate, scale, "
      "duplicate, delete, roughness, f0, diffuse; see docs/edit-files.md) to a Gaussian scene and write the "
      "edited scene as a new .ply in Glint's layout. Prints how many Gaussians each operation selected and warns "
      "about selections that hold none.");
  cmd->add_option("scene", o->scene, "Gaussian scene .ply, or a training run folder (its scene.ply)")->required();
  addInputLayoutFlag(*cmd, o->inputLayout);
  cmd->add_option("edits", o->edits, "Edit file (JSON, \"glint_edits\": 1)")->required();
  cmd->add_option("-o,--output", o->output, "Output .ply file (written atomically)")->required();
  cmd->add_flag("--force", o->force, "Replace the output file if it exists");
  cmd->add_option("--max-gaussians", o->maxGaussians,
                  "Most Gaussians the edits may leave in the scene; a file whose duplications would make more is "
                  "refused before they allocate")
      ->check(CLI::Range(size_t(1), size_t(1) << 40))
      ->capture_default_str();
  addThreadsFlag(cmd, &o->threads);
  addDeviceFlag(cmd, &o->device);
  o->relight.add(cmd);
  o->heal.add(cmd);
  cmd->callback([o]() { runEdit(*o); });
}

}  // namespace glint
