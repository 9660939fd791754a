// Refusing to replace an existing output file without --force.
#include "app/output_file.h"

#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"

namespace glint {

void refuseExistingOutput(const std::string& output, bool force) {
  checkReplaceableOutput(output);  // a device, folder or link is refused even with --force
  if (std::filesystem::exists(output) && !force)
    throw Error(output, "already exists; choose another -o file or pass --force to replace it");
}

}  // namespace glint
