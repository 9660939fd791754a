// Declaring the --relight flags and running differential relighting after an edit.
#include "app/relight_flags.h"

#include <chrono>
#include <cstdio>

#include "render/healed_lighting.h"

namespace glint {

void RelightFlags::add(CLI::App* cmd) {
  cmd->add_flag("--relight,!--no-relight", on_,
                "Move shadows and colour bleeding with the edited objects (on by default; --no-relight keeps every "
                "trained colour): the diffuse colour of every Gaussian the edit left in place is scaled by E_after / "
                "E_before, the change of the irradiance arriving at it, traced through the Gaussians before and after "
                "the edit (differential relighting). Gaussians the edit cannot affect keep their trained colour "
                "exactly. Costs a few seconds per 20,000 Gaussians");
  cmd->add_option("--relight-rays", settings_.rays,
                  "Rays per Gaussian for --relight: toward the edited objects (fewer for Gaussians far from them; "
                  "half of them aimed at the lights behind or beside those objects, see --relight-lights), "
                  "and as many over the hemisphere for the irradiance before the edit (a quarter of them where the "
                  "edit changes it by less than 0.5%)")
      ->check(CLI::Range(1, 65536))
      ->capture_default_str();
  cmd->add_option("--relight-filter", settings_.filterRadius,
                  "--relight averages each Gaussian's ratio with its neighbours' (facing the same way) within this "
                  "many of its largest standard deviations; 0 = no filter")
      ->check(CLI::Range(0.0f, 100.0f))
      ->capture_default_str();
  cmd->add_option("--relight-traced", settings_.tracedBudget,
                  "--relight traces rays from at most this many Gaussians within reach of the edit, spread evenly over "
                  "them, and the others take their neighbours' ratios: faster on large scenes, coarser shadows (the "
                  "viewer's preview traces 4000 at 32 rays); 0 = every one")
      ->check(CLI::Range(size_t(0), size_t(1) << 40))
      ->capture_default_str();
  cmd->add_option("--relight-bounces", settings_.path.bounces,
                  "--relight counts, in the light a ray brings to a Gaussian, the blended diffuse colour it meets and "
                  "up to this many reflected segments from there where it meets a metal or mirror (F0 >= 0.1), as the "
                  "renderer traces them: a mirror's light on the floor is its reflection. 0 = the diffuse colour alone, "
                  "the default: 1 measured better on one scene and worse on another, and costs a third more time")
      ->check(CLI::Range(0, 8))
      ->capture_default_str();
  cmd->add_option("--relight-lights", settings_.lights.factor,
                  "--relight takes as lights the Gaussians whose diffuse radiance is at least this many times the "
                  "90th percentile of the surfaces' (emitters), grouped into regions where they touch, and aims half "
                  "of the rays toward an edited object at the lights that lie behind or beside it (the light it blocks "
                  "or uncovers). 0 = no light is aimed at")
      ->check(CLI::Range(0.0f, 1000.0f))
      ->capture_default_str();
  cmd->add_option("--relight-max-ratio", settings_.maxRatio,
                  "--relight changes no diffuse colour by more than this factor, up or down")
      ->check(CLI::Range(1.0f, 1000.0f))
      ->capture_default_str();
}

RelightSettings RelightFlags::settings(const PathSettings& path) const {
  RelightSettings s = settings_;
  s.setRays(settings_.rays);  // one flag scales every ray count
  const int bounces = s.path.bounces;
  s.path = path;  // the run's reflection settings
  s.path.bounces = bounces;
  return s;
}

std::string relightAfterEdit(const GaussianTracer& beforeTracer, const GaussianScene& before,
                             const GaussianTracer& afterTracer, GaussianScene& after, const EditProvenance& provenance,
                             const HealReport& healed, const RelightSettings& settings) {
  const ChangedRegion regions[] = {changedRegionOf(before, provenance.movedOrRemoved()),
                                   changedRegionOf(after, provenance.movedOrAdded())};
  auto started = std::chrono::steady_clock::now();
  // The healed Gaussians' light factors first: tracers may keep copies of the colours that
  // relighting is about to change.
  uint64_t healedRays = 0;
  const std::vector<float> lit = healedLightFactors(afterTracer, after, healed, settings, &healedRays);
  RelightReport r = relightDiffuse(beforeTracer, afterTracer, after, provenance.unmoved(), regions, settings);
  r.rays += healedRays;
  continueHealedColours(healed, after);
  for (size_t k = 0; k < lit.size(); ++k) after.diffuse[healed.healed[k].index] *= lit[k];
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  char traced[64] = "";
  if (r.traced < r.reached) std::snprintf(traced, sizeof traced, ", %zu of them traced", r.traced);
  char text[320];
  std::snprintf(text, sizeof text,
                "relit %zu of the %zu Gaussians left in place (%zu within reach of the edit%s, %zu at the ratio's "
                "clamp; %zu light regions in the scene), %.2f M rays, %.2f s",
                r.changed, r.receivers, r.reached, traced, r.clamped, r.lights, double(r.rays) * 1e-6, seconds);
  return text;
}

}  // namespace glint
