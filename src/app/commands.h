// The `glint` subcommands. Each registers its flags on the CLI11 app and runs when chosen.
#pragma once

#include <CLI/CLI.hpp>

namespace glint {

void addSynthCommand(CLI::App& app);
void addInfoCommand(CLI::App& app);
void addCaptureCommand(CLI::App& app);
void addSheetCommand(CLI::App& app);
void addExportCommand(CLI::App& app);
void addRenderCommand(CLI::App& app);
void addTrainCommand(CLI::App& app);
void addEvalCommand(CLI::App& app);
void addReportCommand(CLI::App& app);
void addEditCommand(CLI::App& app);
void addViewCommand(CLI::App& app);

}  // namespace glint
