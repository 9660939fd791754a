// The --threads flag every computing command shares: its range, help and the limit it sets.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace glint {

// Declares --threads N on cmd, storing into *threads (0 = all cores, the default). `more`
// is appended to the help (e.g. what the thread count changes for that command).
CLI::Option* addThreadsFlag(CLI::App* cmd, int* threads, const std::string& more = "");

}  // namespace glint
