// Entry point of the `glint` command line program: dispatches to subcommands and turns
// errors into one clear message and a non-zero exit.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "app/help_formatter.h"
#include "app/nearest_name.h"
#include "core/activity.h"
#include "core/cluster.h"
#include "core/error.h"
#include "tracers/compute_device.h"

namespace {

// One clear message and a non-zero exit. In an MPI job every rank may fail alike (a missing
// file); each says so with its rank, and the job ends at once, since the other ranks may be
// waiting in a collective for this one.
int fail(const std::string& message) {
  glint::cluster::reportError("glint: error: " + message);
  if (glint::cluster::distributed()) glint::cluster::abortJob(1);
  return 1;
}

// The command line, parsed and run; returns the exit status.
int runGlint(int argc, char** argv) {
  CLI::App app{
      "Glint: editable physically-based reflections in ray-traced Gaussian radiance fields.\n"
      "Run `glint COMMAND --help` for the flags of each command.",
      "glint"};
  app.require_subcommand(1);
  // Every command inherits it: help text within 100 columns, one line per command here.
  app.formatter(std::make_shared<glint::HelpFormatter>());
  // Scripts (the MPI tests) tell from it whether this build can join an MPI job.
  app.set_version_flag("--version", std::string("glint 0.1.0") +
                                        (glint::cluster::builtWithMpi() ? " (with MPI)" : " (without MPI)") + " (" +
                                        glint::cudaBuildDescription() + ")");
  glint::addSynthCommand(app);
  glint::addCaptureCommand(app);
  glint::addInfoCommand(app);
  glint::addSheetCommand(app);
  glint::addTrainCommand(app);
  glint::addRenderCommand(app);
  glint::addEvalCommand(app);
  glint::addReportCommand(app);
  glint::addExportCommand(app);
  glint::addEditCommand(app);
  glint::addViewCommand(app);
  // Bare `glint` did nothing it was asked to: the command list, and a failing status so that
  // a script that lost its arguments stops.
  if (argc == 1) {
    std::fputs(app.help().c_str(), stderr);
    return 1;
  }
  // Name an unknown command outright; CLI11 alone would only say that one is required.
  std::string names;
  std::vector<std::string> commands;
  for (const CLI::App* sub : app.get_subcommands({})) {
    names += (names.empty() ? "" : ", ") + sub->get_name();
    commands.push_back(sub->get_name());
  }
  if (argv[1][0] != '-' && std::find(commands.begin(), commands.end(), argv[1]) == commands.end()) {
    std::optional<std::string> near = glint::nearestName(argv[1], commands);
    std::fprintf(stderr, "glint: error: unknown command '%s'%s (commands: %s; see glint --help)\n", argv[1],
                 near ? ("; did you mean '" + *near + "'?").c_str() : "", names.c_str());
    return 1;
  }
  // Under an MPI launcher only the commands that share their work over the ranks run; any
  // other would run whole on every rank, each writing the same files.
  const std::vector<std::string> distributable = {"train", "render", "eval", "synth"};
  if (glint::cluster::distributed() && argv[1][0] != '-' &&
      std::find(distributable.begin(), distributable.end(), argv[1]) == distributable.end()) {
    if (glint::cluster::isRoot())
      std::fprintf(stderr, "glint: error: glint %s runs in one process; start it without mpirun or srun (train, "
                   "render, eval and synth run over MPI)\n", argv[1]);
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ExtrasError& e) {
    // An unknown flag: name the nearest one the command has (CLI11 lists the extras only).
    for (const CLI::App* sub : app.get_subcommands())
      for (const std::string& extra : sub->remaining())
        if (extra.size() > 1 && extra[0] == '-' && !std::isdigit((unsigned char)extra[1])) {
          std::fprintf(stderr, "glint %s: error: %s\n", sub->get_name().c_str(),
                       glint::unknownFlagMessage(*sub, extra).c_str());
          return 1;
        }
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // A missing or malformed flag: one line naming the command, and exit status 1 as for
    // every other error (CLI11's own codes, such as 106, mean nothing to a user).
    std::string command = "glint";
    for (const CLI::App* sub : app.get_subcommands()) command += " " + sub->get_name();
    std::fprintf(stderr, "%s: error: %s (see %s --help)\n", command.c_str(), e.what(), command.c_str());
    return 1;
  } catch (const glint::Error& e) {
    return fail(e.what());
  } catch (const std::exception& e) {
    return fail(glint::describeUnexpectedException(e));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  glint::cluster::join(&argc, &argv);
  const int code = runGlint(argc, argv);
  glint::cluster::leave();
  return code;
}
