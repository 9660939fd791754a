// Declaring the --relight flags.
#include "app/relight_flags.h"


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

}  // namespace glint
