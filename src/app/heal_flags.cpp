// Declaring the --heal flags.
#include "app/heal_flags.h"

namespace glint {

void HealFlags::add(CLI::App* cmd) {
  cmd->add_flag("--heal,!--no-heal", on_,
                "Fill the surface a moved or removed object uncovered (a floor no training view saw under it) with "
                "Gaussians continued from the surface around it: colour, normal, roughness, F0, shape; with "
                "--relight their colour follows the relit surroundings, scaled by the irradiance where they stand over "
                "the surroundings' (a floor the moved object still overhangs stays in its shadow). Heals before "
                "relighting. On by default; "
                "--no-heal leaves the surface as trained");
  cmd->add_option("--heal-below", settings_.fillBelow,
                  "--heal fills points of the uncovered surface whose coverage is below this fraction of the "
                  "surrounding surface's")
      ->check(CLI::Range(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--heal-recolour", settings_.recolourSpacings,
                  "--heal also gives the surface within this many spacings of the moved or removed Gaussians (the "
                  "support's median Gaussian width) the colour continued from around it, as no training view saw it "
                  "under a flat-based object. 0 keeps the colour it trained to (the views may have seen around an "
                  "object that met the surface at a point: there it measured up to 0.07 dB better)")
      ->check(CLI::Range(0.0f, 8.0f))
      ->capture_default_str();
  cmd->add_flag("--heal-texture,!--no-heal-texture", settings_.continueTexture,
                "--heal continues a texture that repeats around the hole (a checker, tiles) into it, copying the "
                "surface at the one offset where the texture around the hole repeats best, instead of giving the "
                "hole the surrounding mean colour; a surface whose texture does not repeat gets the mean either way. "
                "On by default");
}

}  // namespace glint
