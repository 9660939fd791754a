// Entry point of the `glint` command line program: dispatches to subcommands and turns
// errors into one clear message and a non-zero exit.
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "core/activity.h"
#include "core/error.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Glint: editable physically-based reflections in ray-traced Gaussian radiance fields.\n"
      "Run `glint COMMAND --help` for the flags of each command.",
      "glint"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "glint 0.1.0");
  glint::addSynthCommand(app);
  glint::addInfoCommand(app);
  glint::addSheetCommand(app);
  glint::addTrainCommand(app);
  glint::addRenderCommand(app);
  glint::addEvalCommand(app);
  glint::addReportCommand(app);
  glint::addExportCommand(app);
  glint::addEditCommand(app);
  glint::addViewCommand(app);
  if (argc == 1) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  }
  // Name an unknown command outright; CLI11 alone would only say that one is required.
  std::string names;
  bool known = false;
  for (const CLI::App* sub : app.get_subcommands({})) {
    names += (names.empty() ? "" : ", ") + sub->get_name();
    known = known || sub->get_name() == argv[1];
  }
  if (argv[1][0] != '-' && !known) {
    std::fprintf(stderr, "glint: error: unknown command '%s' (commands: %s; see glint --help)\n", argv[1], names.c_str());
    return 1;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const glint::Error& e) {
    std::fprintf(stderr, "glint: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint: error: %s\n", glint::describeUnexpectedException(e).c_str());
    return 1;
  }
  return 0;
}
