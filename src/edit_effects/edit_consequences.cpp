// Applying an edit document with its healing and relighting, and the lines that report them.
#include "edit_effects/edit_consequences.h"

#include <chrono>
#include <cstdio>

#include "core/error.h"
#include "edit_effects/healed_lighting.h"

namespace glint {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string describeHealing(const HealReport& r, const HealSettings& settings, double seconds) {
  char recoloured[64] = "";
  if (settings.recolourSpacings > 0)
    std::snprintf(recoloured, sizeof recoloured, ", %zu around them recoloured", r.recoloured);
  char texture[160] = "";
  if (r.copied > 0)
    std::snprintf(texture, sizeof texture, "; %zu continue the texture from %.3g away (correlation %.2f)", r.copied,
                  double(length(r.textureOffset)), double(r.textureCorrelation));
  char text[480];
  std::snprintf(text, sizeof text,
                "healed the uncovered surface: %zu Gaussians added at %zu points under %zu vacated ones%s%s (%zu support "
                "Gaussians, spacing %.3g, ring coverage %.2f), %.2f s",
                r.added, r.candidates, r.vacated, recoloured, texture, r.support, double(r.spacing),
                double(r.ringCoverage), seconds);
  return text;
}

std::string describeRelighting(const RelightReport& r, double seconds) {
  char traced[64] = "";
  if (r.traced < r.reached) std::snprintf(traced, sizeof traced, ", %zu of them traced", r.traced);
  char text[320];
  std::snprintf(text, sizeof text,
                "relit %zu of the %zu Gaussians left in place (%zu within reach of the edit%s, %zu at the ratio's "
                "clamp; %zu light regions in the scene), %.2f M rays, %.2f s",
                r.changed, r.receivers, r.reached, traced, r.clamped, r.lights, double(r.rays) * 1e-6, seconds);
  return text;
}

}  // namespace

EditOutcome applyEditDocument(const EditDocument& document, GaussianScene& scene, const GaussianScene* unedited,
                              const EditConsequenceSettings& settings, const EditCallbacks& callbacks) {
  EditOutcome outcome;
  // Healing and relighting compare the scene with the one before the edit.
  const bool traced = settings.relight || settings.heal;
  std::optional<GaussianScene> copy;
  if (traced && !unedited) unedited = &copy.emplace(scene);
  GLINT_CHECK(!(settings.deferRelighting && settings.relight && copy),
              "applyEditDocument: a deferred relighting needs the unedited scene kept by the caller");
  RelightInputs inputs;
  if (traced) inputs.provenance = EditProvenance::identity(scene.size());
  outcome.report = applyEdits(document, scene, settings.maxGaussians, traced ? &inputs.provenance : nullptr);
  if (callbacks.report) callbacks.report(formatEditReport(outcome.report));

  if (settings.heal) {  // before relighting, so that the filled surface is relit with the rest
    auto started = std::chrono::steady_clock::now();
    inputs.healed = healUncovered(*unedited, scene, inputs.provenance, *settings.heal);
    outcome.healedCount = inputs.healed.added;
    if (callbacks.step) callbacks.step(describeHealing(inputs.healed, *settings.heal, secondsSince(started)));
  }
  TracedScenePointers edited{nullptr, &scene};
  if (callbacks.editedTracer) edited = callbacks.editedTracer(scene);
  if (!settings.relight) return outcome;
  GLINT_CHECK(edited.tracer && edited.scene && callbacks.uneditedTracer,
              "applyEditDocument: relighting needs both tracers");
  const bool movesSomething = !inputs.provenance.movedOrAdded().empty() || !inputs.provenance.movedOrRemoved().empty();
  if (settings.deferRelighting && movesSomething) {
    outcome.pending = std::move(inputs);
    return outcome;
  }
  const GaussianTracer& uneditedTracer = callbacks.uneditedTracer(*unedited);
  auto started = std::chrono::steady_clock::now();
  outcome.relightLine =
      relightEdit(uneditedTracer, *unedited, *edited.tracer, *edited.scene, inputs, *settings.relight);
  edited.tracer->refit();  // tracers may keep copies of the colours
  outcome.relightSeconds = secondsSince(started);
  if (callbacks.step) callbacks.step(outcome.relightLine);
  return outcome;
}

EditCallbacks printingCallbacks(const std::string& command) {
  EditCallbacks callbacks;
  callbacks.report = [](const std::string& text) { std::fputs(text.c_str(), stderr); };
  callbacks.step = [command](const std::string& line) { std::fprintf(stderr, "%s: %s\n", command.c_str(), line.c_str()); };
  return callbacks;
}

std::string relightEdit(const GaussianTracer& uneditedTracer, const GaussianScene& unedited,
                        const GaussianTracer& editedTracer, GaussianScene& relit, const RelightInputs& inputs,
                        const RelightSettings& settings) {
  const ChangedRegion regions[] = {changedRegionOf(unedited, inputs.provenance.movedOrRemoved()),
                                   changedRegionOf(relit, inputs.provenance.movedOrAdded())};
  auto started = std::chrono::steady_clock::now();
  // The healed Gaussians' light factors first: the edited tracer may keep copies of the
  // colours that relighting is about to change.
  uint64_t healedRays = 0;
  const std::vector<float> lit = healedLightFactors(editedTracer, relit, inputs.healed, settings, &healedRays);
  RelightReport r =
      relightDiffuse(uneditedTracer, editedTracer, relit, inputs.provenance.unmoved(), regions, settings);
  r.rays += healedRays;
  continueHealedColours(inputs.healed, relit);
  for (size_t k = 0; k < lit.size(); ++k) relit.diffuse[inputs.healed.healed[k].index] *= lit[k];
  return describeRelighting(r, secondsSince(started));
}

}  // namespace glint
