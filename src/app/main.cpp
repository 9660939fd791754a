// Entry point of the `glint` command line program: dispatches to subcommands and turns
// errors into one clear message and a non-zero exit.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "core/error.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Glint: editable physically-based reflections in ray-traced Gaussian radiance fields.\n"
      "Run `glint COMMAND --help` for the flags of each command."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "glint 0.1.0");
  glint::addSynthCommand(app);
  glint::addInfoCommand(app);
  glint::addSheetCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const glint::Error& e) {
    std::fprintf(stderr, "glint: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
