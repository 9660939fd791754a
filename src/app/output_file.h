// The rule of the commands that write one output file (edit, export): an existing file is
// replaced only with --force.
#pragma once

#include <string>

namespace glint {

// Throws Error naming `output` when it exists and `force` is false, or when it is not a
// regular file (checkReplaceableOutput), whatever `force` says.
void refuseExistingOutput(const std::string& output, bool force);

}  // namespace glint
